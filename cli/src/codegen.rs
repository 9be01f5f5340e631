//! `gbuffer codegen`: layout files to shader includes, Rust mirrors and reports.

use std::path::PathBuf;
use std::process::ExitCode;

use gbuffer_codegen::layout_file::{read_layout_file, FileError};
use gbuffer_codegen::output::{generate, write_if_changed, Output, WriteOutcome};

/// Turns G-buffer layout files (TOML) into shader includes: WGSL, GLSL ES pixel local storage
/// blocks, framebuffer-fetch and Vulkan subpass-input includes, Rust mirrors and bit reports.
///
/// With no output switch, every output is written. Files are written atomically, and a file
/// whose contents would not change is not rewritten.
///
/// Exit status: 0 on success, 1 when a layout is invalid (or an output cannot be written),
/// 2 on a usage error (bad arguments, an unreadable layout file).
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
    /// GLSL ES framebuffer-fetch include (`<name>.fetch.glsl`).
    #[arg(long)]
    glsl_fetch: bool,
    /// Vulkan GLSL subpass-input include (`<name>.vulkan.glsl`).
    #[arg(long)]
    glsl_vulkan: bool,
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

const INVALID_LAYOUT: u8 = 1;
const USAGE: u8 = 2;

pub fn run(arguments: Arguments) -> ExitCode {
    let outputs = arguments.outputs();
    // Read and check every layout first, so that all problems are reported together and
    // nothing is written from a set of layouts that has an invalid one.
    let mut layouts = Vec::new();
    let mut status = None;
    for path in &arguments.layouts {
        match read_layout_file(path) {
            Ok(layout) => layouts.push(layout),
            Err(error @ FileError::Io { .. }) => {
                eprintln!("gbuffer codegen: {error}");
                status = Some(USAGE);
            }
            Err(error) => {
                eprintln!("{error}\n");
                status = status.or(Some(INVALID_LAYOUT));
            }
        }
    }
    if let Some(status) = status {
        return ExitCode::from(status);
    }
    for file in &layouts {
        let layout = &file.layout;
        let files = match generate(layout, file.conversions, &outputs) {
            Ok(files) => files,
            Err(error) => {
                eprintln!("gbuffer codegen: {}: {error}", layout.name);
                return ExitCode::from(INVALID_LAYOUT);
            }
        };
        for file in files {
            let path = arguments.out.join(&file.name);
            match write_if_changed(&path, &file.contents) {
                Ok(outcome) if !arguments.quiet => {
                    let verb = if outcome == WriteOutcome::Written {
                        "wrote"
                    } else {
                        "unchanged"
                    };
                    println!("{verb:>9} {}", path.display());
                }
                Ok(_) => {}
                Err(error) => {
                    eprintln!("gbuffer codegen: {}: cannot write: {error}", path.display());
                    return ExitCode::from(INVALID_LAYOUT);
                }
            }
        }
    }
    ExitCode::SUCCESS
}
