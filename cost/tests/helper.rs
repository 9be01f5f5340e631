//! The helper (`cost/helper/shader_stats.c`, as `scripts/cost-setup.sh` builds it) on every
//! target, by hand: it starts each driver as the GPU asked for, compiles a fragment shader (GL:
//! two in one run, the second broken; Vulkan: a compute shader and a fragment shader), reports
//! the compiler's statistics for the good ones and one `error:` line for the broken one, and
//! exits 2 on a usage error. The parsing of what it prints is tested in the crate; here, only
//! what the helper itself promises. Outside CI a missing setup skips with the reason; under
//! `CI=true` it fails.

use std::path::Path;

use gbuffer_core::Named;
use gbuffer_cost::{Api, Shader, Stage, TARGETS};
use gbuffer_testkit::{compilers_set_up, shader_stats_by_hand as helper};

fn write(folder: &Path, name: &str, bytes: &[u8]) -> String {
    let path = folder.join(name);
    std::fs::write(&path, bytes).unwrap();
    path.display().to_string()
}

#[test]
fn the_helper_reports_each_shader_on_every_target() {
    if !compilers_set_up() {
        return;
    }
    let folder = tempfile::tempdir().unwrap();
    let fragment =
        "#version 310 es\nprecision highp float;\nlayout(location = 0) out highp uint word;\n\
                    void main() { word = packUnorm4x8(fract(gl_FragCoord.xyxy)); }\n";
    let vertex = "#version 310 es\nvoid main() { gl_Position = vec4(float(gl_VertexID)); }\n";
    let good = write(folder.path(), "good.frag", fragment.as_bytes());
    let broken = write(
        folder.path(),
        "broken.frag",
        b"#version 310 es\nvoid main() { nonsense; }\n",
    );
    let vertex = write(folder.path(), "good.vert", vertex.as_bytes());
    let wgsl = "@group(0) @binding(0) var<storage, read_write> words: array<u32>;\n\
                @compute @workgroup_size(64)\nfn pack(@builtin(global_invocation_id) id: vec3<u32>) {\n    \
                words[id.x] = pack4x8unorm(vec4<f32>(f32(id.x)));\n}\n\
                @fragment\nfn shade(@location(0) colour: vec4<f32>) -> @location(0) u32 {\n    \
                return pack4x8unorm(colour);\n}\n";
    let compute = Shader::wgsl(wgsl, "pack").unwrap().vulkan().unwrap();
    let shade = Shader::wgsl(wgsl, "shade").unwrap().vulkan().unwrap();
    let compute_spv = write(
        folder.path(),
        "pack.spv",
        bytemuck::cast_slice(&compute.shader),
    );
    let shade_spv = write(
        folder.path(),
        "shade.spv",
        bytemuck::cast_slice(&shade.shader),
    );
    let shade_vertex = write(
        folder.path(),
        "shade.vert.spv",
        bytemuck::cast_slice(shade.vertex.as_ref().unwrap()),
    );
    for target in TARGETS {
        let output = match target.api {
            Api::Gles => helper(
                &target,
                &[
                    "gl", "fragment", &good, &vertex, "--", "fragment", &broken, &vertex,
                ],
            ),
            Api::Vulkan => {
                let mut arguments = vec![
                    "vulkan",
                    "compute",
                    &compute_spv,
                    "--entry",
                    "pack",
                    "--descriptor",
                    "0,0,storage",
                    "--",
                    "fragment",
                    &shade_spv,
                    &shade_vertex,
                    "--entry",
                    "shade",
                    "--color",
                    "r32ui",
                ];
                // The companion vertex shader's buffer.
                for descriptor in &shade.descriptors {
                    arguments.extend(["--descriptor", descriptor]);
                }
                helper(&target, &arguments)
            }
        };
        let stdout = String::from_utf8_lossy(&output.stdout);
        let what = format!(
            "{}:\n{stdout}{}",
            target.name,
            String::from_utf8_lossy(&output.stderr)
        );
        assert!(output.status.success(), "{what}");
        let device = stdout.lines().next().unwrap_or_default();
        assert!(device.contains(target.expected_device), "{what}");
        let sections: Vec<&str> = stdout.split("\nshader: ").skip(1).collect();
        assert_eq!(sections.len(), 2, "{what}");
        match target.api {
            Api::Gles => {
                assert!(
                    sections[0].contains("message: ") && !sections[0].contains("error: "),
                    "{what}"
                );
                assert!(
                    sections[1].contains("error: broken.frag does not compile")
                        || sections[1].contains("does not compile"),
                    "{what}"
                );
            }
            Api::Vulkan => {
                for section in sections {
                    assert!(
                        section.contains("executable: ") && section.contains("statistic: "),
                        "{what}"
                    );
                }
            }
        }
    }
    let usage = helper(&TARGETS[0], &["neither"]);
    assert_eq!(usage.status.code(), Some(2));
    // The stage names the helper takes are the crate's.
    assert_eq!(
        [Stage::Fragment.name(), Stage::Compute.name()],
        ["fragment", "compute"]
    );
}
