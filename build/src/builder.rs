//! The build-script API: reads layout files, writes their includes into `OUT_DIR` and tells
//! cargo to rerun when a layout changes.
//!
//! ```text
//! // build.rs
//! fn main() {
//!     if let Err(error) = gbuffer_build::Builder::new().layout("layouts/mobile_metallic.toml").build() {
//!         eprintln!("{error}");
//!         std::process::exit(1);
//!     }
//! }
//! // src/lib.rs
//! include!(concat!(env!("OUT_DIR"), "/mobile_metallic.rs"));
//! ```
//!
//! `examples/build-script` is a crate that does this.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::output::{generate, write_if_changed, Output};
use gbuffer_layout_file::{read_layout_file, FileError};

/// Generates the includes of layout files from a build script.
///
/// A layout file (see [`gbuffer_layout_file`] for its keys) and the WGSL and bit
/// report of it, written into a folder of the caller's choosing rather than `OUT_DIR`:
///
/// ```
/// use gbuffer_build::output::Output;
/// use gbuffer_build::Builder;
///
/// let folder = std::env::temp_dir().join(format!("gbuffer-builder-{}", std::process::id()));
/// std::fs::create_dir_all(&folder).unwrap();
/// let layout = folder.join("small.toml");
/// std::fs::write(&layout, r#"
/// name = "Small"
/// budget = 64
///
/// [[fields]]
/// name = "normal"
/// bits = 24
/// encoding = "octahedral"
/// type = "Vec3"
///
/// [[fields]]
/// name = "albedo"
/// format = "rgba8"
/// type = "Vec4"
/// "#).unwrap();
///
/// let written = Builder::new()
///     .layout(&layout)
///     .out_dir(&folder)
///     .outputs(&[Output::Wgsl, Output::Report])
///     .build()
///     .unwrap();
/// let names: Vec<_> = written.iter().map(|path| path.file_name().unwrap().to_owned()).collect();
/// assert_eq!(names, ["small.wgsl", "small.report.txt"]);
/// let wgsl = std::fs::read_to_string(folder.join("small.wgsl")).unwrap();
/// assert!(wgsl.contains("fn pack_small("));
///
/// // A mistake names the file, line and column, and nothing is written for it.
/// std::fs::write(&layout, "name = \"Small\"\nbudget = 100\nfields = []\n").unwrap();
/// let error = Builder::new().layout(&layout).out_dir(&folder).build().unwrap_err();
/// assert!(error.to_string().contains("small.toml:2:10: error: budget must be a positive multiple of 32"));
/// # std::fs::remove_dir_all(&folder).unwrap();
/// ```
#[derive(Clone, Debug)]
pub struct Builder {
    layouts: Vec<PathBuf>,
    out_dir: Option<PathBuf>,
    outputs: Vec<Output>,
}

impl Default for Builder {
    fn default() -> Self {
        Builder::new()
    }
}

/// Why a build step failed.
#[derive(Debug)]
pub enum BuildError {
    /// A layout file was unreadable or invalid.
    Layout(FileError),
    /// No output folder: neither `out_dir` nor the `OUT_DIR` variable cargo sets.
    NoOutDir,
    /// Writing an output failed.
    Write {
        /// The file that could not be written.
        path: PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// naga failed to translate the WGSL (a bug in this crate).
    Translation(gbuffer_codegen::TranslationError),
}

impl fmt::Display for BuildError {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::Layout(error) => write!(out, "{error}"),
            BuildError::NoOutDir => write!(
                out,
                "no output folder: call `out_dir` or run from a build script (cargo sets OUT_DIR)"
            ),
            BuildError::Write { path, error } => {
                write!(out, "{}: cannot write: {error}", path.display())
            }
            BuildError::Translation(error) => write!(out, "{error}"),
        }
    }
}

impl std::error::Error for BuildError {}

impl Builder {
    /// A builder for every output, into `OUT_DIR`.
    pub fn new() -> Self {
        Builder {
            layouts: Vec::new(),
            out_dir: None,
            outputs: Output::ALL.to_vec(),
        }
    }

    /// Adds a layout file.
    pub fn layout(mut self, path: impl AsRef<Path>) -> Self {
        self.layouts.push(path.as_ref().to_path_buf());
        self
    }

    /// Writes into `folder` instead of `OUT_DIR`.
    pub fn out_dir(mut self, folder: impl AsRef<Path>) -> Self {
        self.out_dir = Some(folder.as_ref().to_path_buf());
        self
    }

    /// Chooses the outputs (all by default).
    pub fn outputs(mut self, outputs: &[Output]) -> Self {
        self.outputs = outputs.to_vec();
        self
    }

    /// Generates every layout's outputs; prints `cargo:rerun-if-changed` for each layout file.
    /// Returns the paths of the files, written or already up to date.
    pub fn build(self) -> Result<Vec<PathBuf>, BuildError> {
        let folder = match self.out_dir {
            Some(folder) => folder,
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or(BuildError::NoOutDir)?,
        };
        let mut paths = Vec::new();
        for layout_path in &self.layouts {
            println!("cargo:rerun-if-changed={}", layout_path.display());
            let file = read_layout_file(layout_path).map_err(BuildError::Layout)?;
            for file in generate(&file.layout, file.conversions, &self.outputs)
                .map_err(BuildError::Translation)?
            {
                let path = folder.join(&file.name);
                write_if_changed(&path, &file.contents).map_err(|error| BuildError::Write {
                    path: path.clone(),
                    error,
                })?;
                paths.push(path);
            }
        }
        Ok(paths)
    }
}
