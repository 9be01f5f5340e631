//! Build-script helpers (feature `build`): a layout file's includes written into `OUT_DIR`,
//! regenerated when the file changes.
//!
//! ```no_run
//! // build.rs, with `gbuffer = { path = "../gbuffer/gbuffer", features = ["build"] }` (this
//! // repository beside the crate; nothing is on crates.io yet) in [build-dependencies]
//! fn main() {
//!     if let Err(error) = gbuffer::build::generate(["layouts/mobile_metallic.toml"]) {
//!         eprintln!("{error}");
//!         std::process::exit(1);
//!     }
//! }
//! ```
//!
//! and in the crate, `include!(concat!(env!("OUT_DIR"), "/mobile_metallic.rs"))` for the
//! Rust mirror, `include_str!(concat!(env!("OUT_DIR"), "/mobile_metallic.wgsl"))` for the
//! WGSL, and likewise the GLSL includes. [`Builder`] chooses the outputs and the folder.

// The example is a build script, whose `fn main` is the point.
#![allow(clippy::needless_doctest_main)]

use std::path::{Path, PathBuf};

pub use gbuffer_build::output::Output;
pub use gbuffer_build::{BuildError, Builder};

/// Writes every output of each layout file into `OUT_DIR` and tells cargo to rerun the build
/// script when one of the files changes. Returns the paths written (or already up to date).
pub fn generate<P: AsRef<Path>>(
    layout_files: impl IntoIterator<Item = P>,
) -> Result<Vec<PathBuf>, BuildError> {
    layout_files
        .into_iter()
        .fold(Builder::new(), |builder, path| builder.layout(path))
        .build()
}
