//! `gbuffer solve`: a scene file gives what `gbuffer codegen` gives a layout file plus the
//! scene's WGSL; a bad scene is an error at its `file:line:col` with exit status 1, as is a
//! missing file.

use crate::{gbuffer, workspace, Run};
use assert_cmd::Command;

fn solve() -> Command {
    gbuffer("solve")
}

#[test]
fn writes_every_output_and_places_errors() {
    let folder = tempfile::tempdir().unwrap();
    let preset = workspace().join("solver/scenes/mobile-metallic.toml");
    let output = solve()
        .arg(&preset)
        .arg("--out")
        .arg(folder.path())
        .succeed();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("MobileMetallicScene: 96 of 128 bits"),
        "{stdout}"
    );
    for name in [
        "mobile_metallic_scene.wgsl",
        "mobile_metallic_scene.rs",
        "mobile_metallic_scene.report.txt",
        "mobile_metallic_scene.vulkan.glsl",
        "mobile_metallic_scene.scene.wgsl",
        "mobile_metallic_scene.lighting.wgsl",
        "mobile_metallic_scene.layout.toml",
        "mobile_metallic_scene.derive.rs",
    ] {
        assert!(folder.path().join(name).exists(), "{name} was not written");
    }
    let scene_wgsl =
        std::fs::read_to_string(folder.path().join("mobile_metallic_scene.scene.wgsl")).unwrap();
    gbuffer_validator::validate_wgsl(&scene_wgsl).unwrap();
    // The layout file it writes is a layout `gbuffer codegen` reads.
    let layout_file = folder.path().join("mobile_metallic_scene.layout.toml");
    let read = gbuffer_layout_file::read_layout_file(&layout_file).unwrap();
    assert_eq!(read.layout.name, "MobileMetallicScene");

    let broken = folder.path().join("broken.toml");
    let text = std::fs::read_to_string(&preset).unwrap();
    std::fs::write(
        &broken,
        text.replace("normal_degrees = 0.5", "normal_degrees = -1"),
    )
    .unwrap();
    let output = solve().arg(&broken).fails_with(1);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("broken.toml:15:18: error"), "{stderr}");
    solve().arg(folder.path().join("none.toml")).fails_with(1);
}
