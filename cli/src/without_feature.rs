//! A subcommand this build of `gbuffer` left out: `report` and `cost` need the GPU stack and
//! the compilers' harness, which a build pipeline that only generates code should not compile.
//! Their names stay, so that asking for one says which feature brings it (exit 2, a usage
//! error) instead of "unrecognized subcommand".

use std::process::ExitCode;

/// Whatever arguments were given: they are not read.
#[derive(clap::Args, Debug)]
pub struct Arguments {
    #[arg(trailing_var_arg = true, allow_hyphen_values = true, hide = true)]
    ignored: Vec<std::ffi::OsString>,
}

/// Says that `subcommand` needs the `feature` this build lacks.
pub fn run(subcommand: &str) -> ExitCode {
    say!(
        "gbuffer {subcommand}: this gbuffer was built without the `{subcommand}` feature; \
         install it with `cargo install --locked --path cli --features {subcommand}` in a clone of the \
         repository (or run the workspace's with `cargo run -p gbuffer-cli --features {subcommand}`)"
    );
    ExitCode::from(2)
}
