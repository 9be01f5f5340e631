//! naga validates every module of the WGSL shading library alone and all of them composed,
//! and the harness of every function translates to every backend.

use gbuffer_shading::wgsl::{compose, modules, CODEC_PREFIX};
use gbuffer_testkit::shading_cases::{cases, compute_harness};
use gbuffer_validator::{validate_everywhere, validate_wgsl};

#[test]
fn every_module_is_valid_alone_with_its_dependencies() {
    for module in modules() {
        let wgsl = compose(&[module.name]).unwrap();
        if let Err(problem) = validate_wgsl(&wgsl) {
            panic!("module `{}`: {problem}", module.name);
        }
    }
}

#[test]
fn all_modules_compose_into_one_valid_module() {
    let names: Vec<&str> = modules().iter().map(|module| module.name).collect();
    let wgsl = compose(&names).unwrap();
    validate_wgsl(&wgsl).unwrap_or_else(|problem| panic!("{problem}"));
}

#[test]
fn the_library_composes_with_a_generated_layout() {
    use gbuffer::GBufferLayout;
    let mut wgsl = compose(&["shading", "normals", "colour", "hdr"]).unwrap();
    wgsl.push_str(gbuffer::seed_layouts::MobileMetallic::WGSL);
    validate_wgsl(&wgsl).unwrap_or_else(|problem| panic!("{problem}"));
}

#[test]
fn every_function_translates_to_every_backend() {
    for case in cases() {
        if let Err(problem) = validate_everywhere(&compute_harness(&case)) {
            panic!("{}: {problem}", case.call);
        }
    }
}

#[test]
fn every_wgsl_function_has_a_test_case() {
    let cases = cases();
    let tested: Vec<&str> = cases.iter().map(|case| case.name()).collect();
    // Helpers exercised through the functions that call them, and the f16 forms, which
    // tests/stability.rs runs on the adapter against `shading::half_precision`. The codecs'
    // functions (`shading_library_...`) are the layouts' own, tested with them.
    let helpers = [
        "radical_inverse",
        "env_brdf_approx_half",
        "env_brdf_approx_nonmetal_half",
        "d_approx_half",
        "shade_directional_mobile_half",
    ];
    for module in modules() {
        for line in module.source.lines() {
            if let Some(rest) = line.strip_prefix("fn ") {
                let name = rest.split('(').next().unwrap();
                assert!(
                    tested.contains(&name)
                        || helpers.contains(&name)
                        || name.starts_with(CODEC_PREFIX),
                    "`{name}` of module `{}` has no test case",
                    module.name
                );
            }
        }
    }
}
