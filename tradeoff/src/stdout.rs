//! The report's standard output. `std::println!` panics when standard output cannot be
//! written (a full disk, `> /dev/full`); the report's lines go through [`report_line!`]
//! instead, which stops printing at the first failure and lets [`run`](crate::run) return it
//! as an error, and which ends quietly on a closed pipe (`gbuffer report | head`), as Unix
//! tools do.

use std::io::{ErrorKind, Write};
use std::sync::OnceLock;

/// The first write failure of this process's report output: its message, or `None` for a
/// closed pipe.
static FAILURE: OnceLock<Option<String>> = OnceLock::new();

/// Writes one line of the report to standard output, unless an earlier one failed.
pub fn line(text: &str) {
    if FAILURE.get().is_some() {
        return;
    }
    let mut stdout = std::io::stdout().lock();
    if let Err(error) = writeln!(stdout, "{text}").and_then(|()| stdout.flush()) {
        let _ = FAILURE.set((error.kind() != ErrorKind::BrokenPipe).then(|| error.to_string()));
    }
}

/// The error that stopped the report's output, if one did (a closed pipe is none).
pub fn failure() -> Option<String> {
    FAILURE.get().cloned().flatten()
}

/// `println!` for the report: see the module's documentation.
macro_rules! report_line {
    ($($argument:tt)*) => {
        $crate::stdout::line(&format!($($argument)*))
    };
}
pub(crate) use report_line;
