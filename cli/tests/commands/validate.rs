//! `gbuffer validate`: user shaders with their includes resolved, problems placed in
//! their file with a caret, JSON output, and exit statuses 0, 1 and 2.

use crate::{gbuffer, Run};
use assert_cmd::Command;
use std::path::{Path, PathBuf};

fn validate() -> Command {
    gbuffer("validate")
}

fn write(folder: &Path, name: &str, text: &str) -> PathBuf {
    let path = folder.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// `gbuffer validate` on `shader` fails with status 1: its standard error.
fn failure(shader: &Path) -> String {
    let output = validate().arg(shader).fails_with(1);
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn a_shader_using_the_library_and_a_layout_file_is_valid_everywhere() {
    let output = validate()
        .arg("validator/examples/shaders/lighting.wgsl")
        .succeed();
    assert_eq!(
        String::from_utf8_lossy(&output.stdout),
        "validator/examples/shaders/lighting.wgsl: valid\n"
    );
}

#[test]
fn an_invalid_shader_is_reported_at_its_line_with_a_caret() {
    let output = validate()
        .arg("validator/examples/shaders/broken.wgsl")
        .fails_with(1);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.starts_with("validator/examples/shaders/broken.wgsl:6:13: error: "),
        "{stderr}"
    );
    assert!(
        stderr.contains("Requires 2 arguments, but 1 are provided"),
        "{stderr}"
    );
    assert!(
        stderr.contains("6 |     let d = d_ggx(0.5);\n  |             ^"),
        "{stderr}"
    );
}

#[test]
fn json_output_lists_every_file() {
    let output = validate()
        .args([
            "--json",
            "validator/examples/shaders/lighting.wgsl",
            "validator/examples/shaders/broken.wgsl",
        ])
        .fails_with(1);
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let files = report["files"].as_array().unwrap();
    assert_eq!(files.len(), 2);
    assert_eq!(files[0]["valid"], true);
    assert_eq!(files[1]["valid"], false);
    assert_eq!(files[1]["problems"][0]["line"], 6);
    assert_eq!(files[1]["problems"][0]["stage"], "validate");
}

/// naga labels a return-type error with the function first and the returned expression
/// second; the problem sits at the expression, in the text and in `--json`, the function kept as
/// context.
#[test]
fn a_wrong_return_is_placed_at_the_returned_expression() {
    let folder = tempfile::tempdir().unwrap();
    let shader = write(
        folder.path(),
        "return.wgsl",
        "fn offset(y: vec2<f32>) -> f32 {\n    let unused = 1.0;\n    return y + vec2<f32>(1.0);\n}\n",
    );
    let stderr = failure(&shader);
    assert!(
        stderr.starts_with(&format!("{}:3:12: error: ", shader.display())),
        "{stderr}"
    );
    assert!(
        stderr.contains("1 | fn offset"),
        "the function stays as context: {stderr}"
    );
    let output = validate().arg("--json").arg(&shader).fails_with(1);
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let problem = &report["files"][0]["problems"][0];
    assert_eq!(problem["line"], 3, "{problem}");
    assert_eq!(problem["column"], 12, "{problem}");
}

#[test]
fn include_problems_are_placed_at_the_include_line() {
    let folder = tempfile::tempdir().unwrap();
    let shader = write(
        folder.path(),
        "a.wgsl",
        "fn f() {}\n#include <gbuffer/brdf>\n",
    );
    let stderr = failure(&shader);
    assert!(
        stderr.starts_with(&format!(
            "{}:2:1: error: unknown WGSL module `brdf`",
            shader.display()
        )),
        "{stderr}"
    );

    // A bad layout file reports its own position, through the include.
    write(
        folder.path(),
        "bad.toml",
        "name = \"Bad\"\n\n[[fields]]\nname = \"x\"\nformat = \"rgba9\"\ncomponents = 4\n",
    );
    let shader = write(folder.path(), "b.wgsl", "#include \"bad.toml\"\n");
    let stderr = String::from_utf8_lossy(&validate().arg(&shader).fails_with(1).stderr).to_string();
    assert!(
        stderr.contains("bad.toml:5:10: error: unknown pixel local storage format `rgba9`"),
        "{stderr}"
    );
}

#[test]
fn problems_in_an_included_wgsl_file_name_that_file() {
    let folder = tempfile::tempdir().unwrap();
    write(
        folder.path(),
        "common.wgsl",
        "fn helper() -> f32 {\n    return 1u;\n}\n",
    );
    let shader = write(
        folder.path(),
        "main.wgsl",
        "#include \"common.wgsl\"\nfn main_helper() -> f32 { return helper(); }\n",
    );
    let stderr = failure(&shader);
    // naga labels a return-type mismatch at the function and the value: the problem sits at
    // the value, in the included file.
    assert!(
        stderr.starts_with(&format!(
            "{}:2:12: error: Function `helper` is invalid",
            folder.path().join("common.wgsl").display()
        )),
        "{stderr}"
    );
    assert!(
        stderr.contains("2 |     return 1u;\n  |            ^^ expression `1u`"),
        "{stderr}"
    );
    assert!(
        stderr.contains(
            "note: The `return` expression `1u` does not match the declared return type `f32`"
        ),
        "{stderr}"
    );
}

#[test]
fn usage_errors_exit_2() {
    validate().fails_with(2);
    validate().arg("no/such/shader.wgsl").fails_with(1);
    validate().args(["--hlsl", "a.wgsl"]).fails_with(2);
}
