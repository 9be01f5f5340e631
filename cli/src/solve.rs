//! `gbuffer solve`: scene descriptions to layouts.
//!
//! Prints each scene's solved layout with the encoding and predicted error of every stored
//! quantity. With `--out`, writes what a hand-written layout gets from `codegen` (WGSL, GLSL
//! ES includes, Rust mirror, bit report) plus `<name>.scene.wgsl` (the values struct, encode
//! and decode), `<name>.lighting.wgsl` (the specialised lighting function), and the solved
//! layout as a layout file (`<name>.layout.toml`) and as derive source (`<name>.derive.rs`).
//!
//! Exit status: 0 on success, 1 when a scene is unreadable or cannot be solved or an output
//! cannot be written (nothing is written then), 2 on a usage error (bad arguments).

use std::path::PathBuf;
use std::process::ExitCode;

use gbuffer_build::output::{generate, GeneratedFile, Output};
use gbuffer_core::Conversions;
use gbuffer_layout_file::FileError;
use gbuffer_solver::file::read_and_solve;
use gbuffer_solver::lighting::{lighting_wgsl, Forms};

use crate::output;

/// Solves scene descriptions (TOML): the smallest G-buffer layout that meets their precision,
/// and a lighting shader with only the terms they use.
///
/// Prints each scene's layout with the encoding and predicted error of every stored quantity.
/// With `--out`, writes what `gbuffer codegen` writes for a layout file, plus
/// `<name>.scene.wgsl`, `<name>.lighting.wgsl`, and the layout as `<name>.layout.toml` and
/// `<name>.derive.rs`.
///
/// A run writes all its files or none; two scenes that would write one file are an error.
///
/// Exit status: 0 on success, 1 when a scene is unreadable or cannot be solved or an output
/// cannot be written (nothing is written then), 2 on a usage error (bad arguments).
#[derive(clap::Args, Debug)]
pub struct Arguments {
    /// Scene description files.
    #[arg(required = true, value_name = "SCENE.toml")]
    scenes: Vec<PathBuf>,
    /// Folder to write the generated files into (created if missing).
    #[arg(long, short, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Generate the mobile forms of the lighting (D_Approx, EnvBRDFApprox) instead of GGX and
    /// the split-sum LUT.
    #[arg(long)]
    mobile: bool,
}

pub fn run(arguments: Arguments) -> ExitCode {
    let forms = if arguments.mobile {
        Forms::MOBILE
    } else {
        Forms::ACCURATE
    };
    // Every scene is solved before anything is printed or written: one that fails fails the
    // run, and nothing is written.
    let mut failed = false;
    let mut summaries = String::new();
    let mut files = Vec::new();
    for path in &arguments.scenes {
        let solution = match read_and_solve(path) {
            Ok(solution) => solution,
            Err(error @ FileError::Io { .. }) => {
                say!("gbuffer solve: {error}");
                failed = true;
                continue;
            }
            Err(error) => {
                say!("{error}");
                failed = true;
                continue;
            }
        };
        summaries.push_str(&format!("{solution}\n"));
        if arguments.out.is_none() {
            continue;
        }
        let source = format!("{} (scene {})", path.display(), solution.layout.name);
        let symbols = solution.layout.symbols();
        let mut generated = match generate(&solution.layout, Conversions::Exact, &Output::ALL) {
            Ok(generated) => generated,
            Err(error) => {
                say!("gbuffer solve: {}: {error}", path.display());
                failed = true;
                continue;
            }
        };
        for (suffix, contents) in [
            ("scene.wgsl", gbuffer_solver::texel::texel_wgsl(&solution)),
            ("lighting.wgsl", lighting_wgsl(&solution, forms)),
            ("layout.toml", solution.layout_file()),
            ("derive.rs", solution.derive_source()),
        ] {
            generated.push(GeneratedFile {
                name: symbols.file(suffix),
                contents,
            });
        }
        files.extend(generated.into_iter().map(|file| (source.clone(), file)));
    }
    if failed {
        return ExitCode::FAILURE;
    }
    let Some(folder) = &arguments.out else {
        return match output::print(&summaries) {
            Ok(()) => ExitCode::SUCCESS,
            Err(()) => ExitCode::FAILURE,
        };
    };
    output::write_files("solve", folder, &files, |_| output::print(&summaries))
}
