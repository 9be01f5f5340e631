//! What the package's benches share: the rounds they time their passes in, and where they
//! write the tables the guide shows (`.ci/check-figures` holds the guide's tables to them).

use std::path::{Path, PathBuf};

/// The rounds a bench times and counts, after [`WARM_UP_ROUNDS`]; fewer where
/// `GBUFFER_TIMING=short` asks, as CI does: it checks the tables' shape, not their figures.
pub fn rounds() -> usize {
    match std::env::var_os("GBUFFER_TIMING") {
        Some(value) if value == "short" => 5,
        _ => 31,
    }
}

/// Rounds run before a bench counts: the caches, the branch predictors and the CPU's clock
/// settle.
pub const WARM_UP_ROUNDS: usize = 3;

/// The target folder: `CARGO_TARGET_DIR`, or three folders above the bench (target/release/deps).
pub fn target_folder() -> Option<PathBuf> {
    if let Some(folder) = std::env::var_os("CARGO_TARGET_DIR") {
        return Some(PathBuf::from(folder));
    }
    let exe = std::env::current_exe().ok()?;
    Some(exe.parent()?.parent()?.parent()?.to_path_buf())
}

/// Writes `table` to `figures/{file}` under `target`, and says where (or why not). Written
/// beside and renamed, so that a failed write leaves no half table.
pub fn write_figures(target: &Path, file: &str, table: &str) {
    let figures = target.join("figures");
    let partial = figures.join(format!("{file}.partial"));
    let written = std::fs::create_dir_all(&figures)
        .and_then(|()| std::fs::write(&partial, table))
        .and_then(|()| std::fs::rename(&partial, figures.join(file)));
    match written {
        Ok(()) => println!("written to {}", figures.join(file).display()),
        Err(error) => eprintln!("cannot write {}: {error}", figures.display()),
    }
}
