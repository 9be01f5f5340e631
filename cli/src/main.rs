//! `gbuffer`: one command for the tools around a G-buffer layout. Each subcommand lives in its
//! own module, with its arguments, its `--help` text and its exit statuses. `report` and
//! `cost` come with the features of their names (off by default, so that `cargo install
//! --path cli` builds no GPU stack); without them, asking for one says which feature to
//! enable.

/// `eprintln!` without its panic: where standard error cannot be written (`2>/dev/full`), the
/// exit status is all a command can still say, and it stays 0, 1 or 2, never 101.
macro_rules! say {
    ($($message:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($message)*);
    }};
}

mod codegen;
#[cfg(feature = "cost")]
mod cost;
mod json;
mod output;
#[cfg(feature = "report")]
mod report;
mod solve;
mod validate;
#[cfg(not(all(feature = "report", feature = "cost")))]
mod without_feature;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Tools for pixel local storage G-buffers: generate shader includes from layout files,
/// validate shaders that use them, solve scenes for the smallest layout, measure the
/// speed/accuracy trade of the shading library, and cost shaders on the compilers of Mali,
/// Adreno, AMD and NVIDIA GPUs.
///
/// `report` and `cost` need the features of their names: `cargo install --locked --path cli --features
/// report,cost`.
///
/// Exit status: 0 on success, 1 when an input is invalid or unreadable (a layout, a shader, a
/// scene) or an output cannot be written, 2 on a usage error.
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
    #[cfg(feature = "report")]
    Report(report::Arguments),
    /// Measures the speed/accuracy trade of the shading library (this build lacks the `report`
    /// feature: `cargo install --locked --path cli --features report`).
    #[cfg(not(feature = "report"))]
    Report(without_feature::Arguments),
    #[cfg(feature = "cost")]
    Cost(cost::Arguments),
    /// Costs a shader on the compilers of Mali, Adreno, AMD and NVIDIA GPUs (this build lacks
    /// the `cost` feature: `cargo install --locked --path cli --features cost`).
    #[cfg(not(feature = "cost"))]
    Cost(without_feature::Arguments),
}

/// The stack of the thread a subcommand runs on: naga walks a shader's expressions
/// recursively, and the largest statement the commands accept (see
/// `gbuffer_validator::expression_size`) needs more than a main thread's 8 MiB.
const STACK_BYTES: usize = 256 << 20;

fn main() -> ExitCode {
    let command = match Command::try_parse() {
        Ok(command) => command,
        // Help and version (exit 0) and usage errors (exit 2), printed where clap prints them;
        // a help that cannot be written is a failure, not a success.
        Err(error) => {
            return match error.print() {
                Ok(()) => ExitCode::from(error.exit_code() as u8),
                Err(_) => ExitCode::FAILURE,
            };
        }
    };
    let run = move || match command.subcommand {
        Subcommands::Codegen(arguments) => codegen::run(arguments),
        Subcommands::Validate(arguments) => validate::run(arguments),
        Subcommands::Solve(arguments) => solve::run(arguments),
        #[cfg(feature = "report")]
        Subcommands::Report(arguments) => report::run(arguments),
        #[cfg(not(feature = "report"))]
        Subcommands::Report(_) => without_feature::run("report"),
        #[cfg(feature = "cost")]
        Subcommands::Cost(arguments) => cost::run(arguments),
        #[cfg(not(feature = "cost"))]
        Subcommands::Cost(_) => without_feature::run("cost"),
    };
    match std::thread::Builder::new()
        .stack_size(STACK_BYTES)
        .spawn(run)
    {
        // A panic stays one (exit 101): the tests must see it, not a quiet failure.
        Ok(thread) => thread
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
        Err(error) => {
            say!("gbuffer: cannot start: {error}");
            ExitCode::FAILURE
        }
    }
}
