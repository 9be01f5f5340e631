//! The G-buffer layout model, and all that derived code calls at run time.
//!
//! Every front end (the `#[derive(GBufferLayout)]` macro, layout files, the solver) builds a
//! [`Layout`] and [`Layout::check`]s it; the emitters of `gbuffer-codegen` write its WGSL, GLSL
//! and Rust; the derived `pack`/`unpack` call the conversions here. The model, bottom up:
//!
//! - [`format`](mod@format): the twelve pixel local storage formats and their channels;
//! - [`encoding`](mod@encoding): bit fields and their encodings;
//! - [`layout`]: fields, types, the words they fill, the bit budget and its checks;
//! - [`naming`]: the identifiers the emitters derive from the layout's names;
//! - [`convert`]: the bit-exact conversions (the CPU side of the generated WGSL);
//! - [`report`]: the bit report and the WebGPU render-target cost.
//!
//! It depends on nothing: a user's runtime links no proc-macro2, quote or syn.

pub mod convert;
pub mod encoding;
pub mod format;
pub mod layout;
pub mod naming;
pub mod report;

pub use encoding::{BitField, Encoding, RgbmRange};
pub use format::{
    Channel, ChannelEncoding, Format, FormatRow, GlFormat, PackedTarget, ScalarKind, TargetFormat,
    VulkanFormat, WebGpuTarget,
};
pub use layout::{
    Conversions, Diagnostic, Field, FieldType, Layout, Member, Storage, Subject, Word,
    DEFAULT_BUDGET,
};
pub use report::Report;
