//! The seed layouts have the sizes their sources state, and the report's WebGPU cost of the
//! same fields as separate render targets is what wgpu itself enforces.

use gbuffer::layout::{Format, Report};
use gbuffer::seed_layouts::{
    ArmTileBlock, FutureMetallic, FutureSpecular, MobileMetallic, SpecularWorkflow,
};
use gbuffer::GBufferLayout;
use gbuffer_gpu::Gpu;

#[test]
fn seed_layouts_have_the_published_bit_counts() {
    // (bits, used bits, words) per layout.
    assert_eq!(
        (
            SpecularWorkflow::BITS,
            SpecularWorkflow::USED_BITS,
            SpecularWorkflow::WORDS
        ),
        (160, 142, 5)
    );
    assert_eq!(
        (
            MobileMetallic::BITS,
            MobileMetallic::USED_BITS,
            MobileMetallic::WORDS
        ),
        (128, 126, 4)
    );
    assert_eq!(
        (FutureMetallic::BITS, FutureMetallic::USED_BITS),
        (256, 256)
    );
    assert_eq!(
        (FutureSpecular::BITS, FutureSpecular::USED_BITS),
        (256, 256)
    );
    assert_eq!((ArmTileBlock::BITS, ArmTileBlock::USED_BITS), (128, 102));
    assert_eq!(SpecularWorkflow::BUDGET, 256);
}

#[test]
fn reports_state_bits_budget_and_target_cost() {
    let text = SpecularWorkflow::report().to_string();
    assert!(
        text.contains("5 words, 160 bits, 142 used, budget 256"),
        "{text}"
    );
    assert!(
        text.contains("total 36 bytes per sample: exceeds the default limit of 32"),
        "{text}"
    );
    assert!(
        text.contains("packed: rgba32uint + r32uint = 20 bytes per sample"),
        "{text}"
    );
}

fn wgpu_format(format: Format) -> wgpu::TextureFormat {
    use wgpu::TextureFormat as T;
    match format {
        Format::R11fG11fB10f => T::Rg11b10Ufloat,
        Format::R32f => T::R32Float,
        Format::Rg16f => T::Rg16Float,
        Format::Rgb10A2 => T::Rgb10a2Unorm,
        Format::Rgba8 => T::Rgba8Unorm,
        Format::Rg16 => T::Rg16Unorm,
        Format::Rgba8i => T::Rgba8Sint,
        Format::Rg16i => T::Rg16Sint,
        Format::Rgb10A2ui => T::Rgb10a2Uint,
        Format::Rgba8ui => T::Rgba8Uint,
        Format::Rg16ui => T::Rg16Uint,
        Format::R32ui => T::R32Uint,
    }
}

/// Creates a render pipeline with one target per field under a 32-byte per-sample limit;
/// wgpu's validation error, if any.
fn wgpu_rejection(gpu: &Gpu, formats: &[Format]) -> Option<String> {
    let outputs: Vec<String> = formats
        .iter()
        .enumerate()
        .map(|(location, format)| {
            format!(
                "@location({location}) o{location}: vec4<{}>,",
                format.scalar_kind().wgsl()
            )
        })
        .collect();
    let shader = format!(
        "struct Outputs {{ {} }}\n\
         {}\n\
         @fragment fn fs() -> Outputs {{ var o: Outputs; return o; }}",
        outputs.join(" "),
        gbuffer_gpu::fullscreen::FULLSCREEN_WGSL
    );
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(shader.into()),
    });
    let targets: Vec<Option<wgpu::ColorTargetState>> = formats
        .iter()
        .map(|&format| Some(wgpu_format(format).into()))
        .collect();
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let _pipeline = gbuffer_gpu::fullscreen::render_pipeline(device, &module, "fs", None, &targets);
    pollster::block_on(scope.pop()).map(|error| error.to_string())
}

#[test]
fn report_cost_matches_wgpu_validation() {
    let limits = wgpu::Limits {
        max_color_attachment_bytes_per_sample: 32,
        ..Default::default()
    };
    let Some(gpu) =
        gbuffer_testkit::gpu_with(Some(limits), wgpu::Features::RG11B10UFLOAT_RENDERABLE)
    else {
        return;
    };
    let features = gpu.device.features();
    for (layout, _) in gbuffer::seed_layouts::all() {
        let formats: Vec<Format> = layout
            .fields
            .iter()
            .filter_map(|field| field.format())
            .collect();
        let report = Report::new(&layout);
        // The formats' features, by the name the report prints.
        let renderable = formats
            .iter()
            .all(|&format| match format.target().webgpu.feature {
                Some("RG11B10UFLOAT_RENDERABLE") => {
                    features.contains(wgpu::Features::RG11B10UFLOAT_RENDERABLE)
                }
                Some(_) => features.contains(wgpu::Features::TEXTURE_FORMAT_16BIT_NORM),
                None => true,
            });
        let within_limit = report.separate_targets_bytes() <= 32;
        let rejection = wgpu_rejection(&gpu, &formats);
        assert_eq!(
            rejection.is_none(),
            within_limit && renderable,
            "{}: the report says {} bytes per sample; wgpu says {rejection:?}",
            layout.name,
            report.separate_targets_bytes()
        );
    }
}
