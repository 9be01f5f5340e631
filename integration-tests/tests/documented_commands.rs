//! `.ci/documented-commands`, which lists the commands `.ci/readme-commands` runs, against a
//! page that writes commands as the documents do: wrapped over a line break, after a variable,
//! continued with a backslash in a ```sh block, and beside code that is not a command.

use std::path::Path;
use std::process::Command;

#[test]
fn the_extractor_lists_each_command_whole_and_once() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let output = Command::new("python3")
        .arg(root.join(".ci/documented-commands"))
        .arg(root.join("integration-tests/tests/documented_commands/wrapped.md"))
        .current_dir(&root)
        .output()
        .expect("python3 runs .ci/documented-commands");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let listed = String::from_utf8(output.stdout).expect("UTF-8");
    assert_eq!(
        listed.lines().collect::<Vec<_>>(),
        [
            "cargo run --release -p gbuffer-render --example deferred -- --size 320x180 --reference",
            "INSTA_UPDATE=always cargo test -p gbuffer-validator",
            "cargo run -p gbuffer-cli -- codegen codegen/layouts/mobile_metallic.toml",
            "scripts/cost-setup.sh",
        ]
    );
}
