//! On a real adapter: the generated `pack_`/`unpack_` WGSL against the Rust mirror, over more
//! than a million texels of every format, edge cases first. Packed words must be identical;
//! unpacked values identical too, except unorm channels, which may differ from the exact
//! quotient by 2 ulp (the WGSL multiplies by a correctly rounded reciprocal). Fast conversions
//! are held to their own contract, within a code or two of the exact mirror.

use gbuffer::layout::{Conversions, Layout};
use gbuffer::{seed_layouts, GBufferLayout};
use gbuffer_codegen::wgsl::emit_with;
use gbuffer_gpu::harness::scalars_per_texel;
use gbuffer_gpu::values::Values;
use gbuffer_gpu::Gpu;
use gbuffer_testkit::texels::{check_on_adapter, inputs};
use gbuffer_testkit::{AllFormats, FastBitFields, FastFormats, MixedConversions};
use gbuffer_tradeoff::packing_cost::deviation;

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
    let mut values = Values::new(seed);
    let inputs = |first, count| inputs(layout, first, count, &mut values);
    let failures = check_on_adapter(gpu, layout, wgsl, texels, inputs, 20);
    eprintln!(
        "{}: compared {texels} texels ({} scalars, {} words each)",
        layout.name,
        scalars_per_texel(layout),
        layout.words()
    );
    failures
}

/// Runs `texels` texels in the domain fast conversions promise to handle (finite, within f16's
/// range; edge cases first) through `wgsl`, a form of `layout` whose conversions are
/// `conversions` (fields may choose their own), prints how far its codes are from the exact
/// mirror's and holds them to the layout contract's rule (`packing_cost::allowed_code_error`).
fn holds_the_fast_contract(
    gpu: &Gpu,
    layout: &Layout,
    (wgsl, conversions): (&str, Conversions),
    texels: usize,
    seed: u64,
) {
    let found = deviation(gpu, layout, wgsl, texels, seed).unwrap();
    eprintln!(
        "{} ({conversions:?}) on {}: {found}",
        layout.name,
        gpu.describe()
    );
    let beyond = found.beyond_contract(layout, conversions);
    assert!(beyond.is_empty(), "{}", beyond.join("\n"));
}

/// `conversions = fast`: the adapter's builtins and f32 idioms against the exact Rust mirror,
/// over four million texels of whole-word formats and a quarter million of bit fields: within
/// one code a channel (octahedral normals and RGBM colours within two steps of their decoded
/// values). The exact conversions of the same layouts do not differ at all.
#[test]
fn fast_conversions_keep_their_contract_and_exact_ones_do_not_differ() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let layouts = [
        (FastFormats::layout(), FastFormats::WGSL, 1 << 22, 77),
        (FastBitFields::layout(), FastBitFields::WGSL, 1 << 18, 41),
    ];
    for (layout, fast, texels, seed) in layouts {
        holds_the_fast_contract(&gpu, &layout, (fast, Conversions::Fast), texels, seed);
        let exact = emit_with(&layout, Conversions::Exact);
        holds_the_fast_contract(
            &gpu,
            &layout,
            (&exact, Conversions::Exact),
            1 << 16,
            seed + 1,
        );
    }
}

/// A layout whose fields choose their own conversions: the exact ones keep the mirror's bits,
/// the fast ones stay within one code, on the same adapter and in the same texels.
#[test]
fn each_field_keeps_its_own_conversions() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let mixed = (MixedConversions::WGSL, Conversions::Exact);
    holds_the_fast_contract(&gpu, &MixedConversions::layout(), mixed, 1 << 20, 79);
}

#[test]
fn fast_conversions_translate_everywhere_but_webgl2() {
    let shader = gbuffer_gpu::harness::fragment_harness(&FastFormats::layout(), FastFormats::WGSL);
    let validated =
        gbuffer_validator::validate_wgsl(&shader).unwrap_or_else(|problem| panic!("{problem}"));
    for backend in [
        gbuffer_validator::Backend::SpirV,
        gbuffer_validator::Backend::Msl,
        gbuffer_validator::Backend::Hlsl,
    ] {
        gbuffer_validator::write_backend(&validated, backend)
            .unwrap_or_else(|problem| panic!("{problem}"));
    }
    // GLSL ES 3.00 lacks packUnorm4x8 (ES 3.10 has it): naga cannot translate fast WGSL for
    // WebGL2. The codegen's GLSL includes carry their own fallback (`gles_includes.rs`).
    let problem = gbuffer_validator::write_backend(&validated, gbuffer_validator::Backend::GlslEs)
        .unwrap_err();
    assert!(problem.message.contains("packUnorm4x8"), "{problem}");
}
