//! Everything generated from a G-buffer layout: the WGSL, GLSL and Rust emitters, over the
//! layout model of [`gbuffer_core`].
//!
//! One implementation serves every front end: the `#[derive(GBufferLayout)]` macro and the
//! `codegen` command both build a [`Layout`](gbuffer_core::Layout),
//! [`check`](gbuffer_core::Layout::check) it, and hand it to the emitters:
//!
//! - [`emit`]: WGSL and Rust mirror emitters;
//! - with the `tools` feature (on by default): `layout_file` (layouts in TOML, read through
//!   `gbuffer-files`), `output` (the
//!   files the tool writes, atomically and only when changed), `staging` (a run's files, all
//!   or none), the GLSL and
//!   Rust-source emitters, `Builder` for build scripts (the `gbuffer codegen` command runs them).
//!
//! The model is named by one path, `gbuffer_core` (users of the facade: `gbuffer::layout`);
//! this crate re-exports none of it.

#[cfg(feature = "tools")]
mod builder;
pub mod emit;
#[cfg(feature = "tools")]
pub mod layout_file;
#[cfg(feature = "tools")]
pub mod output;
#[cfg(feature = "tools")]
pub mod staging;

#[cfg(feature = "tools")]
pub use builder::{BuildError, Builder};
