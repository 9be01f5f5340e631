//! `gbuffer solve`: scene descriptions to layouts.
//!
//! Prints each scene's solved layout with the encoding and predicted error of every stored
//! quantity. With `--out`, writes what a hand-written layout gets from `codegen` (WGSL, GLSL
//! ES includes, Rust mirror, bit report) plus `<name>.scene.wgsl` (the values struct, encode
//! and decode), `<name>.lighting.wgsl` (the specialised lighting function), and the solved
//! layout as a layout file (`<name>.layout.toml`) and as derive source (`<name>.derive.rs`).
//!
//! Exit status: 0 on success, 1 when a scene cannot be solved or an output cannot be written,
//! 2 on a usage error (bad arguments, an unreadable file).

use std::path::PathBuf;
use std::process::ExitCode;

use gbuffer_codegen::emit::wgsl::Conversions;
use gbuffer_codegen::layout_file::FileError;
use gbuffer_codegen::output::{generate, write_if_changed, Output};
use gbuffer_solver::file::read_and_solve;
use gbuffer_solver::lighting::{lighting_wgsl, Forms};

/// Solves scene descriptions (TOML): the smallest G-buffer layout that meets their precision,
/// and a lighting shader with only the terms they use.
///
/// Prints each scene's layout with the encoding and predicted error of every stored quantity.
/// With `--out`, writes what `gbuffer codegen` writes for a layout file, plus
/// `<name>.scene.wgsl`, `<name>.lighting.wgsl`, and the layout as `<name>.layout.toml` and
/// `<name>.derive.rs`.
///
/// Exit status: 0 on success, 1 when a scene cannot be solved or an output cannot be written,
/// 2 on a usage error (bad arguments, an unreadable file).
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
    let mut status = ExitCode::SUCCESS;
    for path in &arguments.scenes {
        let solution = match read_and_solve(path) {
            Ok(solution) => solution,
            Err(error @ FileError::Io { .. }) => {
                eprintln!("gbuffer solve: {error}");
                return ExitCode::from(2);
            }
            Err(error) => {
                eprintln!("{error}");
                status = ExitCode::FAILURE;
                continue;
            }
        };
        println!("{solution}");
        let Some(folder) = &arguments.out else {
            continue;
        };
        let snake = solution.layout.snake_name();
        let mut files = match generate(&solution.layout, Conversions::Exact, &Output::ALL) {
            Ok(files) => files,
            Err(error) => {
                eprintln!("gbuffer solve: {}: {error}", path.display());
                status = ExitCode::FAILURE;
                continue;
            }
        };
        files.push(gbuffer_codegen::output::GeneratedFile {
            name: format!("{snake}.scene.wgsl"),
            contents: gbuffer_solver::texel::texel_wgsl(&solution),
        });
        files.push(gbuffer_codegen::output::GeneratedFile {
            name: format!("{snake}.lighting.wgsl"),
            contents: lighting_wgsl(&solution, forms),
        });
        files.push(gbuffer_codegen::output::GeneratedFile {
            name: format!("{snake}.layout.toml"),
            contents: solution.layout_file(),
        });
        files.push(gbuffer_codegen::output::GeneratedFile {
            name: format!("{snake}.derive.rs"),
            contents: solution.derive_source(),
        });
        if let Err(error) = std::fs::create_dir_all(folder) {
            eprintln!("gbuffer solve: cannot create {}: {error}", folder.display());
            return ExitCode::FAILURE;
        }
        for file in files {
            let target = folder.join(&file.name);
            if let Err(error) = write_if_changed(&target, &file.contents) {
                eprintln!("gbuffer solve: cannot write {}: {error}", target.display());
                status = ExitCode::FAILURE;
            }
        }
    }
    status
}
