//! The Vulkan subpass-input includes on a real driver (Mesa's lavapipe through `ash`), exactly as
//! generated: each include is pasted unedited into small user shaders under every preamble its
//! header allows, compiled with glslangValidator, and run in one render pass of three
//! subpasses over transient attachments, as a tiler keeps a G-buffer:
//!
//! - subpass 0 builds texels from input scalars (edge cases first, then random values) and
//!   writes them to G-buffer A with the include's pack functions;
//! - subpass 1 reads A as input attachments with `load_<layout>()`, writes A's words and each
//!   decoded field to a storage buffer, and writes the texel again to G-buffer B;
//! - subpass 2 reads B and writes its words.
//!
//! The attachments are never stored: the storage buffer is all that leaves the pass. A's words
//! equal the Rust mirror's bit for bit, B's equal A's (store(load()) changes no bit), and the
//! decoded fields equal the mirror's unpack. For the seed layouts, a layout of every format and
//! layouts generated at random (with names GLSL reserves), for the packed include and the
//! native one (one attachment per field in its own format, converted by the driver).

use std::collections::BTreeSet;

use ash::vk;
use gbuffer::layout::Layout;
use gbuffer_codegen::emit::glsl::{self, Include, Interface};
use gbuffer_codegen::CompiledLayout;
use gbuffer_core::Conversions;
use gbuffer_gpu::fullscreen::fullscreen_vertex_glsl;
use gbuffer_gpu::harness::scalars_per_texel;
use gbuffer_gpu::tools::glslang;
use gbuffer_gpu::values::Values;
use gbuffer_gpu::vulkan::{AttachmentMemory, Resource, Subpass, Vulkan};
use gbuffer_testkit::or_skip;
use gbuffer_testkit::texels::{
    check_native_words, compare, compare_decoded, inputs, restore_changes, word_from_components,
};
use gbuffer_testkit::user_shaders::{preambles, scalars_of_texel, texel_from_scalars};
use proptest::prelude::*;

const WIDTH: u32 = 48;
const HEIGHT: u32 = 48;

fn vulkan() -> Option<Vulkan> {
    or_skip("Vulkan", Vulkan::new())
}

/// Where each texel's results sit in the output buffer: what subpass 1 read from G-buffer A
/// (four components per attachment, as bits), the decoded scalars, what subpass 2 read from B.
struct OutputLayout {
    components: usize,
    scalars: usize,
}

impl OutputLayout {
    fn of(layout: &Layout, interface: &Interface) -> OutputLayout {
        OutputLayout {
            components: 4 * interface.attachments.len(),
            scalars: scalars_per_texel(layout),
        }
    }

    fn stride(&self) -> usize {
        2 * self.components + self.scalars
    }

    /// A's words, the decoded scalars and B's words of every texel, each run end to end.
    fn split(
        &self,
        layout: &Layout,
        interface: &Interface,
        outputs: &[u32],
    ) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
        let (mut first, mut decoded, mut second) = (Vec::new(), Vec::new(), Vec::new());
        for texel in outputs.chunks_exact(self.stride()) {
            let (read_first, rest) = texel.split_at(self.components);
            let (scalars, read_second) = rest.split_at(self.scalars);
            first.extend(words(layout, interface, read_first));
            decoded.extend_from_slice(scalars);
            second.extend(words(layout, interface, read_second));
        }
        (first, decoded, second)
    }
}

/// A texel's words from the components read from its attachments: the packed words as they
/// are, or each native attachment's word from its channels.
fn words(layout: &Layout, interface: &Interface, components: &[u32]) -> Vec<u32> {
    if interface.include.is_packed() {
        components[..layout.words()].to_vec()
    } else {
        layout
            .word_contents()
            .iter()
            .zip(components.chunks_exact(4))
            .map(|(word, components)| word_from_components(word.format, components))
            .collect()
    }
}

/// The three fragment shaders of the user's render pass for `include` under `preamble`.
struct UserShaders {
    store: String,
    reload: String,
    verify: String,
}

fn user_shaders(layout: &Layout, include: Include, preamble: &str) -> UserShaders {
    let compiled = CompiledLayout::new(layout, Conversions::Exact).unwrap();
    let (text, interface) = glsl::include(&compiled, include, 0).unwrap();
    let names = compiled.names();
    let output = OutputLayout::of(layout, &interface);
    let stride = output.stride();
    let common = format!(
        "{preamble}{text}\n// The user's code.\n\
         layout(std430, set = 1, binding = 0) readonly buffer HarnessInputs {{\n    highp uint harness_inputs[];\n}};\n\
         layout(std430, set = 1, binding = 1) buffer HarnessOutputs {{\n    highp uint harness_outputs[];\n}};\n\n\
         highp int harness_texel() {{\n    highp ivec2 pixel = ivec2(gl_FragCoord.xy);\n    return pixel.y * {WIDTH} + pixel.x;\n}}\n"
    );
    let writer = gbuffer_writer(&compiled, &interface);
    let reads = attachment_reader(&interface);
    let load = layout.symbols().load();
    let scalars = output.scalars;
    let texel = texel_from_scalars(layout, names, |index| {
        format!("harness_inputs[base + {index}]")
    });
    let store = format!(
        "{common}{writer}\nvoid main() {{\n    highp int base = harness_texel() * {scalars};\n    harness_store({texel});\n}}\n"
    );
    let mut reload = format!(
        "{common}{writer}{reads}\nvoid main() {{\n    {} texel = {load}();\n    \
         highp int base = harness_texel() * {stride};\n    harness_write_attachments(base);\n",
        names.layout
    );
    for (index, scalar) in scalars_of_texel(layout, names, "texel").iter().enumerate() {
        reload.push_str(&format!(
            "    harness_outputs[base + {}] = {scalar};\n",
            output.components + index
        ));
    }
    reload.push_str("    harness_store(texel);\n}\n");
    let verify = format!(
        "{common}{reads}\nvoid main() {{\n    harness_write_attachments(harness_texel() * {stride} + {});\n}}\n",
        output.components + output.scalars
    );
    UserShaders {
        store,
        reload,
        verify,
    }
}

/// The user's colour outputs over the G-buffer attachments and `harness_store(texel)`, which
/// writes a texel to them with the statements the fetch include's `store_<layout>()` has.
fn gbuffer_writer(compiled: &CompiledLayout, interface: &Interface) -> String {
    let mut out = String::new();
    for attachment in &interface.attachments {
        out.push_str(&format!(
            "layout(location = {}) out highp {} harness_gbuffer{};\n",
            attachment.index, attachment.format.glsl_type, attachment.index
        ));
    }
    out.push_str(&format!(
        "\nvoid harness_store({} texel) {{\n",
        compiled.names().layout
    ));
    out.push_str(&glsl::store_statements(compiled, interface, |attachment| {
        format!("harness_gbuffer{}", attachment.index)
    }));
    out.push_str("}\n");
    out
}

/// `harness_write_attachments(base)`: the four components of every input attachment, as
/// bits, into the output buffer: what the previous subpass left there, before any conversion
/// of the include's.
fn attachment_reader(interface: &Interface) -> String {
    let mut out = String::from("\nvoid harness_write_attachments(highp int base) {\n");
    for attachment in &interface.attachments {
        let index = attachment.index;
        let bits = match attachment.format.glsl_type {
            "vec4" => "floatBitsToUint",
            "ivec4" => "uvec4",
            _ => "",
        };
        out.push_str(&format!(
            "    highp uvec4 attachment{index} = {bits}(subpassLoad({}));\n",
            attachment.name
        ));
        for component in 0..4 {
            out.push_str(&format!(
                "    harness_outputs[base + {}] = attachment{index}.{};\n",
                index as usize * 4 + component,
                &"xyzw"[component..component + 1]
            ));
        }
    }
    out.push_str("}\n");
    out
}

/// Compiles a shader to a module, or says which shader failed and why.
fn module(vulkan: &Vulkan, source: &str, stage: &str, what: &str) -> vk::ShaderModule {
    let spirv = glslang(source, stage, true).unwrap_or_else(|log| panic!("{what}: {log}"));
    vulkan
        .shader_module(&spirv)
        .unwrap_or_else(|error| panic!("{what}: {error}"))
}

/// Runs the render pass of `include` for `layout` under `preamble`; pushes mismatches onto
/// `failures` and returns the memory the attachments got. Prints why and returns `None` when
/// the device cannot hold the layout's attachments.
fn check(
    vulkan: &Vulkan,
    layout: &Layout,
    include: Include,
    preamble: &str,
    seed: u64,
    failures: &mut Vec<String>,
) -> Option<AttachmentMemory> {
    let compiled = CompiledLayout::new(layout, Conversions::Exact).unwrap();
    let (_, interface) = glsl::include(&compiled, include, 0).unwrap();
    let count = interface.attachments.len();
    let limits = &vulkan.limits;
    let most = limits
        .max_color_attachments
        .min(limits.max_per_stage_descriptor_input_attachments) as usize;
    let formats: Vec<vk::Format> = interface
        .attachments
        .iter()
        .map(|attachment| vk::Format::from_raw(attachment.format.vulkan.format))
        .collect();
    if count > most {
        eprintln!(
            "{}: {include:?} needs {count} attachments; the device has {most}",
            layout.name
        );
        return None;
    }
    if let Some(format) = formats.iter().find(|&&format| !vulkan.renders_to(format)) {
        failures.push(format!(
            "{}: {include:?}: the device cannot render to {format:?}",
            layout.name
        ));
        return None;
    }
    let what = format!(
        "{} {include:?} under {:?}",
        layout.name,
        preamble.replace('\n', " ")
    );
    let shaders = user_shaders(layout, include, preamble);
    let vertex_shader = fullscreen_vertex_glsl("#version 450", true);
    let vertex = module(vulkan, &vertex_shader, "vert", "the vertex shader");
    let store = module(vulkan, &shaders.store, "frag", &what);
    let reload = module(vulkan, &shaders.reload, "frag", &what);
    let verify = module(vulkan, &shaders.verify, "frag", &what);

    let run = || -> Result<(Vec<u32>, Vec<u32>, AttachmentMemory), String> {
        // G-buffer A is attachments 0..count, B is count..2 count.
        let mut views = Vec::new();
        let mut memory = AttachmentMemory::LazilyAllocated;
        for &format in formats.iter().chain(&formats) {
            let (view, kind) = vulkan.transient_attachment(format, WIDTH, HEIGHT)?;
            if kind == AttachmentMemory::DeviceLocal {
                memory = kind;
            }
            views.push(view);
        }
        let all_formats: Vec<vk::Format> = formats.iter().chain(&formats).copied().collect();
        let a: Vec<u32> = (0..count as u32).collect();
        let b: Vec<u32> = (count as u32..2 * count as u32).collect();
        let render_pass = vulkan.render_pass(
            &all_formats,
            &[
                Subpass {
                    inputs: vec![],
                    colours: a.clone(),
                },
                Subpass {
                    inputs: a,
                    colours: b.clone(),
                },
                Subpass {
                    inputs: b,
                    colours: vec![],
                },
            ],
        )?;
        let framebuffer = vulkan.framebuffer(render_pass, &views, WIDTH, HEIGHT)?;

        let output = OutputLayout::of(layout, &interface);
        let texels = (WIDTH * HEIGHT) as usize;
        let inputs = inputs(layout, 0, texels, &mut Values::new(seed));
        let input_buffer = vulkan.storage_buffer(inputs.len())?;
        vulkan.write_buffer(&input_buffer, &inputs)?;
        // Every output word starts as a value no path writes, so a texel the shaders skip
        // cannot pass for a zero word.
        let output_buffer = vulkan.storage_buffer(texels * output.stride())?;
        vulkan.write_buffer(&output_buffer, &vec![0xdead_beef; texels * output.stride()])?;

        let gbuffer_set_layout =
            vulkan.descriptor_set_layout(&vec![vk::DescriptorType::INPUT_ATTACHMENT; count])?;
        let buffers_set_layout =
            vulkan.descriptor_set_layout(&[vk::DescriptorType::STORAGE_BUFFER; 2])?;
        let pipeline_layout =
            vulkan.pipeline_layout(&[gbuffer_set_layout, buffers_set_layout], None)?;
        let input_attachments = |views: &[vk::ImageView]| -> Vec<Resource> {
            views
                .iter()
                .map(|&view| Resource::InputAttachment(view))
                .collect()
        };
        let a_set =
            vulkan.descriptor_set(gbuffer_set_layout, &input_attachments(&views[..count]))?;
        let b_set =
            vulkan.descriptor_set(gbuffer_set_layout, &input_attachments(&views[count..]))?;
        let buffers_set = vulkan.descriptor_set(
            buffers_set_layout,
            &[
                Resource::StorageBuffer(input_buffer.buffer),
                Resource::StorageBuffer(output_buffer.buffer),
            ],
        )?;
        let size = (WIDTH, HEIGHT);
        let pipelines = [
            vulkan.fullscreen_pipeline(
                render_pass,
                0,
                pipeline_layout,
                vertex,
                store,
                count,
                size,
            )?,
            vulkan.fullscreen_pipeline(
                render_pass,
                1,
                pipeline_layout,
                vertex,
                reload,
                count,
                size,
            )?,
            vulkan.fullscreen_pipeline(render_pass, 2, pipeline_layout, vertex, verify, 0, size)?,
        ];
        vulkan.submit_and_wait(|device, commands| {
            let graphics = vk::PipelineBindPoint::GRAPHICS;
            // SAFETY: every handle is alive until `release`; the sets match the layout.
            unsafe {
                device.cmd_begin_render_pass(
                    commands,
                    &vk::RenderPassBeginInfo::default()
                        .render_pass(render_pass)
                        .framebuffer(framebuffer)
                        .render_area(vk::Rect2D {
                            offset: vk::Offset2D { x: 0, y: 0 },
                            extent: vk::Extent2D {
                                width: WIDTH,
                                height: HEIGHT,
                            },
                        }),
                    vk::SubpassContents::INLINE,
                );
                device.cmd_bind_descriptor_sets(
                    commands,
                    graphics,
                    pipeline_layout,
                    1,
                    &[buffers_set],
                    &[],
                );
                for (subpass, pipeline) in pipelines.iter().enumerate() {
                    if subpass > 0 {
                        device.cmd_next_subpass(commands, vk::SubpassContents::INLINE);
                        let gbuffer = [a_set, b_set][subpass - 1];
                        device.cmd_bind_descriptor_sets(
                            commands,
                            graphics,
                            pipeline_layout,
                            0,
                            &[gbuffer],
                            &[],
                        );
                    }
                    device.cmd_bind_pipeline(commands, graphics, *pipeline);
                    device.cmd_draw(commands, 3, 1, 0, 0);
                }
                device.cmd_end_render_pass(commands);
            }
        })?;
        Ok((inputs, vulkan.read_buffer(&output_buffer)?, memory))
    };
    let result = run();
    vulkan.release();
    let (inputs, outputs, memory) = result.unwrap_or_else(|error| panic!("{what}: {error}"));

    let (stored, decoded, reloaded) =
        OutputLayout::of(layout, &interface).split(layout, &interface, &outputs);
    if include.is_packed() {
        compare(
            &what,
            layout,
            &inputs,
            Some(&stored),
            Some(&decoded),
            failures,
            12,
        );
    } else {
        // The driver converts, as on GLES: its words within one code of the mirror on defined
        // inputs, and the shader's decoding equal to the mirror's decoding of those words.
        check_native_words(&what, layout, &inputs, &stored, failures);
        compare_decoded(&what, layout, &stored, &decoded, failures, 24);
    }
    let (changed, _twins) = restore_changes(layout, &stored, &reloaded);
    if changed > 0 {
        failures.push(format!(
            "{what}: store(load()) changed {changed} of {} words",
            stored.len()
        ));
    }
    Some(memory)
}

/// Prints which memory the transient attachments got, as the test's output says.
fn report_memory(vulkan: &Vulkan, memory: &BTreeSet<String>) {
    eprintln!(
        "Vulkan: {}; transient attachments in {}",
        vulkan.describe(),
        memory.iter().cloned().collect::<Vec<_>>().join(" and ")
    );
}

fn memory_name(memory: AttachmentMemory) -> String {
    match memory {
        AttachmentMemory::LazilyAllocated => "LAZILY_ALLOCATED memory".into(),
        AttachmentMemory::DeviceLocal => {
            "DEVICE_LOCAL memory (the device offers no LAZILY_ALLOCATED type for them)".into()
        }
    }
}

/// Every seed layout and layout of every format through `include` under every preamble. Each
/// include is a test of its own, so that the two run on two threads (lavapipe compiles a
/// pipeline on one).
fn round_trips_bit_exactly_under_every_preamble(include: Include) {
    let Some(vulkan) = vulkan() else { return };
    let mut failures = Vec::new();
    let mut memory = BTreeSet::new();
    for (index, layout) in gbuffer_testkit::layouts::seeds_and_every_format()
        .iter()
        .enumerate()
    {
        for preamble in preambles(include) {
            let got = check(
                &vulkan,
                layout,
                include,
                &preamble,
                index as u64,
                &mut failures,
            );
            memory.extend(got.map(memory_name));
        }
    }
    report_memory(&vulkan, &memory);
    assert!(!memory.is_empty(), "no layout ran");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn packed_subpass_include_round_trips_bit_exactly_on_vulkan_under_every_preamble() {
    round_trips_bit_exactly_under_every_preamble(Include::SubpassPacked);
}

#[test]
fn native_subpass_include_round_trips_bit_exactly_on_vulkan_under_every_preamble() {
    round_trips_bit_exactly_under_every_preamble(Include::SubpassNative);
}

/// Bit-field words whose joined names meet: `albedo_1` alone in one word, and `albedo_`, which
/// naga names `albedo_1`, in another, both joined to `albedo_1_bits`. Each word needs its own
/// attachment (the random layouts below found the redefinition this once was).
#[test]
fn bit_field_words_whose_names_meet_get_their_own_attachments() {
    use gbuffer::layout::{BitField, Encoding, Field, FieldType, Format, ScalarKind, Storage};
    let Some(vulkan) = vulkan() else {
        return;
    };
    let float = FieldType::new(ScalarKind::Float, 1);
    let field = |name: &str, storage| Field {
        name: name.into(),
        storage,
        ty: float,
        conversions: None,
    };
    let one_bit = Storage::Bits(BitField {
        bits: 1,
        encoding: Encoding::Unorm,
    });
    let layout = Layout {
        name: "MeetingNames".into(),
        budget: 128,
        fields: vec![
            field("albedo", Storage::Word(Format::R11fG11fB10f)),
            field("albedo_1", one_bit),
            field("field_2", Storage::Word(Format::R11fG11fB10f)),
            field("albedo_", one_bit),
        ],
    };
    let preamble = &preambles(Include::SubpassNative)[0];
    let mut failures = Vec::new();
    check(
        &vulkan,
        &layout,
        Include::SubpassNative,
        preamble,
        11,
        &mut failures,
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, failure_persistence: None, ..ProptestConfig::default() })]

    /// Layouts the repo has never seen, named with words GLSL reserves.
    #[test]
    fn random_layouts_round_trip_bit_exactly_on_vulkan(
        layout in gbuffer_testkit::layouts::random_layout(),
        preamble_index in 0usize..9,
    ) {
        let Some(vulkan) = vulkan() else { return Ok(()) };
        let mut failures = Vec::new();
        for include in [Include::SubpassPacked, Include::SubpassNative] {
            let preambles = preambles(include);
            let preamble = &preambles[preamble_index % preambles.len()];
            check(&vulkan, &layout, include, preamble, 11, &mut failures);
        }
        prop_assert!(failures.is_empty(), "{}", failures.join("\n"));
    }
}
