//! The wgpu helpers of a layout (`GBufferTargets`, feature `wgpu`), used as a renderer uses
//! them, with no format or count written here:
//!
//! - on the adapter at hand (lavapipe on CI), a G-buffer pass renders texels into the targets
//!   `create_targets` made, through a pipeline of `color_targets()` and the generated
//!   `pack_<snake>_targets`; a second pass binds them with `bind_group_layout_entries` and
//!   `create_bind_group` and reads them with `lighting_wgsl`'s `read_<snake>_targets`. The
//!   words equal the Rust mirror's bit for bit, and the texels read back its unpack;
//! - `check_limits` says what wgpu's own validation says of the targets, on the adapter's
//!   limits and on `Limits::downlevel_defaults()`, and its error names what is needed against
//!   what is allowed; `required_limits` gives limits that fit.

use gbuffer::glam::{UVec4, Vec3, Vec4};
use gbuffer::seed_layouts::{MobileMetallic, SpecularWorkflow};
use gbuffer::targets::packed_target_formats;
use gbuffer::{wgpu, GBufferLayout, GBufferTargets, LimitError};
use gbuffer_gpu::harness::{scalars_per_texel, scalars_to_output, texel_from_inputs};
use gbuffer_gpu::values::Values;
use gbuffer_gpu::Gpu;
use gbuffer_testkit::texels::{compare, inputs};
use gbuffer_testkit::AllFormats;

/// Nine r32f words, 288 bits: the layout of the limit example.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 288)]
struct NineWords {
    #[pls(r32f)]
    a: f32,
    #[pls(r32f)]
    b: f32,
    #[pls(r32f)]
    c: f32,
    #[pls(r32f)]
    d: f32,
    #[pls(r32f)]
    e: f32,
    #[pls(r32f)]
    f: f32,
    #[pls(r32f)]
    g: f32,
    #[pls(r32f)]
    h: f32,
    #[pls(r32f)]
    i: f32,
}

/// Six words: the last target two words wide.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 192)]
struct SixWords {
    #[pls(rgb10_a2)]
    light: Vec3,
    #[pls(r32f)]
    depth: f32,
    #[pls(rgba8)]
    normal: Vec4,
    #[pls(rgba8)]
    albedo: Vec4,
    #[pls(rgba8ui)]
    material: UVec4,
    #[pls(r11f_g11f_b10f)]
    emissive: Vec3,
}

/// Twenty words: more attachments than the downlevel limits allow.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 640)]
struct TwentyWords {
    #[pls(r32ui)]
    w0: u32,
    #[pls(r32ui)]
    w1: u32,
    #[pls(r32ui)]
    w2: u32,
    #[pls(r32ui)]
    w3: u32,
    #[pls(r32ui)]
    w4: u32,
    #[pls(r32ui)]
    w5: u32,
    #[pls(r32ui)]
    w6: u32,
    #[pls(r32ui)]
    w7: u32,
    #[pls(r32ui)]
    w8: u32,
    #[pls(r32ui)]
    w9: u32,
    #[pls(r32ui)]
    w10: u32,
    #[pls(r32ui)]
    w11: u32,
    #[pls(r32ui)]
    w12: u32,
    #[pls(r32ui)]
    w13: u32,
    #[pls(r32ui)]
    w14: u32,
    #[pls(r32ui)]
    w15: u32,
    #[pls(r32ui)]
    w16: u32,
    #[pls(r32ui)]
    w17: u32,
    #[pls(r32ui)]
    w18: u32,
    #[pls(r32ui)]
    w19: u32,
}

const WIDTH: u32 = 64;
const HEIGHT: u32 = 64;

/// The G-buffer pass: a fullscreen triangle whose fragments pack the texel of their pixel.
fn gbuffer_pass_wgsl<T: GBufferTargets>() -> String {
    let layout = T::layout();
    let symbols = layout.symbols();
    let scalars = scalars_per_texel(&layout);
    format!(
        "{wgsl}\n\
         @group(0) @binding(0) var<storage, read> harness_inputs: array<u32>;\n\n\
         @vertex\nfn harness_vertex(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {{\n    \
         let corner = vec2<f32>(f32((vertex << 1u) & 2u), f32(vertex & 2u));\n    \
         return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);\n}}\n\n\
         @fragment\nfn harness_fragment(@builtin(position) position: vec4<f32>) -> {targets} {{\n    \
         let base = (u32(position.y) * {WIDTH}u + u32(position.x)) * {scalars}u;\n\
         {texel}    return {pack_targets}(texel);\n}}\n",
        wgsl = T::WGSL,
        targets = symbols.targets(),
        pack_targets = symbols.pack_targets(),
        texel = texel_from_inputs(&layout),
    )
}

/// The reading pass: per pixel, the words as stored and the texel `read_<snake>_targets`
/// unpacks, into a storage buffer after the targets' bindings.
fn reading_pass_wgsl<T: GBufferTargets>() -> String {
    let layout = T::layout();
    let symbols = layout.symbols();
    let words = layout.words();
    let stride = words + scalars_per_texel(&layout);
    let output_binding = T::TARGET_FORMATS.len();
    let mut raw = String::new();
    for word in 0..words {
        raw.push_str(&format!(
            "    harness_output[base + {word}u] = textureLoad({}, id.xy, 0)[{}];\n",
            symbols.target(word / 4),
            word % 4
        ));
    }
    format!(
        "{wgsl}\n{bindings}\n\
         @group(0) @binding({output_binding}) var<storage, read_write> harness_output: array<u32>;\n\n\
         @compute @workgroup_size(8, 8)\nfn harness_read(@builtin(global_invocation_id) id: vec3<u32>) {{\n    \
         let base = (id.y * {WIDTH}u + id.x) * {stride}u;\n{raw}    \
         let texel = {read_targets}(id.xy);\n{decoded}}}\n",
        wgsl = T::WGSL,
        read_targets = symbols.read_targets(),
        bindings = T::lighting_wgsl(0, 0),
        decoded = scalars_to_output(&layout, "texel", "harness_output", &format!("base + {words}u")),
    )
}

/// Renders the texels of `inputs` into the layout's targets and reads them back through the
/// helpers: per texel, the words and the decoded scalars.
fn render_and_read<T: GBufferTargets>(gpu: &Gpu, inputs: &[u32]) -> Vec<u32> {
    let device = &gpu.device;
    let layout = T::layout();
    let stride = layout.words() + scalars_per_texel(&layout);
    let texels = (WIDTH * HEIGHT) as usize;
    let storage = |contents: &[u32], usage| gpu.buffer_of(contents, usage);
    let input_buffer = storage(inputs, wgpu::BufferUsages::STORAGE);
    let output_buffer = storage(
        &vec![0xdead_beef; texels * stride],
        wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    );
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: (texels * stride * 4) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });

    let targets = T::create_targets(device, WIDTH, HEIGHT, wgpu::TextureUsages::empty());
    let gbuffer_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("G-buffer pass"),
        source: wgpu::ShaderSource::Wgsl(gbuffer_pass_wgsl::<T>().into()),
    });
    let colour_targets = T::color_targets();
    let gbuffer_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("G-buffer pass"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &gbuffer_module,
            entry_point: Some("harness_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &gbuffer_module,
            entry_point: Some("harness_fragment"),
            compilation_options: Default::default(),
            targets: &colour_targets,
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    let input_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &gbuffer_pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: input_buffer.as_entire_binding(),
        }],
    });

    let mut entries = T::bind_group_layout_entries(0, wgpu::ShaderStages::COMPUTE);
    entries.push(wgpu::BindGroupLayoutEntry {
        binding: entries.len() as u32,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: false },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    });
    let reading_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("reading pass"),
        entries: &entries,
    });
    let mut group_entries = T::bind_group_entries(0, &targets);
    group_entries.push(wgpu::BindGroupEntry {
        binding: group_entries.len() as u32,
        resource: output_buffer.as_entire_binding(),
    });
    let reading_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("reading pass"),
        layout: &reading_layout,
        entries: &group_entries,
    });
    let reading_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("reading pass"),
        source: wgpu::ShaderSource::Wgsl(reading_pass_wgsl::<T>().into()),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&reading_layout)],
        immediate_size: 0,
    });
    let reading_pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("reading pass"),
        layout: Some(&pipeline_layout),
        module: &reading_module,
        entry_point: Some("harness_read"),
        compilation_options: Default::default(),
        cache: None,
    });

    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let attachments = targets.color_attachments(wgpu::Color::TRANSPARENT);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("G-buffer pass"),
            color_attachments: &attachments,
            ..Default::default()
        });
        pass.set_pipeline(&gbuffer_pipeline);
        pass.set_bind_group(0, &input_group, &[]);
        pass.draw(0..3, 0..1);
    }
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&reading_pipeline);
        pass.set_bind_group(0, &reading_group, &[]);
        pass.dispatch_workgroups(WIDTH / 8, HEIGHT / 8, 1);
    }
    encoder.copy_buffer_to_buffer(&output_buffer, 0, &readback, 0, None);
    gpu.queue.submit([encoder.finish()]);
    readback.slice(..).map_async(wgpu::MapMode::Read, |result| {
        result.expect("mapping the readback buffer")
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("the device finishes");
    let mapped = readback
        .slice(..)
        .get_mapped_range()
        .expect("the readback buffer is mapped");
    bytemuck::cast_slice(&mapped).to_vec()
}

/// Renders and reads back one layout; pushes mismatches with the mirror onto `failures`.
fn check_round_trip<T: GBufferTargets>(gpu: &Gpu, seed: u64, failures: &mut Vec<String>) {
    let layout = T::layout();
    if let Err(error) = T::check_limits(&gpu.device.limits()) {
        failures.push(format!("{}: {error}", layout.name));
        return;
    }
    let texels = (WIDTH * HEIGHT) as usize;
    let inputs = inputs(&layout, 0, texels, &mut Values::new(seed));
    let output = render_and_read::<T>(gpu, &inputs);
    let stride = layout.words() + scalars_per_texel(&layout);
    let (words, decoded): (Vec<u32>, Vec<u32>) = {
        let (mut words, mut decoded) = (Vec::new(), Vec::new());
        for texel in output.chunks_exact(stride) {
            words.extend_from_slice(&texel[..layout.words()]);
            decoded.extend_from_slice(&texel[layout.words()..]);
        }
        (words, decoded)
    };
    let what = format!("{:?}", T::TARGET_FORMATS);
    compare(
        &what,
        &layout,
        &inputs,
        Some(&words),
        Some(&decoded),
        failures,
        12,
    );
}

#[test]
fn targets_made_by_the_helpers_round_trip_bit_exactly_on_the_adapter() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let mut failures = Vec::new();
    check_round_trip::<MobileMetallic>(&gpu, 1, &mut failures);
    check_round_trip::<SpecularWorkflow>(&gpu, 2, &mut failures);
    check_round_trip::<SixWords>(&gpu, 3, &mut failures);
    check_round_trip::<NineWords>(&gpu, 4, &mut failures);
    check_round_trip::<AllFormats>(&gpu, 5, &mut failures);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn target_formats_follow_the_words() {
    use wgpu::TextureFormat::{R32Uint, Rg32Uint, Rgba32Uint};
    assert_eq!(MobileMetallic::TARGET_FORMATS, &[Rgba32Uint]);
    assert_eq!(SpecularWorkflow::TARGET_FORMATS, &[Rgba32Uint, R32Uint]);
    assert_eq!(SixWords::TARGET_FORMATS, &[Rgba32Uint, Rg32Uint]);
    assert_eq!(
        NineWords::TARGET_FORMATS,
        &[Rgba32Uint, Rgba32Uint, R32Uint]
    );
    assert_eq!(NineWords::bytes_per_sample(), 36);
    // The formats, and the bytes wgpu counts for them, are the ones the layout model reports.
    for words in 1..=64 {
        let formats = packed_target_formats(words);
        let names: Vec<String> = formats
            .iter()
            .map(|format| format!("{format:?}").to_lowercase())
            .collect();
        let layout = gbuffer::layout::Layout {
            name: "Words".into(),
            budget: 32 * words as u32,
            fields: vec![NineWords::layout().fields[0].clone(); words],
        };
        assert_eq!(names, layout.packed_target_formats(), "{words} words");
        let wgpu_bytes = formats.iter().fold(0, |total: u32, format| {
            total.next_multiple_of(format.target_component_alignment().unwrap())
                + format.target_pixel_byte_cost().unwrap()
        });
        assert_eq!(wgpu_bytes, layout.packed_target_bytes(), "{words} words");
    }
}

#[test]
fn limit_errors_name_what_is_needed_against_what_is_allowed() {
    let downlevel = wgpu::Limits::downlevel_defaults();
    assert_eq!(MobileMetallic::check_limits(&downlevel), Ok(()));
    let nine = NineWords::check_limits(&downlevel).unwrap_err();
    assert_eq!(
        nine,
        LimitError {
            layout: "NineWords".into(),
            attachments: 3,
            max_attachments: downlevel.max_color_attachments,
            bytes_per_sample: 36,
            max_bytes_per_sample: 32,
        }
    );
    assert_eq!(
        nine.to_string(),
        format!(
            "G-buffer layout `NineWords` needs 3 colour attachments (max_color_attachments allows \
             {}) and 36 bytes per sample (max_color_attachment_bytes_per_sample allows 32): \
             request the layout's required_limits from an adapter that offers them, or shrink \
             the layout",
            downlevel.max_color_attachments
        )
    );
    let twenty = TwentyWords::check_limits(&downlevel)
        .unwrap_err()
        .to_string();
    assert!(
        twenty.contains(&format!(
            "needs 5 colour attachments (max_color_attachments allows {}) and 80 bytes per sample",
            downlevel.max_color_attachments
        )),
        "{twenty}"
    );
    let raised = NineWords::required_limits(downlevel.clone());
    assert_eq!(raised.max_color_attachment_bytes_per_sample, 36);
    assert_eq!(NineWords::check_limits(&raised), Ok(()));
    assert_eq!(
        TwentyWords::check_limits(&TwentyWords::required_limits(downlevel)),
        Ok(())
    );
}

/// WebGL2's limits (wgpu's `downlevel_webgl2_defaults`): the report's WebGL2 line says what
/// `check_limits` says, with the constants it prints being wgpu's.
#[test]
fn the_report_says_what_webgl2_allows() {
    use gbuffer::layout::Report;
    use gbuffer_core::report::{WEBGL2_COLOR_ATTACHMENT_LIMIT, WEBGPU_BYTES_PER_SAMPLE_LIMIT};
    let webgl2 = wgpu::Limits::downlevel_webgl2_defaults();
    assert_eq!(
        webgl2.max_color_attachments as usize,
        WEBGL2_COLOR_ATTACHMENT_LIMIT
    );
    assert_eq!(
        webgl2.max_color_attachment_bytes_per_sample,
        WEBGPU_BYTES_PER_SAMPLE_LIMIT
    );
    let verdicts = [
        (
            MobileMetallic::layout(),
            MobileMetallic::check_limits(&webgl2).is_ok(),
        ),
        (
            NineWords::layout(),
            NineWords::check_limits(&webgl2).is_ok(),
        ),
        (
            TwentyWords::layout(),
            TwentyWords::check_limits(&webgl2).is_ok(),
        ),
    ];
    for (layout, fits) in verdicts {
        let line = Report::new(&layout).webgl2();
        assert_eq!(line.contains("fit ("), fits, "{}: {line}", layout.name);
    }
    let twenty = Report::new(&TwentyWords::layout()).webgl2();
    assert!(
        twenty.contains("5 colour attachments, over max_color_attachments 4")
            && twenty
                .contains("80 bytes per sample, over max_color_attachment_bytes_per_sample 32"),
        "{twenty}"
    );
}

/// Whether wgpu accepts a G-buffer pipeline of `T`'s colour targets on `gpu`.
fn wgpu_accepts_targets<T: GBufferTargets>(gpu: &Gpu) -> bool {
    let device = &gpu.device;
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(gbuffer_pass_wgsl::<T>().into()),
    });
    let _ = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: None,
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("harness_vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("harness_fragment"),
            compilation_options: Default::default(),
            targets: &T::color_targets(),
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    pollster::block_on(scope.pop()).is_none()
}

#[test]
fn check_limits_agrees_with_wgpu_validation_under_downlevel_limits() {
    let Some(gpu) = gbuffer_testkit::gpu_with(
        Some(wgpu::Limits::downlevel_defaults()),
        wgpu::Features::empty(),
    ) else {
        return;
    };
    let limits = gpu.device.limits();
    for (name, predicted, accepted) in [
        (
            "MobileMetallic",
            MobileMetallic::check_limits(&limits).is_ok(),
            wgpu_accepts_targets::<MobileMetallic>(&gpu),
        ),
        (
            "NineWords",
            NineWords::check_limits(&limits).is_ok(),
            wgpu_accepts_targets::<NineWords>(&gpu),
        ),
        (
            "SixWords",
            SixWords::check_limits(&limits).is_ok(),
            wgpu_accepts_targets::<SixWords>(&gpu),
        ),
    ] {
        assert_eq!(
            predicted, accepted,
            "{name}: check_limits and wgpu disagree"
        );
    }
    assert!(NineWords::check_limits(&limits).is_err());
}
