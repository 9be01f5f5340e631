//! `gbuffer`: one command for the tools around a G-buffer layout. Each subcommand lives in its
//! own module, with its arguments, its `--help` text and its exit statuses.

mod codegen;
mod cost;
mod output;
mod report;
mod solve;
mod validate;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Tools for pixel local storage G-buffers: generate shader includes from layout files,
/// validate shaders that use them, solve scenes for the smallest layout, measure the
/// speed/accuracy trade of the shading library, and cost shaders on the compilers of Mali,
/// Adreno, AMD and NVIDIA GPUs.
///
/// Exit status: 0 on success, 1 when an input is invalid (a layout, a shader, a scene) or an
/// output cannot be written, 2 on a usage error.
#[derive(Parser, Debug)]
#[command(name = "gbuffer", version, about, long_about)]
struct Command {
    #[command(subcommand)]
    subcommand: Subcommands,
}

/// One subcommand; its help is its arguments' doc comment.
#[derive(Subcommand, Debug)]
enum Subcommands {
    Codegen(codegen::Arguments),
    Validate(validate::Arguments),
    Solve(solve::Arguments),
    Report(report::Arguments),
    Cost(cost::Arguments),
}

fn main() -> ExitCode {
    match Command::parse().subcommand {
        Subcommands::Codegen(arguments) => codegen::run(arguments),
        Subcommands::Validate(arguments) => validate::run(arguments),
        Subcommands::Solve(arguments) => solve::run(arguments),
        Subcommands::Report(arguments) => report::run(arguments),
        Subcommands::Cost(arguments) => cost::run(arguments),
    }
}
