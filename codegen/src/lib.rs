//! Everything generated from a G-buffer layout: the WGSL, GLSL and Rust emitters, over the
//! layout model of [`gbuffer_core`].
//!
//! One implementation serves every front end: the `#[derive(GBufferLayout)]` macro's attribute
//! parser (`gbuffer-macros`) and the layout-file reader (`gbuffer-layout-file`) both make a
//! [`Layout`](gbuffer_core::Layout) and [`check`](gbuffer_core::Layout::check) it, and the
//! emitters take it from there:
//!
//! - [`emit`]: WGSL and Rust mirror emitters;
//! - with the `tools` feature (on by default): `CompiledLayout` (a layout's WGSL, naga's
//!   module and the printed GLSL, built once and handed to every include), `wgsl_module`, the
//!   one front door for WGSL (naga's parse and validation, used by every package that takes
//!   WGSL in), `glsl_stage` (a whole stage of a validated module as GLSL by naga's writer),
//!   `output` (the files the tool writes, atomically and only when changed), `staging` (a
//!   run's files, all or none), the GLSL and Rust-source emitters, `Builder` for build scripts
//!   (the `gbuffer codegen` command runs them), which reads layout files through
//!   `gbuffer-layout-file`.
//!
//! The model is named by one path, `gbuffer_core` (users of the facade: `gbuffer::layout`);
//! this crate re-exports none of it.
//!
//! # Feature flags
//!
//! - `tools` (on by default): the compile step, the GLSL and Rust-source emitters, the files
//!   the tools write and the build-script API (naga, layout files and prettyplease come with
//!   it). The derive builds without it.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

// On docs.rs (`--cfg docsrs`, Cargo.toml's [package.metadata.docs.rs]), each feature-gated item
// says which feature it needs.
#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(feature = "tools")]
mod builder;
#[cfg(feature = "tools")]
mod compiled;
pub mod emit;
#[cfg(feature = "tools")]
pub mod glsl_stage;
#[cfg(feature = "tools")]
pub mod output;
#[cfg(feature = "tools")]
pub mod staging;
#[cfg(feature = "tools")]
pub mod wgsl_module;

#[cfg(feature = "tools")]
pub use builder::{BuildError, Builder};
#[cfg(feature = "tools")]
pub use compiled::CompiledLayout;
