//! `gbuffer codegen`: good layouts give every output, bad ones a `file:line:col` error
//! and exit status 1, usage errors exit status 2.

use crate::{gbuffer, workspace, Run};
use assert_cmd::Command;

fn codegen() -> Command {
    gbuffer("codegen")
}

#[test]
fn writes_every_output_for_the_seed_layouts_and_rewrites_nothing_unchanged() {
    let out = tempfile::tempdir().unwrap();
    let layouts = workspace().join("codegen/layouts");
    let mut command = codegen();
    command
        .arg(layouts.join("mobile_metallic.toml"))
        .arg(layouts.join("future_specular.toml"))
        .arg("--out")
        .arg(out.path());
    command.succeed();
    for name in [
        "mobile_metallic.wgsl",
        "mobile_metallic.pls_inout.glsl",
        "mobile_metallic.pls_in.glsl",
        "mobile_metallic.pls_out.glsl",
        "mobile_metallic.fetch.glsl",
        "mobile_metallic.vulkan.glsl",
        "mobile_metallic.vulkan.local_read.json",
        "mobile_metallic.vulkan_native.local_read.json",
        "mobile_metallic.rs",
        "mobile_metallic.report.txt",
        "future_specular.wgsl",
    ] {
        assert!(out.path().join(name).is_file(), "{name} missing");
    }
    let stamp = std::fs::metadata(out.path().join("mobile_metallic.wgsl"))
        .unwrap()
        .modified()
        .unwrap();
    let second = codegen()
        .arg(layouts.join("mobile_metallic.toml"))
        .arg("--out")
        .arg(out.path())
        .succeed();
    let stdout = String::from_utf8_lossy(&second.stdout);
    assert!(
        stdout
            .lines()
            .all(|line| line.trim_start().starts_with("unchanged")),
        "{stdout}"
    );
    assert_eq!(
        std::fs::metadata(out.path().join("mobile_metallic.wgsl"))
            .unwrap()
            .modified()
            .unwrap(),
        stamp
    );
}

#[test]
fn output_switches_choose_what_is_written() {
    let out = tempfile::tempdir().unwrap();
    let layout = workspace().join("codegen/layouts/arm_tile_block.toml");
    codegen()
        .arg(&layout)
        .args(["--wgsl", "--report", "--out"])
        .arg(out.path())
        .succeed();
    let mut names: Vec<String> = std::fs::read_dir(out.path())
        .unwrap()
        .map(|entry| entry.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["arm_tile_block.report.txt", "arm_tile_block.wgsl"]);
}

/// Each bad layout file and the start of the error it must give, after `file:line:col: error: `.
const BAD_LAYOUTS: [(&str, &str, &str); 28] = [
    ("unclosed_string", "1:15", "invalid basic string"),
    ("unknown_key", "2:1", "unknown key `budjet`, expected one of `name`, `budget`, `conversions`, `fields`"),
    ("unknown_field_key", "5:1", "unknown key `formt`"),
    ("missing_name", "1:1", "missing key `name`"),
    ("missing_format", "4:8", "field `depth` needs `format` (a whole word, e.g. \"rgba8\") or `bits` and `encoding` (a bit field)"),
    ("unknown_format", "5:10", "unknown pixel local storage format `rgba16f`; did you mean `rg16f`?"),
    ("type_and_components", "7:14", "give the field either `type` or `components`, not both"),
    ("neither_type_nor_components", "4:8", "field `colour` needs `type` (e.g. \"Vec3\") or `components` (1 to 4)"),
    ("too_many_components", "6:14", "`rgba8` has 4 channels: components must be 1 to 4, not 5"),
    ("vec4_in_r32f", "6:8", "`Vec4` has 4 components but `r32f` has 1 channel: use `f32`"),
    ("i32_in_rgba8", "6:8", "`i32` cannot be stored in `rgba8`, which holds floats"),
    ("budget_not_multiple_of_32", "2:10", "budget must be a positive multiple of 32 bits (the fields fill 32-bit words), not 100"),
    ("budget_zero", "2:10", "budget must be a positive multiple of 32 bits (the fields fill 32-bit words), not 0"),
    ("budget_negative", "2:10", "invalid value: integer `-32`, expected u32"),
    ("over_budget", "3:10", "layout `SpecularWorkflow` needs 160 bits but the budget is 128: light 32 + depth 32 + normal 32 + albedo 32 + specular 32 = 160 > 128"),
    ("duplicate_field", "9:8", "field `depth` is declared twice"),
    ("reserved_field_name", "4:8", "field name `filter` is a WGSL keyword or reserved word"),
    ("no_fields", "2:10", "layout `Empty` has no fields"),
    ("invalid_layout_name", "1:8", "layout name `2d` must be an ASCII identifier"),
    ("unknown_type", "6:8", "unknown field type `Vec5`"),
    ("name_not_a_string", "1:8", "invalid type: integer `5`, expected a string"),
    ("unknown_conversions", "2:15", "unknown conversions `approximate`: expected \"exact\""),
    ("octahedral_on_a_scalar", "5:8", "field `normal`: `octahedral` stores a unit `Vec3`, not `f32`"),
    ("bits_and_format", "5:10", "field `normal` has both `format` (a whole word) and `bits`/`encoding` (a bit field): keep one"),
    ("rgb9e5_in_16_bits", "5:8", "field `emissive`: `rgb9e5` stores a `Vec3` in exactly 32 bits, not `Vec3` in 16"),
    ("bits_33", "5:8", "field `depth`: a bit field has 1 to 32 bits (it lives in one 32-bit word), not 33"),
    ("sint_on_unsigned", "5:8", "field `flags`: `sint` holds signed integers (`i32` or an `IVec`), not `u32`"),
    ("rgbm_without_range", "6:12", "field `light`: `rgbm` needs the largest value it stores"),
];

#[test]
fn bad_layout_files_name_the_file_line_and_column_and_exit_1() {
    let folder = workspace().join("integration-tests/bad_layouts");
    let on_disk = std::fs::read_dir(&folder).unwrap().count();
    assert_eq!(
        on_disk,
        BAD_LAYOUTS.len(),
        "every file in integration-tests/bad_layouts has an expected message"
    );
    for (name, position, message) in BAD_LAYOUTS {
        let path = folder.join(format!("{name}.toml"));
        let out = tempfile::tempdir().unwrap();
        let output = codegen()
            .arg(&path)
            .arg("--out")
            .arg(out.path())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{name}: {stderr}");
        let expected = format!("{}:{position}: error: {message}", path.display());
        assert!(
            stderr.starts_with(&expected),
            "{name}:\nexpected {expected}\ngot      {stderr}"
        );
        assert!(
            stderr.contains(" | "),
            "{name}: the source line is shown: {stderr}"
        );
        assert_eq!(
            std::fs::read_dir(out.path()).unwrap().count(),
            0,
            "{name}: nothing is written"
        );
    }
}

#[test]
fn usage_errors_exit_2() {
    let layout = workspace().join("codegen/layouts/mobile_metallic.toml");
    // No --out.
    codegen().arg(&layout).fails_with(2);
    // No layout.
    codegen().args(["--out", "/tmp"]).fails_with(2);
    // An unknown switch.
    codegen()
        .arg(&layout)
        .args(["--out", "/tmp", "--hlsl"])
        .fails_with(2);
    // A layout file that does not exist is bad input, not a usage error.
    let output = codegen()
        .args(["/no/such/layout.toml", "--out", "/tmp"])
        .fails_with(1);
    assert!(String::from_utf8_lossy(&output.stderr)
        .contains("/no/such/layout.toml: cannot read the layout file"));
}

#[test]
fn help_describes_the_command() {
    let output = codegen().arg("--help").succeed();
    let help = String::from_utf8_lossy(&output.stdout);
    for expected in [
        "--out",
        "--wgsl",
        "--glsl-pls",
        "--glsl-fetch",
        "--glsl-vulkan",
        "--rust",
        "--report",
        "Exit status",
    ] {
        assert!(help.contains(expected), "--help lacks {expected}:\n{help}");
    }
}

/// The guide's page of outputs (book/src/codegen-outputs.md) names, for each switch, exactly
/// the files `gbuffer codegen` writes with it alone.
#[test]
fn the_guides_outputs_page_names_the_files_each_switch_writes() {
    let page = std::fs::read_to_string(workspace().join("book/src/codegen-outputs.md")).unwrap();
    let rows: Vec<(&str, Vec<String>)> = page
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.strip_prefix("| `--")?.split(" | ").collect();
            let switch = cells.first()?.strip_suffix('`')?;
            let files = (cells.get(1)?.split(", "))
                .map(|file| file.trim_matches('`').replace("<name>", "mobile_metallic"))
                .collect();
            Some((switch, files))
        })
        .collect();
    assert_eq!(rows.len(), 7, "a row per switch: {rows:?}");
    let layout = workspace().join("codegen/layouts/mobile_metallic.toml");
    for (switch, mut listed) in rows {
        let out = tempfile::tempdir().unwrap();
        codegen()
            .arg(&layout)
            .arg("--out")
            .arg(out.path())
            .arg(format!("--{switch}"))
            .succeed();
        let mut written: Vec<String> = std::fs::read_dir(out.path())
            .unwrap()
            .map(|entry| entry.unwrap().file_name().into_string().unwrap())
            .collect();
        written.sort();
        listed.sort();
        assert_eq!(written, listed, "--{switch}");
    }
}
