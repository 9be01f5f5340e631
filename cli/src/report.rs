//! `gbuffer report`: the speed/accuracy trade of every approximation and encoding.

use std::path::PathBuf;
use std::process::ExitCode;

/// Measures every approximation and encoding of the shading library: its error against the f64
/// references, its cost in naga expressions and SPIR-V instructions, its time on the adapter
/// at hand and its Rust mirror's time on the CPU. Prints the table and writes `report.md`,
/// `report.json` and PNG plots.
///
/// Exit status: 0 on success, 1 when no adapter or tool is there or a report file cannot be
/// written.
#[derive(clap::Args, Debug)]
pub struct Arguments {
    /// Folder to write the report into (created if missing).
    #[arg(long, short, value_name = "DIR", default_value = "target/tradeoff")]
    out: PathBuf,
}

pub fn run(arguments: Arguments) -> ExitCode {
    match gbuffer_tradeoff::run(&arguments.out) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            say!("gbuffer report: {error}");
            ExitCode::FAILURE
        }
    }
}
