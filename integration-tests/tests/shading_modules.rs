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

/// The names a row of the guide's table lists: each backticked name, where `` `_decode` `` after
/// `` `rgbm_encode` `` stands for `rgbm_decode` (the last word of the name before, replaced).
fn listed_names(cell: &str) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for name in cell.split('`').skip(1).step_by(2) {
        let name = match (name.strip_prefix('_'), names.last()) {
            (Some(_), Some(before)) => format!("{}{name}", &before[..before.rfind('_').unwrap()]),
            _ => name.to_string(),
        };
        names.push(name);
    }
    names
}

#[test]
fn the_guide_lists_every_module_and_everything_it_declares() {
    let chapter = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../book/src/shading-library.md"
    ))
    .expect("the shading library's chapter");
    let rows: Vec<(String, Vec<String>)> = chapter
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.trim().strip_prefix('|')?.split('|').collect();
            let module = cells.first()?.trim().strip_prefix('`')?.strip_suffix('`')?;
            Some((module.to_string(), listed_names(cells.get(1)?)))
        })
        .collect();
    let shipped: Vec<&str> = modules().iter().map(|module| module.name).collect();
    let listed: Vec<&str> = rows.iter().map(|(module, _)| module.as_str()).collect();
    assert_eq!(
        listed, shipped,
        "the chapter's modules, in the library's order"
    );
    for ((_, names), module) in rows.iter().zip(modules()) {
        let declared: Vec<&str> = module
            .source
            .lines()
            .filter_map(|line| line.strip_prefix("fn ").or(line.strip_prefix("const ")))
            .map(|rest| rest.split(['(', ':', ' ']).next().unwrap())
            .filter(|name| !name.starts_with(CODEC_PREFIX))
            .collect();
        assert_eq!(names, &declared, "module `{}`", module.name);
    }
}
