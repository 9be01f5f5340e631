//! On a real adapter: the generated `pack_`/`unpack_` WGSL against the Rust mirror, over more
//! than a million texels of every format, edge cases first. Packed words must be identical;
//! unpacked values identical too, except unorm channels, which may differ from the exact
//! quotient by 2 ulp (the WGSL multiplies by a correctly rounded reciprocal).

use gbuffer::packing::Layout;
use gbuffer::{seed_layouts, GBufferLayout};
use gbuffer_testkit::gpu::Gpu;
use gbuffer_testkit::harness::{compute_harness, expected_words, scalars_per_texel};
use gbuffer_testkit::texels::{compare, describe, inputs, slots};
use gbuffer_testkit::values::Values;
use gbuffer_testkit::AllFormats;

/// Texels per dispatch, to stay under the default storage binding size.
const BATCH: usize = 1 << 18;

#[test]
fn generated_wgsl_matches_the_rust_mirror_bit_for_bit_on_the_adapter() {
    let gpu = Gpu::new();
    eprintln!("adapter: {}", gpu.describe());
    let mut failures = Vec::new();
    failures.extend(check_layout(
        &gpu,
        &AllFormats::layout(),
        AllFormats::WGSL,
        1 << 20,
        1,
    ));
    for (index, (layout, wgsl)) in seed_layouts::all().into_iter().enumerate() {
        failures.extend(check_layout(
            &gpu,
            &layout,
            wgsl,
            1 << 16,
            100 + index as u64,
        ));
    }
    assert!(
        failures.is_empty(),
        "on {}:\n{}",
        gpu.describe(),
        failures.join("\n")
    );
}

/// Runs `texels` texels of `layout` through the adapter; returns a line per mismatch (the
/// first few of each kind).
fn check_layout(gpu: &Gpu, layout: &Layout, wgsl: &str, texels: usize, seed: u64) -> Vec<String> {
    let harness = compute_harness(layout, wgsl);
    let scalars = scalars_per_texel(layout);
    let words = layout.words();
    let mut values = Values::new(seed);
    let mut failures = Vec::new();
    for first in (0..texels).step_by(BATCH) {
        let count = BATCH.min(texels - first);
        let inputs = inputs(layout, first, count, &mut values);
        let outputs = gpu.run_compute(
            &harness,
            "harness_main",
            &inputs,
            &[count * words, count * scalars],
            count as u32,
        );
        compare(
            "wgpu",
            layout,
            &inputs,
            Some(&outputs[0]),
            Some(&outputs[1]),
            &mut failures,
            20,
        );
    }
    eprintln!(
        "{}: compared {texels} texels ({} scalars, {} words each)",
        layout.name, scalars, words
    );
    failures
}

/// `conversions = fast`: the adapter's pack builtins against the exact Rust mirror, over
/// values in the builtins' defined domain (finite, and within f16's range for rg16f). The
/// deviation found is printed; the contract is at most one code per channel.
#[test]
fn fast_conversions_deviate_from_the_exact_mirror_by_at_most_one_code() {
    use gbuffer_testkit::FastFormats;
    let gpu = Gpu::new();
    let layout = FastFormats::layout();
    let harness = compute_harness(&layout, FastFormats::WGSL);
    let scalars = scalars_per_texel(&layout);
    let words = layout.words();
    let count = 1 << 18;
    let mut values = Values::new(77);
    let inputs: Vec<u32> = (0..count * scalars)
        .map(|_| {
            let value = values.float();
            if value.is_finite() && value.abs() <= 65504.0 {
                value
            } else {
                0.5
            }
            .to_bits()
        })
        .collect();
    let outputs = gpu.run_compute(
        &harness,
        "harness_main",
        &inputs,
        &[count * words, count * scalars],
        count as u32,
    );
    let slots = slots(&layout);
    let (mut differing, mut worst_code) = (0usize, 0u32);
    for texel in 0..count {
        let input = &inputs[texel * scalars..][..scalars];
        let expected = expected_words(&layout, input);
        for (word, field) in layout.fields.iter().enumerate() {
            let got = outputs[0][texel * words + word];
            for channel in field.format.channels() {
                let decode = |bits: u32| (bits >> channel.offset) & channel.mask();
                let (want, have) = (decode(expected[word]), decode(got));
                // Codes of one sign are ordered like their values (the sign bit is the top bit).
                let distance = want.abs_diff(have);
                if distance != 0 {
                    differing += 1;
                    worst_code = worst_code.max(distance);
                }
                assert!(
                    distance <= 1,
                    "{}.{}: input {:?}: exact code {want:#x}, fast {have:#x}",
                    field.name,
                    channel.name,
                    describe(input, &slots)
                );
            }
        }
    }
    eprintln!(
        "fast conversions on {}: {differing} of {} channel codes differ from the exact mirror, by at most {worst_code}",
        gpu.describe(),
        count * slots.len()
    );
}

#[test]
fn fast_conversions_translate_everywhere_but_webgl2() {
    use gbuffer::GBufferLayout;
    use gbuffer_testkit::FastFormats;
    let shader =
        gbuffer_testkit::harness::fragment_harness(&FastFormats::layout(), FastFormats::WGSL);
    let validated =
        gbuffer_validator::validate_wgsl(&shader).unwrap_or_else(|problem| panic!("{problem}"));
    for backend in [
        gbuffer_validator::Backend::SpirV,
        gbuffer_validator::Backend::Msl,
        gbuffer_validator::Backend::Hlsl,
    ] {
        gbuffer_validator::translate(&validated, backend)
            .unwrap_or_else(|problem| panic!("{problem}"));
    }
    // GLSL ES 3.00 lacks packUnorm4x8 (ES 3.10 has it): the portability the exact path keeps.
    let problem =
        gbuffer_validator::translate(&validated, gbuffer_validator::Backend::GlslEs).unwrap_err();
    assert!(problem.message.contains("packUnorm4x8"), "{problem}");
}
