//! naga validates the WGSL of every fixture and of random layouts, and translates each to
//! SPIR-V, MSL, HLSL and GLSL ES 3.00 (WebGL2), exercised by a fragment shader that calls
//! every generated function.

use gbuffer::packing::Layout;
use gbuffer::{seed_layouts, GBufferLayout};
use gbuffer_testkit::harness::fragment_harness;
use gbuffer_testkit::AllFormats;
use gbuffer_validator::{translate, validate_everywhere, validate_wgsl, Backend};
use proptest::prelude::*;

fn fixtures() -> Vec<(Layout, &'static str)> {
    let mut fixtures = seed_layouts::all();
    fixtures.push((AllFormats::layout(), AllFormats::WGSL));
    fixtures
}

#[test]
fn fixture_wgsl_is_valid_alone() {
    for (layout, wgsl) in fixtures() {
        if let Err(problem) = validate_wgsl(wgsl) {
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
    validate_wgsl(&all).unwrap_or_else(|problem| panic!("{problem}"));
}

#[test]
fn generated_code_uses_no_builtin_that_breaks_on_some_backend() {
    for (layout, wgsl) in fixtures() {
        for builtin in [
            "pack4x8",
            "unpack4x8",
            "pack2x16",
            "unpack2x16",
            "extractBits",
            "insertBits",
            "countLeadingZeros",
            "firstLeadingBit",
        ] {
            assert!(!wgsl.contains(builtin), "{} uses `{builtin}`", layout.name);
        }
    }
}

#[test]
fn webgl2_output_is_glsl_es_300() {
    let (layout, wgsl) = (
        seed_layouts::MobileMetallic::layout(),
        seed_layouts::MobileMetallic::WGSL,
    );
    let validated = validate_everywhere(&fragment_harness(&layout, wgsl)).unwrap();
    let glsl = translate(&validated, Backend::GlslEs).unwrap();
    assert!(glsl.starts_with("#version 300 es"), "{glsl}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_layouts_validate_and_translate_everywhere(layout in gbuffer_testkit::layouts::random_layout_with(16)) {
        prop_assert!(layout.check().is_empty(), "{:?}", layout.check());
        let wgsl = gbuffer_codegen::emit::wgsl::emit(&layout);
        let shader = fragment_harness(&layout, &wgsl);
        if let Err(problem) = validate_everywhere(&shader) {
            return Err(TestCaseError::fail(format!("{problem}\n{shader}")));
        }
    }
}
