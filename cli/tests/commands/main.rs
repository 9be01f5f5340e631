//! The `gbuffer` command as users run it: each subcommand's outputs, its errors placed at
//! `file:line:col`, and its exit statuses. Cargo builds the binary for these tests.

mod codegen;
#[cfg(feature = "cost")]
mod cost;
mod fuzz;
mod hostile;
mod solve;
mod validate;
#[cfg(not(all(feature = "report", feature = "cost")))]
mod without_feature;

use assert_cmd::Command;
use std::path::{Path, PathBuf};
use std::process::Output;

/// The workspace's root folder, where the fixtures live and the commands run.
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("cli/ is in the workspace")
        .to_path_buf()
}

/// `gbuffer <subcommand>`, run from the workspace's root.
fn gbuffer(subcommand: &str) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_gbuffer"));
    command.current_dir(workspace()).arg(subcommand);
    command
}

/// Running a command for what a test checks.
trait Run {
    /// Its output, failing the test with its standard error unless it succeeded.
    fn succeed(&mut self) -> Output;
    /// Its output, failing the test with its standard error unless it exited with `code`.
    fn fails_with(&mut self, code: i32) -> Output;
}

impl Run for Command {
    fn succeed(&mut self) -> Output {
        let output = self.output().expect("running gbuffer");
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        output
    }

    fn fails_with(&mut self, code: i32) -> Output {
        let output = self.output().expect("running gbuffer");
        assert_eq!(
            output.status.code(),
            Some(code),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        output
    }
}
