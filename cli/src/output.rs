//! What the commands write. Standard output that cannot be written is an error (exit 1, a line
//! on standard error), not a panic as `println!` makes it; a closed pipe (`gbuffer ... | head`)
//! ends the output quietly, as Unix tools do. A run's files are written all or none.

use std::io::{ErrorKind, Write};
use std::path::Path;
use std::process::ExitCode;

use gbuffer_build::output::GeneratedFile;
use gbuffer_build::staging::{write_all, Planned, StagingError};

/// Writes `text` to standard output and flushes it; `Err` when it could not be written
/// (reported on standard error already).
pub fn print(text: &str) -> Result<(), ()> {
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Ok(()) => Ok(()),
        Err(error) if error.kind() == ErrorKind::BrokenPipe => Ok(()),
        Err(error) => {
            say!("gbuffer: cannot write standard output: {error}");
            Err(())
        }
    }
}

/// Writes `files` (each with its source's name) into `folder`, all or none, after `report`
/// (which prints what the run does) succeeded: exit 0, or 1 with the reason on standard error.
pub fn write_files(
    command: &str,
    folder: &Path,
    files: &[(String, GeneratedFile)],
    report: impl FnOnce(&[Planned]) -> Result<(), ()>,
) -> ExitCode {
    match write_all(folder, files, report) {
        Ok(_) => ExitCode::SUCCESS,
        // The report said why itself.
        Err(StagingError::Report) => ExitCode::FAILURE,
        Err(error) => {
            say!("gbuffer {command}: {error}; nothing was written");
            ExitCode::FAILURE
        }
    }
}
