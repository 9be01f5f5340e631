//! On a real adapter: the generated `pack_`/`unpack_` WGSL against the Rust mirror, over more
//! than a million texels of every format, edge cases first. Packed words must be identical;
//! unpacked values identical too, except unorm channels, which may differ from the exact
//! quotient by 2 ulp (the WGSL multiplies by a correctly rounded reciprocal).

use gbuffer::packing::{Conversions, Layout};
use gbuffer::{seed_layouts, GBufferLayout};
use gbuffer_gpu::harness::{compute_harness, run_in_batches, scalars_per_texel};
use gbuffer_gpu::values::Values;
use gbuffer_gpu::Gpu;
use gbuffer_testkit::texels::{compare, inputs};
use gbuffer_testkit::AllFormats;

#[test]
fn generated_wgsl_matches_the_rust_mirror_bit_for_bit_on_the_adapter() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let mut failures = Vec::new();
    failures.extend(check_layout(
        &gpu,
        &AllFormats::layout(),
        AllFormats::WGSL,
        1 << 20,
        1,
    ));
    let seeds_and_engines = seed_layouts::all()
        .into_iter()
        .chain(gbuffer::engine_layouts::all());
    for (index, (layout, wgsl)) in seeds_and_engines.enumerate() {
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
    run_in_batches(
        gpu,
        layout,
        &harness,
        texels,
        |first, count| inputs(layout, first, count, &mut values),
        |inputs, packed, unpacked, loaded| {
            compare(
                "wgpu",
                layout,
                inputs,
                Some(packed),
                Some(unpacked),
                &mut failures,
                20,
            );
            compare(
                "wgpu, per-field loads",
                layout,
                inputs,
                None,
                Some(loaded),
                &mut failures,
                20,
            );
        },
    )
    .expect("the adapter runs the harness");
    eprintln!(
        "{}: compared {texels} texels ({} scalars, {} words each)",
        layout.name, scalars, words
    );
    failures
}

/// `conversions = fast`: the adapter's builtins and f32 idioms against the exact Rust mirror,
/// over four million texels of values in the domain fast conversions promise to handle
/// (finite, within f16's range), edge cases first. The contract is at most one code per
/// channel; the deviation found is printed.
#[test]
fn fast_conversions_deviate_from_the_exact_mirror_by_at_most_one_code() {
    use gbuffer_testkit::FastFormats;
    use gbuffer_tradeoff::packing_cost::deviation;
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let layout = FastFormats::layout();
    let found = deviation(&gpu, &layout, FastFormats::WGSL, 1 << 22, 77).unwrap();
    eprintln!("fast conversions on {}: {found}", gpu.describe());
    let beyond = found.beyond_contract(&layout, Conversions::Fast);
    assert!(beyond.is_empty(), "{}", beyond.join("\n"));
    // The exact conversions of the same layout do not differ at all.
    let exact = gbuffer_codegen::emit::wgsl::emit(&layout);
    let found = deviation(&gpu, &layout, &exact, 1 << 16, 78).unwrap();
    assert_eq!(found.differing, 0, "{found:?}");
}

/// A layout whose fields choose their own conversions: the exact ones keep the mirror's bits,
/// the fast ones stay within one code, on the same adapter and in the same texels.
#[test]
fn each_field_keeps_its_own_conversions() {
    use gbuffer_testkit::MixedConversions;
    use gbuffer_tradeoff::packing_cost::deviation;
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let layout = MixedConversions::layout();
    let found = deviation(&gpu, &layout, MixedConversions::WGSL, 1 << 20, 79).unwrap();
    eprintln!("mixed conversions on {}: {found}", gpu.describe());
    let beyond = found.beyond_contract(&layout, Conversions::Exact);
    assert!(beyond.is_empty(), "{}", beyond.join("\n"));
}

#[test]
fn fast_conversions_translate_everywhere_but_webgl2() {
    use gbuffer::GBufferLayout;
    use gbuffer_testkit::FastFormats;
    let shader = gbuffer_gpu::harness::fragment_harness(&FastFormats::layout(), FastFormats::WGSL);
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
    // GLSL ES 3.00 lacks packUnorm4x8 (ES 3.10 has it): naga cannot translate fast WGSL for
    // WebGL2. The codegen's GLSL includes carry their own fallback (`gles_includes.rs`).
    let problem =
        gbuffer_validator::translate(&validated, gbuffer_validator::Backend::GlslEs).unwrap_err();
    assert!(problem.message.contains("packUnorm4x8"), "{problem}");
}
