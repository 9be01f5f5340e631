//! The fused Vulkan paths' pipelines, exactly as the renderer creates them (its SPIR-V, its
//! attachments, input attachments, vertex attributes and push constants), built by the
//! production compilers of GPUs that take SPIR-V, through the cost model's helper under Mesa's
//! drm-shim, for each pass they are drawn in: the subpass path's render pass object, a dynamic
//! rendering read through local read (`local-read`), and local read in rasterization order
//! (`local-read-ordered`).
//!
//! - turnip (Adreno 630 and 740) builds all three;
//! - RADV/ACO (AMD navi21) builds the first two and refuses the third: it offers no
//!   rasterization-order attachment access;
//! - panvk (Mali-G610, Mesa 25.0) is not among the cost model's targets (Mesa calls it a broken
//!   driver and it reports no instruction counts): it builds the subpass path's sky and refuses
//!   local read, its Vulkan being older than 1.3.
//!
//! The helper gives each vertex attribute a binding of its own, read per vertex: the renderer
//! reads the volume index per instance, which changes the vertex stage's fetch, not the
//! fragment stage. A refusal is the helper's one-line reason, held here to what each driver
//! offers. Each compiler turns a stage into as many instructions for every pass it builds.

use ash::vk;
use gbuffer_core::Named;
use gbuffer_cost::{measure, Api, Architecture, Compiler, Rendering, Shader, Target, VulkanForm};
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::on_tile::Stage;
use gbuffer_render::options::{IblForm, Options, SunForm};
use gbuffer_render::vulkan::fused_pipelines::{
    fused_pipelines, FusedPipeline, PUSH_CONSTANT_BYTES,
};

const RENDERINGS: [Rendering; 3] = [
    Rendering::RenderPass,
    Rendering::LocalRead,
    Rendering::LocalReadOrdered,
];

fn pipelines() -> Vec<FusedPipeline> {
    let options = Options {
        gbuffer: GBuffer::Packed(PackedLayout::MobileMetallic),
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width: 64,
        height: 64,
    };
    let pipelines = fused_pipelines(&options).expect("the fused pipelines build");
    assert_eq!(pipelines.len(), Stage::ALL.len());
    pipelines
}

/// The helper's name of a format the fused pipelines use.
fn format_name(format: vk::Format) -> String {
    let name = match format {
        vk::Format::R32G32B32A32_UINT => "rgba32ui",
        vk::Format::R8G8B8A8_UNORM => "rgba8",
        vk::Format::R32G32B32_SFLOAT => "rgb32f",
        vk::Format::R32_UINT => "r32ui",
        other => panic!("the helper has no name for {other:?}"),
    };
    name.to_string()
}

fn words(spirv: &[u8]) -> Vec<u32> {
    bytemuck::pod_collect_to_vec(spirv)
}

/// The helper's form of `pipeline`, created for `rendering`: set 0's combined image samplers,
/// set 1's input attachments (index `i` reading colour `i` under local read).
fn form(pipeline: &FusedPipeline, rendering: Rendering) -> VulkanForm {
    let sampled = (pipeline.sampled.iter()).map(|binding| format!("0,{binding},combined"));
    let inputs =
        (0..pipeline.input_attachments).map(|binding| format!("1,{binding},input-attachment"));
    VulkanForm {
        shader: words(&pipeline.fragment),
        entry: "main".into(),
        vertex: Some(words(&pipeline.vertex)),
        vertex_entry: Some(pipeline.stage.vertex_entry().into()),
        descriptors: sampled.chain(inputs).collect(),
        colors: pipeline
            .colour_formats
            .iter()
            .copied()
            .map(format_name)
            .collect(),
        attributes: (pipeline.vertex_attributes.iter().copied())
            .map(format_name)
            .collect(),
        push_constant_bytes: PUSH_CONSTANT_BYTES,
        rendering,
    }
}

#[test]
fn turnip_and_radv_build_every_fused_pipeline_for_each_pass() {
    if !gbuffer_testkit::compilers_set_up() {
        return;
    }
    let pipelines = pipelines();
    // Each target, and the reason it refuses a rendering (none: it builds all three).
    let radv_refuses = "rasterization-order attachment access is not offered: the device lacks \
                        VK_EXT_rasterization_order_attachment_access (and ARM's)";
    let targets = [
        ("adreno-630-vulkan", None),
        ("adreno-740-vulkan", None),
        (
            "amd-navi21",
            Some((Rendering::LocalReadOrdered, radv_refuses)),
        ),
    ];
    for (name, refusal) in targets {
        let target = Target::named(name).unwrap();
        let shaders: Vec<Shader> = RENDERINGS
            .iter()
            .flat_map(|&rendering| {
                (pipelines.iter()).map(move |pipeline| Shader::spirv(form(pipeline, rendering)))
            })
            .collect();
        let results = measure(&shaders, &target, false).unwrap_or_else(|error| panic!("{error}"));
        assert_eq!(results.len(), shaders.len());
        let asked = RENDERINGS
            .iter()
            .flat_map(|rendering| pipelines.iter().map(move |pipeline| (rendering, pipeline)));
        // Each stage's instruction counts (fragment, vertex) on the first pass it was built for.
        let mut first: Vec<Option<(u64, u64)>> = vec![None; pipelines.len()];
        for (index, ((&rendering, pipeline), result)) in asked.zip(results).enumerate() {
            let what = format!("{name}, {} on {}", pipeline.stage.name(), rendering.name());
            match (result, refusal) {
                (Err(error), Some((refused, reason))) if refused == rendering => {
                    assert_eq!(error, reason, "{what}")
                }
                (Ok(_), Some((refused, _))) if refused == rendering => {
                    panic!("{what}: built where the driver offers no rasterization order")
                }
                (Ok(measurement), _) => {
                    let vertex = measurement
                        .vertex
                        .unwrap_or_else(|| panic!("{what}: no vertex stage's statistics"));
                    let instructions = (measurement.statistics.instructions, vertex.instructions);
                    eprintln!("{what}: {instructions:?} instructions (fragment, vertex)");
                    assert!(instructions.0 > 0 && instructions.1 > 0, "{what}");
                    // The shaders are the same on every pass; so is their code, in both stages.
                    let stage = &mut first[index % pipelines.len()];
                    assert_eq!(*stage.get_or_insert(instructions), instructions, "{what}");
                }
                (Err(error), _) => panic!("{what}: {error}"),
            }
        }
    }
}

#[test]
fn panvk_builds_the_subpass_sky_and_refuses_local_read() {
    if !gbuffer_testkit::compilers_set_up() {
        return;
    }
    let panvk = Target {
        name: "mali-g610-panvk",
        gpu: "Mali-G610",
        api: Api::Vulkan,
        compiler: Compiler::Valhall,
        architecture: Architecture::Aarch64,
        shim: "libpanfrost_noop_drm_shim.so",
        environment: &[
            ("PAN_GPU_ID", "a867"),
            ("PAN_I_WANT_A_BROKEN_VULKAN_DRIVER", "1"),
            (
                "VK_ICD_FILENAMES",
                "/usr/share/vulkan/icd.d/panfrost_icd.json",
            ),
        ],
        expected_device: "Mali-G610",
    };
    let sky = pipelines()
        .into_iter()
        .find(|pipeline| pipeline.stage == Stage::Sky)
        .expect("a sky stage");
    let folder = tempfile::tempdir().unwrap();
    let mut arguments = Vec::new();
    for rendering in [Rendering::RenderPass, Rendering::LocalRead] {
        let form = form(&sky, rendering);
        let path = |name: &str| folder.path().join(format!("{}.{name}", rendering.name()));
        let (fragment, vertex) = (path("frag.spv"), path("vert.spv"));
        std::fs::write(&fragment, bytemuck::cast_slice(&form.shader)).unwrap();
        std::fs::write(&vertex, bytemuck::cast_slice(&form.vertex.unwrap())).unwrap();
        if !arguments.is_empty() {
            arguments.push("--".to_string());
        }
        arguments.extend(["fragment".into(), fragment.display().to_string()]);
        arguments.push(vertex.display().to_string());
        arguments.extend(["--vertex-entry".into(), form.vertex_entry.unwrap()]);
        for descriptor in form.descriptors {
            arguments.extend(["--descriptor".into(), descriptor]);
        }
        for color in form.colors {
            arguments.extend(["--color".into(), color]);
        }
        arguments.extend(["--push-constants".into(), PUSH_CONSTANT_BYTES.to_string()]);
        arguments.extend(["--rendering".into(), rendering.name().into()]);
    }
    let mut all = vec!["vulkan"];
    all.extend(arguments.iter().map(String::as_str));
    let output = gbuffer_testkit::shader_stats_by_hand(&panvk, &all);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}");
    assert!(stdout.contains("device: Mali-G610"), "{stdout}");
    let (subpass, local_read) = stdout
        .split_once("shader: 1")
        .expect("a section a pipeline");
    assert!(subpass.contains("executable: fragment"), "{stdout}");
    assert_eq!(
        local_read.trim(),
        "error: local read is not offered: the device's Vulkan is older than 1.3 (dynamic \
         rendering)"
    );
}
