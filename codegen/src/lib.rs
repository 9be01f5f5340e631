//! The G-buffer layout model and everything generated from it.
//!
//! One implementation serves every front end: the `#[derive(GBufferLayout)]` macro and the
//! `codegen` command both build a [`Layout`], [`Layout::check`] it, and hand it to the
//! emitters. The pipeline, front to back:
//!
//! - [`format`](mod@format): the twelve pixel local storage formats and their channels;
//! - [`encoding`](mod@encoding): bit fields and their encodings;
//! - [`layout`]: fields, types, the words they fill, the bit budget and its checks;
//! - [`convert`]: the bit-exact conversions (the CPU side of the generated WGSL);
//! - [`emit`]: WGSL and Rust mirror emitters;
//! - [`report`]: the bit report and the WebGPU render-target cost;
//! - with the `tools` feature (on by default): `layout_file` (layouts in TOML), `output` (the
//!   files the tool writes, atomically and only when changed), the GLSL and
//!   Rust-source emitters, `Builder` for build scripts (the `gbuffer codegen` command runs them).

#![warn(missing_docs)]

#[cfg(feature = "tools")]
mod builder;
pub mod convert;
pub mod emit;
pub mod encoding;
pub mod format;
pub mod layout;
#[cfg(feature = "tools")]
pub mod layout_file;
pub mod naming;
#[cfg(feature = "tools")]
pub mod output;
pub mod report;

#[cfg(feature = "tools")]
pub use builder::{BuildError, Builder};

pub use encoding::{BitField, Encoding, RgbmRange};
pub use format::{Channel, ChannelEncoding, Format, ScalarKind};
pub use layout::{
    Conversions, Diagnostic, Field, FieldType, Layout, Member, Storage, Subject, Word,
    DEFAULT_BUDGET,
};
pub use report::Report;
