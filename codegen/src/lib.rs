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
//!   module and the printed GLSL, built once and handed to every include), the GLSL and
//!   Rust-source emitters. WGSL comes in and GLSL goes out through `gbuffer-translate`, which
//!   every package that translates a shader shares.
//!
//! Writing the files (`gbuffer codegen`'s, a build script's) is `gbuffer-build`'s, over these
//! emitters: a library that compiles layouts builds none of it.
//!
//! The model is named by one path, `gbuffer_core` (users of the facade: `gbuffer::layout`);
//! this crate re-exports none of it.
//!
//! # Feature flags
//!
//! - `tools` (on by default): the compile step and the GLSL and Rust-source emitters (naga
//!   and prettyplease come with it). The derive builds without it.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

// On docs.rs (`--cfg docsrs`, Cargo.toml's [package.metadata.docs.rs]), each feature-gated item
// says which feature it needs.
#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(feature = "tools")]
mod compiled;
pub mod emit;
mod lowered;

#[cfg(feature = "tools")]
pub use compiled::{CompiledLayout, GlslNames, Translation, TranslationError};
pub use lowered::LoweredLayout;
