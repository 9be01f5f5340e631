//! The build tooling over the emitters of `gbuffer-codegen`: which files a layout gives and
//! writing them ([`output`]: every file atomically, an unchanged one left alone), a run's files
//! all or none ([`staging`]), and [`Builder`], which reads layout files (through
//! `gbuffer-layout-file`) and writes their outputs into `OUT_DIR` from a build script. The
//! `gbuffer codegen` command and the facade's `gbuffer::build` (feature `build`) run them; a
//! library that only compiles layouts (`gbuffer_codegen::CompiledLayout`) builds none of it.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

mod builder;
pub mod output;
pub mod staging;

pub use builder::{BuildError, Builder};
