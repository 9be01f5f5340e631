//! `gbuffer cost`: the numbers it prints are the ones the drivers print for the same text, in
//! a table and in JSON; a missing setup, an unknown target and GLSL ES asked of Vulkan are
//! one-line errors with exit statuses 1 and 2. The drivers run through Mesa's drm-shim, as
//! `scripts/cost-setup.sh` installs them: outside CI, a missing setup skips with the reason.

use std::path::{Path, PathBuf};

use gbuffer_cost::Target;
use gbuffer_testkit::{compilers_set_up, shader_stats_by_hand};

use crate::{gbuffer, Run};

/// A fragment shader that packs a colour made from its position (no inputs to feed).
const FRAGMENT: &str = "#version 310 es\nprecision highp float;\n\
layout(location = 0) out highp uint word;\n\
void main() { word = packUnorm4x8(fract(gl_FragCoord.xyxy * vec4(0.1, 0.2, 0.3, 0.4))); }\n";
/// A WGSL fragment shader that packs its input.
const PACK_WGSL: &str =
    "@fragment\nfn pack(@location(0) colour: vec4<f32>) -> @location(0) u32 {\n    return pack4x8unorm(colour);\n}\n";
const VERTEX: &str =
    "#version 310 es\nvoid main() { gl_Position = vec4(float(gl_VertexID), 0.0, 0.0, 1.0); }\n";

fn write(folder: &Path, name: &str, text: &str) -> PathBuf {
    let path = folder.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The driver's own shader-db line for the fragment shader, from the helper run by hand.
fn driver_line(target: &str, shader: &Path, vertex: &Path, prefix: &str) -> String {
    let target = Target::named(target).unwrap();
    let (shader, vertex) = (shader.display().to_string(), vertex.display().to_string());
    let output = shader_stats_by_hand(&target, &["gl", "fragment", &shader, &vertex]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    stdout
        .lines()
        .find_map(|line| line.strip_prefix("message: ")?.strip_prefix(prefix))
        .unwrap_or_else(|| panic!("no `{prefix}` line in:\n{stdout}"))
        .to_string()
}

/// `gbuffer cost --json` of [`PACK_WGSL`] with `arguments`: its measurements.
fn pack_measurements(arguments: &[&str]) -> Vec<serde_json::Value> {
    let folder = tempfile::tempdir().unwrap();
    let shader = write(folder.path(), "pack.wgsl", PACK_WGSL);
    let output = gbuffer("cost")
        .arg(&shader)
        .args(arguments)
        .arg("--json")
        .succeed();
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    json["measurements"].as_array().unwrap().clone()
}

#[test]
fn the_numbers_are_the_drivers_own() {
    if !compilers_set_up() {
        return;
    }
    let folder = tempfile::tempdir().unwrap();
    let shader = write(folder.path(), "pack.frag", FRAGMENT);
    let vertex = write(folder.path(), "pack.vert", VERTEX);
    let output = gbuffer("cost")
        .arg(&shader)
        .args(["--target", "mali-g610", "--target", "adreno-740", "--all"])
        .succeed();
    let stdout = String::from_utf8_lossy(&output.stdout);
    let mali = driver_line(
        "mali-g610",
        &shader,
        &vertex,
        "MESA_SHADER_FRAGMENT shader: ",
    );
    let adreno = driver_line("adreno-740", &shader, &vertex, "FRAG shader: ");
    for (target, line) in [("mali-g610", mali), ("adreno-740", adreno)] {
        let section = stdout
            .split(&format!("\n{target} reported:\n"))
            .nth(1)
            .unwrap_or_else(|| panic!("no section for {target} in:\n{stdout}"));
        for item in line.split(", ") {
            let (value, name) = item.split_once(' ').unwrap();
            if name == "spills:fills" {
                continue;
            }
            let value: f64 = value.parse().unwrap();
            assert!(
                section.contains(&format!("  {name} = {value}\n")),
                "{target}: the driver printed `{item}`; gbuffer cost printed:\n{section}"
            );
        }
        let instructions = line.split(" inst").next().unwrap();
        let row = stdout.lines().find(|row| row.starts_with(target)).unwrap();
        assert_eq!(row.split_whitespace().nth(1), Some(instructions), "{row}");
    }
}

#[test]
fn wgsl_is_costed_on_gl_and_vulkan_targets_in_json() {
    if !compilers_set_up() {
        return;
    }
    let measurements = pack_measurements(&[
        "--target",
        "mali-g52",
        "--target",
        "amd-navi21",
        "--target",
        "adreno-630-vulkan",
    ]);
    let names: Vec<&str> = measurements
        .iter()
        .map(|m| m["target"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["mali-g52", "amd-navi21", "adreno-630-vulkan"]);
    assert!(measurements[0]["device"]
        .as_str()
        .unwrap()
        .starts_with("Mali-G52"));
    assert!(
        measurements[0]["statistics"]["cycles"]["total"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    assert!(measurements[1]["device"]
        .as_str()
        .unwrap()
        .contains("NAVI21"));
    assert!(
        measurements[1]["statistics"]["inverse_throughput_cycles"]
            .as_u64()
            .unwrap()
            > 0
    );
    assert!(
        measurements[2]["statistics"]["instructions"]
            .as_u64()
            .unwrap()
            > 0
    );
}

#[test]
fn a_missing_setup_is_one_line_naming_the_script() {
    let folder = tempfile::tempdir().unwrap();
    let shader = write(folder.path(), "pack.frag", FRAGMENT);
    let output = gbuffer("cost")
        .env("GBUFFER_COST_ROOT", folder.path().join("nothing"))
        .arg(&shader)
        .args(["--target", "mali-g610"])
        .fails_with(1);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("mali-g610") && stderr.contains("scripts/cost-setup.sh"),
        "{stderr}"
    );
}

#[test]
fn an_unknown_target_or_glsl_on_vulkan_is_a_usage_error() {
    let folder = tempfile::tempdir().unwrap();
    let shader = write(folder.path(), "pack.frag", FRAGMENT);
    let output = gbuffer("cost")
        .arg(&shader)
        .args(["--target", "mali-t880"])
        .fails_with(2);
    assert!(String::from_utf8_lossy(&output.stderr).contains("mali-g610"));
    let output = gbuffer("cost")
        .arg(&shader)
        .args(["--target", "amd-navi21"])
        .fails_with(2);
    assert!(String::from_utf8_lossy(&output.stderr).contains("GL targets only"));
}

#[test]
fn the_disassembly_comes_on_request() {
    if !compilers_set_up() {
        return;
    }
    let measurements = pack_measurements(&[
        "--target",
        "mali-g610",
        "--target",
        "amd-navi21",
        "--disassembly",
    ]);
    for measurement in &measurements {
        let listing = measurement["disassembly"].as_str().unwrap_or_default();
        assert!(listing.len() > 100, "{measurement}");
    }
    // Panfrost's listing (on the driver's standard output) holds the Valhall blocks, and
    // ACO's names its instructions.
    let mali = measurements[0]["disassembly"].as_str().unwrap();
    assert!(
        mali.contains("block0 {") && mali.contains("STORE"),
        "{mali}"
    );
    let aco = measurements[1]["disassembly"].as_str().unwrap();
    assert!(aco.contains("v_") || aco.contains("s_"), "{aco}");
}
