//! What the package's benches share: the rounds they time their passes in, how they time and
//! summarise them, and where they write the tables the guide shows (`.ci/check-figures` holds
//! the guide's tables to them).

use std::path::{Path, PathBuf};
use std::time::Instant;

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

/// The seconds `run` takes.
pub fn time(run: impl FnOnce()) -> f64 {
    let start = Instant::now();
    run();
    start.elapsed().as_secs_f64()
}

/// The lower quartile, the median and the upper quartile of `values`.
pub fn quartiles(mut values: Vec<f64>) -> [f64; 3] {
    values.sort_by(f64::total_cmp);
    let at = |fraction: f64| values[((values.len() - 1) as f64 * fraction).round() as usize];
    [at(0.25), at(0.5), at(0.75)]
}

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
