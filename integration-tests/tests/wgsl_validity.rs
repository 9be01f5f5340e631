//! naga validates the WGSL of every fixture and of random layouts, and translates each to
//! SPIR-V, MSL, HLSL and GLSL ES 3.00 (WebGL2), exercised by a fragment shader that calls
//! every generated function.

use gbuffer::layout::Layout;
use gbuffer::{seed_layouts, GBufferLayout};
use gbuffer_core::{Conversions, Named};
use gbuffer_gpu::harness::fragment_harness;
use gbuffer_testkit::layouts::seeds_and_every_format;
use gbuffer_testkit::{AllFormats, EveryEncoding};
use gbuffer_validator::{validate_everywhere, validate_generated, write_backend, Backend};
use proptest::prelude::*;

fn fixtures() -> Vec<(Layout, &'static str)> {
    let mut fixtures = seed_layouts::all();
    fixtures.extend(gbuffer::engine_layouts::all());
    fixtures.push((AllFormats::layout(), AllFormats::WGSL));
    fixtures
}

#[test]
fn fixture_wgsl_is_valid_alone() {
    for (layout, wgsl) in fixtures() {
        if let Err(problem) = validate_generated(wgsl) {
            panic!("{}: {problem}\n{wgsl}", layout.name);
        }
    }
}

#[test]
fn fixture_wgsl_translates_to_every_backend() {
    for (layout, wgsl) in fixtures() {
        let shader = fragment_harness(&layout, wgsl);
        if let Err(problem) = validate_everywhere(&shader) {
            panic!("{}: {problem}\n{shader}", layout.name);
        }
    }
}

#[test]
fn layouts_compose_in_one_module() {
    let all: String = fixtures()
        .into_iter()
        .map(|(_, wgsl)| wgsl)
        .collect::<Vec<_>>()
        .join("\n\n");
    validate_generated(&all).unwrap_or_else(|problem| panic!("{problem}"));
}

/// The header says the WGSL needs naga's `SHADER_FLOAT16_IN_FLOAT32` (which the emitter
/// decides from the fields' codecs, not from its text) exactly where naga's validator refuses
/// the WGSL without it: for the seeds and engine layouts, and for every field of every format
/// and bit-field encoding alone, under both conversions.
#[test]
fn the_header_names_the_half_float_capability_exactly_where_naga_needs_it() {
    let mut layouts = seeds_and_every_format();
    for whole in [AllFormats::layout(), EveryEncoding::layout()] {
        for field in &whole.fields {
            layouts.push(Layout {
                name: "OneField".into(),
                fields: vec![field.clone()],
                ..whole.clone()
            });
        }
    }
    let mut default_capabilities = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    );
    for layout in layouts {
        for &conversions in Conversions::ALL {
            let wgsl = gbuffer_codegen::wgsl::emit_with(&layout, conversions);
            let says = wgsl.contains("Capabilities::SHADER_FLOAT16_IN_FLOAT32");
            let module = naga::front::wgsl::parse_str(&wgsl)
                .unwrap_or_else(|error| panic!("{}", error.emit_to_string(&wgsl)));
            let needs = default_capabilities.validate(&module).is_err();
            let field = &layout.fields[0].name;
            assert_eq!(
                says,
                needs,
                "{} (first field `{field}`), {} conversions: the header {} the capability",
                layout.name,
                conversions.name(),
                if says { "names" } else { "leaves out" }
            );
        }
    }
}

/// Exact conversions call no builtin whose rounding is the adapter's, nor one that some
/// backend lacks (GLSL ES 3.00 has no `packUnorm4x8` or bit-field builtins). `unpack2x16float`
/// is neither: binary16 to binary32 is exact, and every backend has it.
#[test]
fn exact_code_calls_no_builtin_that_rounds_its_own_way_or_breaks_on_some_backend() {
    for (layout, wgsl) in fixtures() {
        for builtin in [
            "pack4x8unorm",
            "pack4x8snorm",
            "unpack4x8unorm",
            "unpack4x8snorm",
            "pack2x16unorm",
            "pack2x16snorm",
            "pack2x16float",
            "unpack2x16unorm",
            "unpack2x16snorm",
            "extractBits",
            "insertBits",
            "countLeadingZeros",
            "firstLeadingBit",
        ] {
            assert!(!calls(wgsl, builtin), "{} calls `{builtin}`", layout.name);
        }
    }
}

/// Whether `wgsl` calls the function `name` (not merely a function whose name ends in it).
fn calls(wgsl: &str, name: &str) -> bool {
    wgsl.match_indices(&format!("{name}(")).any(|(at, _)| {
        !wgsl[..at]
            .chars()
            .next_back()
            .is_some_and(|before| before.is_alphanumeric() || before == '_')
    })
}

#[test]
fn webgl2_output_is_glsl_es_300() {
    let (layout, wgsl) = (
        seed_layouts::MobileMetallic::layout(),
        seed_layouts::MobileMetallic::WGSL,
    );
    let validated = validate_everywhere(&fragment_harness(&layout, wgsl)).unwrap();
    let glsl = write_backend(&validated, Backend::GlslEs).unwrap();
    assert!(glsl.starts_with("#version 300 es"), "{glsl}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_layouts_validate_and_translate_everywhere(layout in gbuffer_testkit::layouts::random_layout_with(16)) {
        prop_assert!(layout.check().is_empty(), "{:?}", layout.check());
        let wgsl = gbuffer_codegen::wgsl::emit(&layout);
        let shader = fragment_harness(&layout, &wgsl);
        if let Err(problem) = validate_everywhere(&shader) {
            return Err(TestCaseError::fail(format!("{problem}\n{shader}")));
        }
    }
}
