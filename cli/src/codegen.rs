//! `gbuffer codegen`: layout files to shader includes, Rust mirrors and reports.

use std::path::PathBuf;
use std::process::ExitCode;

use gbuffer_build::output::{generate, Output, WriteOutcome};
use gbuffer_build::staging::Planned;
use gbuffer_layout_file::{read_layout_file, FileError};

use crate::output;

/// Turns G-buffer layout files (TOML) into shader includes: WGSL, GLSL ES pixel local storage
/// blocks, framebuffer-fetch and Vulkan subpass-input includes, WebGL 2 pixel local storage
/// (with its JavaScript host module), Rust mirrors and bit reports.
///
/// With no output switch, every output is written. A run writes all its files or none: they
/// are staged beside the folder and moved in once every one is written (a file whose contents
/// would not change is not rewritten); two layouts that would write one file are an error.
///
/// Exit status: 0 on success, 1 when a layout is invalid or unreadable or an output cannot be
/// written (nothing is written then), 2 on a usage error (bad arguments).
#[derive(clap::Args, Debug)]
pub struct Arguments {
    /// Layout files to generate from.
    #[arg(required = true, value_name = "LAYOUT.toml")]
    layouts: Vec<PathBuf>,
    /// Folder to write the outputs into (created if missing).
    #[arg(long, short, value_name = "DIR")]
    out: PathBuf,
    /// The WGSL include (`<name>.wgsl`).
    #[arg(long)]
    wgsl: bool,
    /// GLSL ES pixel local storage blocks (`<name>.pls_{inout,in,out}.glsl`).
    #[arg(long)]
    glsl_pls: bool,
    /// GLSL ES framebuffer-fetch includes, packed and native (`<name>.fetch{,_native}.glsl`).
    #[arg(long)]
    glsl_fetch: bool,
    /// Vulkan GLSL subpass-input includes (`<name>.vulkan{,_native}.glsl`), each with what a host
    /// sets to read it under dynamic rendering local read (`.local_read.json`).
    #[arg(long)]
    glsl_vulkan: bool,
    /// WebGL 2 pixel local storage include and its host module (`<name>.webgl_pls.{glsl,js}`).
    #[arg(long)]
    webgl_pls: bool,
    /// Rust mirror source (`<name>.rs`, with the `.wgsl` it includes).
    #[arg(long)]
    rust: bool,
    /// Bit report (`<name>.report.txt`).
    #[arg(long)]
    report: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

impl Arguments {
    fn outputs(&self) -> Vec<Output> {
        let chosen: Vec<Output> = [
            (self.wgsl, Output::Wgsl),
            (self.glsl_pls, Output::GlslPixelLocalStorage),
            (self.glsl_fetch, Output::GlslFramebufferFetch),
            (self.glsl_vulkan, Output::GlslVulkan),
            (self.webgl_pls, Output::WebGlPixelLocalStorage),
            (self.rust, Output::Rust),
            (self.report, Output::Report),
        ]
        .into_iter()
        .filter_map(|(on, output)| on.then_some(output))
        .collect();
        if chosen.is_empty() {
            Output::ALL.to_vec()
        } else {
            chosen
        }
    }
}

pub fn run(arguments: Arguments) -> ExitCode {
    let outputs = arguments.outputs();
    // Read and check every layout first, so that all problems are reported together and
    // nothing is written from a set of layouts that has an invalid one.
    let mut layouts = Vec::new();
    let mut failed = false;
    for path in &arguments.layouts {
        match read_layout_file(path) {
            Ok(layout) => layouts.push((path, layout)),
            Err(error @ FileError::Io { .. }) => {
                say!("gbuffer codegen: {error}");
                failed = true;
            }
            Err(error) => {
                say!("{error}\n");
                failed = true;
            }
        }
    }
    if failed {
        return ExitCode::FAILURE;
    }
    let mut files = Vec::new();
    for (path, file) in &layouts {
        match generate(&file.layout, file.conversions, &outputs) {
            Ok(generated) => files.extend(generated.into_iter().map(|generated| {
                (
                    format!("{} (layout {})", path.display(), file.layout.name),
                    generated,
                )
            })),
            Err(error) => {
                say!("gbuffer codegen: {}: {error}", file.layout.name);
                return ExitCode::FAILURE;
            }
        }
    }
    // The lines go out before the files move in: output that cannot be written fails the run.
    let report = |planned: &[Planned]| {
        if arguments.quiet {
            return Ok(());
        }
        let lines: String = planned
            .iter()
            .map(|file| {
                let verb = match file.outcome {
                    WriteOutcome::Written => "wrote",
                    WriteOutcome::Unchanged => "unchanged",
                };
                format!("{verb:>9} {}\n", file.path.display())
            })
            .collect();
        output::print(&lines)
    };
    output::write_files("codegen", &arguments.out, &files, report)
}
