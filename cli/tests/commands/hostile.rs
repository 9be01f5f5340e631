//! The command line under hostile input, one test per reproducer of the issue that found them:
//! every one exits 1 or 2 with a one-line reason, within a few seconds, and leaves no file
//! behind. The property test in `fuzz.rs` keeps the classes closed.

use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

use crate::{gbuffer, workspace, Run};

/// A layout file of one rgba8 field named `field`, the layout named `name`.
fn layout(name: &str, field: &str) -> String {
    format!("name = \"{name}\"\n\n[[fields]]\nname = \"{field}\"\nformat = \"rgba8\"\ntype = \"Vec4\"\n")
}

/// The standard error of `gbuffer codegen INPUT --out OUT`, which must exit 1.
fn codegen_refuses(input: &Path, out: &Path) -> String {
    let output = gbuffer("codegen")
        .arg(input)
        .arg("--out")
        .arg(out)
        .fails_with(1);
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The names of the entries of `folder` (none when it does not exist).
fn entries(folder: &Path) -> Vec<String> {
    std::fs::read_dir(folder).map_or_else(
        |_| Vec::new(),
        |entries| {
            entries
                .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        },
    )
}

#[test]
fn rust_keywords_as_names_are_errors_not_panics() {
    let folder = tempfile::tempdir().unwrap();
    for (layout_name, field) in [("Texel", "in"), ("Texel", "dyn"), ("Texel", "box")] {
        let path = folder.path().join("keyword.toml");
        std::fs::write(&path, layout(layout_name, field)).unwrap();
        let stderr = codegen_refuses(&path, &folder.path().join("out"));

        assert!(
            stderr.contains(&format!("field name `{field}` is a Rust keyword")),
            "{stderr}"
        );
    }
    assert!(entries(&folder.path().join("out")).is_empty());
}

/// `gbuffer ARGUMENTS > /dev/full`: its exit code and standard error.
fn into_full_device(arguments: &[&std::ffi::OsStr]) -> (Option<i32>, String) {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_gbuffer"))
        .current_dir(workspace())
        .args(arguments)
        .stdout(full)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn a_full_standard_output_is_an_error_and_writes_nothing() {
    let folder = tempfile::tempdir().unwrap();
    let out = folder.path().join("out");
    let layout = workspace().join("codegen/layouts/mobile_metallic.toml");
    let (code, stderr) = into_full_device(&[
        "codegen".as_ref(),
        layout.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot write standard output"), "{stderr}");
    assert!(!out.exists(), "{:?}", entries(&out));
    for arguments in [
        ["solve", "solver/scenes/mobile-metallic.toml"],
        ["validate", "validator/examples/shaders/lighting.wgsl"],
    ] {
        let arguments: Vec<&std::ffi::OsStr> = arguments.iter().map(|text| text.as_ref()).collect();
        let (code, stderr) = into_full_device(&arguments);
        assert_eq!(code, Some(1), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn help_that_cannot_be_written_fails() {
    for arguments in [["--help"], ["codegen --help"]] {
        let arguments: Vec<&std::ffi::OsStr> =
            arguments[0].split(' ').map(|text| text.as_ref()).collect();
        let (code, stderr) = into_full_device(&arguments);
        assert_eq!(code, Some(1), "{arguments:?}: {stderr}");
    }
}

#[test]
fn an_error_with_standard_error_unwritable_still_exits_1() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let folder = tempfile::tempdir().unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_gbuffer"))
        .current_dir(workspace())
        .args(["codegen", "no/such/layout.toml", "--out"])
        .arg(folder.path().join("out"))
        .stdout(Stdio::null())
        .stderr(full)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
}

#[test]
fn a_closed_pipe_ends_the_output_quietly() {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_gbuffer"))
        .current_dir(workspace())
        .args(["solve", "solver/scenes/mobile-metallic.toml"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(0));
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn long_expressions_and_include_chains_get_located_errors() {
    let folder = tempfile::tempdir().unwrap();
    let terms = vec!["1.0"; 100_000].join("+");
    let long = folder.path().join("long.wgsl");
    std::fs::write(
        &long,
        format!("@fragment\nfn main() -> @location(0) vec4<f32> {{\n    return vec4<f32>({terms});\n}}\n"),
    )
    .unwrap();
    if cfg!(feature = "cost") {
        let output = gbuffer("cost").arg(&long).fails_with(1);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains("long.wgsl:3:5: this statement has more than 4096"),
            "{stderr}"
        );
    }
    let output = gbuffer("validate").arg(&long).fails_with(1);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("long.wgsl:3:5: error: this statement has more than 4096 operators"),
        "{stderr}"
    );
    let nested = folder.path().join("nested.wgsl");
    std::fs::write(
        &nested,
        format!(
            "fn f() -> f32 {{ return {}1.0{}; }}\n",
            "(".repeat(10_000),
            ")".repeat(10_000)
        ),
    )
    .unwrap();
    let output = gbuffer("validate").arg(&nested).fails_with(1);
    assert!(String::from_utf8_lossy(&output.stderr).contains("nested.wgsl:1:"));
    for index in 0..3000 {
        std::fs::write(
            folder.path().join(format!("{index}.wgsl")),
            format!("#include \"{}.wgsl\"\nfn f{index}() {{}}\n", index + 1),
        )
        .unwrap();
    }
    std::fs::write(folder.path().join("3000.wgsl"), "fn last() {}\n").unwrap();
    let output = gbuffer("validate")
        .arg(folder.path().join("0.wgsl"))
        .fails_with(1);
    assert!(String::from_utf8_lossy(&output.stderr).contains("nest more than 64 files deep"));
}

#[test]
fn oversized_inputs_and_special_files_are_refused_at_once() {
    let folder = tempfile::tempdir().unwrap();
    let huge = folder.path().join("huge.toml");
    std::fs::write(&huge, layout(&"N".repeat(50 << 20), "value")).unwrap();
    let stderr = codegen_refuses(&huge, &folder.path().join("out"));
    assert!(stderr.contains("over the limit"));
    let fifo = folder.path().join("fifo.toml");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let started = Instant::now();
    let stderr = codegen_refuses(&fifo, &folder.path().join("out"));
    assert!(stderr.contains("not a regular file"));
    let shader = folder.path().join("fifo_include.wgsl");
    std::fs::write(&shader, "#include \"fifo.toml\"\n").unwrap();
    gbuffer("validate").arg(&shader).fails_with(1);
    if cfg!(feature = "cost") {
        let output = gbuffer("cost")
            .arg(folder.path().join("fifo.toml"))
            .fails_with(1);
        assert!(String::from_utf8_lossy(&output.stderr).contains("not a regular file"));
    }
    codegen_refuses(folder.path(), &folder.path().join("out"));
    assert!(started.elapsed() < Duration::from_secs(10));
    assert!(!folder.path().join("out").exists());
}

#[test]
fn thousands_of_fields_are_refused_quickly() {
    let folder = tempfile::tempdir().unwrap();
    let mut text = String::from("name = \"Many\"\nbudget = 10016\n");
    for index in 0..10_000 {
        text.push_str(&format!(
            "\n[[fields]]\nname = \"f{index}\"\nbits = 1\nencoding = \"unorm\"\ntype = \"f32\"\n"
        ));
    }
    let path = folder.path().join("many.toml");
    std::fs::write(&path, text).unwrap();
    let started = Instant::now();
    let stderr = codegen_refuses(&path, &folder.path().join("out"));
    assert!(stderr.contains("limited to 256"));
    assert!(started.elapsed() < Duration::from_secs(5));
}

#[test]
fn a_failed_run_leaves_no_file_behind() {
    let folder = tempfile::tempdir().unwrap();
    let out = folder.path().join("out");
    std::fs::create_dir_all(out.join("mobile_metallic.fetch.glsl")).unwrap();
    let stderr = codegen_refuses(
        &workspace().join("codegen/layouts/mobile_metallic.toml"),
        &out,
    );
    assert!(stderr.contains("nothing was written"));
    assert_eq!(entries(&out), ["mobile_metallic.fetch.glsl"]);
    // Two scenes, the second unsolvable: nothing of the first.
    let scene =
        std::fs::read_to_string(workspace().join("solver/scenes/mobile-metallic.toml")).unwrap();
    let broken = folder.path().join("broken.toml");
    std::fs::write(
        &broken,
        scene.replace("normal_degrees = 0.5", "normal_degrees = -1"),
    )
    .unwrap();
    let scenes_out = folder.path().join("scenes");
    gbuffer("solve")
        .arg(workspace().join("solver/scenes/mobile-metallic.toml"))
        .arg(&broken)
        .arg("--out")
        .arg(&scenes_out)
        .fails_with(1);
    assert!(!scenes_out.exists());
}

#[test]
fn two_sources_of_one_file_are_an_error_naming_both() {
    let folder = tempfile::tempdir().unwrap();
    let first = folder.path().join("first.toml");
    let second = folder.path().join("second.toml");
    std::fs::write(&first, layout("MobileMetallic", "value")).unwrap();
    std::fs::write(&second, layout("Mobile_Metallic", "value")).unwrap();
    let out = folder.path().join("out");
    let output = gbuffer("codegen")
        .arg(&first)
        .arg(&second)
        .arg("--out")
        .arg(&out)
        .fails_with(1);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("first.toml") && stderr.contains("second.toml"),
        "{stderr}"
    );
    assert!(!out.exists());
    // One scene given twice: the same.
    let scene = workspace().join("solver/scenes/mobile-metallic.toml");
    gbuffer("solve")
        .arg(&scene)
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .fails_with(1);
    assert!(!out.exists());
}

#[test]
fn a_very_long_name_is_refused() {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("long.toml");
    std::fs::write(&path, layout("Texel", &"n".repeat(10_000))).unwrap();
    let stderr = codegen_refuses(&path, &folder.path().join("out"));
    assert!(stderr.contains("names are limited to 128"));
}

#[test]
fn includes_outside_the_roots_are_refused() {
    let folder = tempfile::tempdir().unwrap();
    let inner = folder.path().join("project/shaders");
    std::fs::create_dir_all(&inner).unwrap();
    std::fs::write(folder.path().join("elsewhere.wgsl"), "fn f() {}\n").unwrap();
    let shader = inner.join("main.wgsl");
    std::fs::write(&shader, "#include \"../../elsewhere.wgsl\"\n").unwrap();
    let output = gbuffer("validate").arg(&shader).fails_with(1);
    assert!(String::from_utf8_lossy(&output.stderr).contains("outside the include roots"));
    // An include directory lets it in.
    gbuffer("validate")
        .arg(&shader)
        .arg("--include-dir")
        .arg(folder.path())
        .succeed();
}
