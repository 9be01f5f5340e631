//! Standard output that cannot be written is an error (exit 1, a line on standard error), not a
//! panic as `println!` makes it; a closed pipe (`gbuffer ... | head`) ends the output quietly,
//! as Unix tools do.

use std::io::{ErrorKind, Write};

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
            eprintln!("gbuffer: cannot write standard output: {error}");
            Err(())
        }
    }
}
