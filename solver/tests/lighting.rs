//! The specialised lighting shader: valid for every combination of features, and an unused
//! feature costs no instruction (counted with naga after compaction).

use gbuffer_core::Named;
use gbuffer_solver::lighting::{lighting_modules, lighting_wgsl, Forms, IblForm, SunForm};
use gbuffer_solver::texel::texel_wgsl;
use gbuffer_solver::{solve, Feature, Features, MaterialModel, SceneDescription, Solution};
use gbuffer_validator::cost::{compile_compacted, spirv_instructions};

const FORMS: [Forms; 4] = [
    Forms {
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
    },
    Forms {
        sun: SunForm::Ggx,
        ibl: IblForm::Approx,
    },
    Forms {
        sun: SunForm::Approx,
        ibl: IblForm::Lut,
    },
    Forms {
        sun: SunForm::Approx,
        ibl: IblForm::Approx,
    },
];

/// The lighting function in a fragment shader, with the host items it may read.
fn shader(solution: &Solution, forms: Forms) -> String {
    let mut modules = lighting_modules();
    modules.extend(["environment", "mobile"]);
    format!(
        "{}\n{}\n{}
const SUN_DIRECTION: vec3<f32> = vec3<f32>(0.0, 0.8, 0.6);
const SUN_COLOUR: vec3<f32> = vec3<f32>(3.0);
const POINT_LIGHT_COUNT: u32 = 2u;
const POINT_LIGHT_POSITIONS: array<vec3<f32>, 2> = array<vec3<f32>, 2>(vec3<f32>(1.0), vec3<f32>(-1.0));
const POINT_LIGHT_COLOURS: array<vec3<f32>, 2> = array<vec3<f32>, 2>(vec3<f32>(4.0), vec3<f32>(2.0));
const POINT_LIGHT_RADIUS: f32 = 5.0;
@group(0) @binding(0) var environment: texture_2d<f32>;
@group(0) @binding(1) var lut: texture_2d<f32>;
@group(0) @binding(2) var linear_sampler: sampler;
@group(0) @binding(3) var gbuffer: texture_2d<u32>;
fn environment_radiance(direction: vec3<f32>, roughness: f32) -> vec3<f32> {{
    return textureSampleLevel(environment, linear_sampler, direction.xy * 0.5 + vec2<f32>(0.5), roughness * 6.0).rgb;
}}
fn env_brdf_lut(n_dot_v: f32, roughness: f32) -> vec2<f32> {{
    return textureSampleLevel(lut, linear_sampler, vec2<f32>(n_dot_v, roughness), 0.0).xy;
}}
@fragment
fn lighting_main(@builtin(position) pixel: vec4<f32>, @location(0) view: vec3<f32>) -> @location(0) vec4<f32> {{
    let texel = textureLoad(gbuffer, vec2<i32>(pixel.xy), 0);
    var words: array<u32, {words}>;
    for (var index = 0u; index < {words}u; index++) {{
        words[index] = texel[index % 4u];
    }}
    let values = {decode}({unpack}(words));
    return vec4<f32>({shade}(values, normalize(view), view), 1.0);
}}
",
        gbuffer_shading::compose(&modules).unwrap(),
        texel_wgsl(solution),
        lighting_wgsl(solution, forms),
        words = solution.layout.words(),
        decode = solution.layout.symbols().decode_values(),
        unpack = solution.layout.symbols().unpack(),
        shade = solution.layout.symbols().shade(),
    )
}

fn loose(name: &str, model: MaterialModel, features: Features) -> SceneDescription {
    SceneDescription::new(name)
        .model(model)
        .features(features.iter())
        .budget(512)
}

#[test]
fn every_feature_combination_lights_with_valid_wgsl() {
    let mut checked = 0;
    for bits in 0u32..1 << Feature::ALL.len() {
        let features: Features = Feature::ALL
            .iter()
            .copied()
            .enumerate()
            .filter(|(index, _)| bits & (1 << index) != 0)
            .map(|(_, feature)| feature)
            .collect();
        for &model in MaterialModel::ALL {
            let Ok(solution) = solve(&loose("Combination", model, features)) else {
                continue; // nothing stored
            };
            // Every form on a quarter of the combinations, one form on the rest.
            let forms: &[Forms] = if bits % 4 == 0 {
                &FORMS
            } else {
                &FORMS[(bits as usize / 4) % 4..][..1]
            };
            for &form in forms {
                let source = shader(&solution, form);
                if let Err(problem) = gbuffer_validator::validate_wgsl(&source) {
                    panic!(
                        "{features:?} {model:?} {form:?}: {problem}\n{}",
                        problem.detail
                    );
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 2000, "{checked}");
}

/// SPIR-V instructions of the compacted module, and whether a function of that name is left.
fn compiled(solution: &Solution, forms: Forms) -> (usize, naga::Module) {
    let source = shader(solution, forms);
    let (_, words) = compile_compacted(&source).unwrap();
    let mut module = gbuffer_validator::validate_wgsl(&source).unwrap().module;
    naga::compact::compact(&mut module, naga::compact::KeepUnused::No);
    (spirv_instructions(&words), module)
}

fn has_function(module: &naga::Module, name: &str) -> bool {
    module
        .functions
        .iter()
        .any(|(_, function)| function.name.as_deref() == Some(name))
}

#[test]
fn an_unused_feature_costs_no_instruction() {
    let full: Features = Feature::ALL
        .iter()
        .copied()
        .filter(|feature| *feature != Feature::FullyRough)
        .collect();
    // Features the lighting reads, and a function only they bring.
    let lighting_features = [
        (Feature::PointLights, "point_light_falloff"),
        (Feature::ImageBasedLighting, "environment_radiance"),
        (Feature::Metals, "metallic_workflow"),
        (Feature::DielectricSpecular, "dielectric_f0_from_specular"),
    ];
    for forms in FORMS {
        let full_solution = solve(&loose("Full", MaterialModel::Metallic, full)).unwrap();
        let (full_count, full_module) = compiled(&full_solution, forms);
        for (feature, function) in lighting_features {
            let solution = solve(&loose(
                "Less",
                MaterialModel::Metallic,
                full.without(feature),
            ))
            .unwrap();
            let (count, module) = compiled(&solution, forms);
            assert!(
                has_function(&full_module, function),
                "{function} missing from the full shader"
            );
            assert!(
                !has_function(&module, function),
                "without {feature}, {function} is still compiled ({forms:?})"
            );
            assert!(
                count < full_count,
                "without {feature}: {count} >= {full_count} instructions ({forms:?})"
            );
        }
        // Without point lights, the sun alone brings the direct-light BRDF.
        let no_points = full.without(Feature::PointLights);
        let sunless = solve(&loose(
            "Sunless",
            MaterialModel::Metallic,
            no_points.without(Feature::Sun),
        ))
        .unwrap();
        let (_, module) = compiled(&sunless, forms);
        for function in ["shade_directional", "shade_directional_mobile"] {
            assert!(
                !has_function(&module, function),
                "{function} without direct light ({forms:?})"
            );
        }
        // Features the lighting pass does not read change nothing in it.
        for feature in [Feature::NormalMaps, Feature::Decals] {
            let solution = solve(&loose(
                "Full",
                MaterialModel::Metallic,
                full.without(feature),
            ))
            .unwrap();
            assert_eq!(
                shader(&solution, forms),
                shader(&full_solution, forms),
                "{feature} changed the lighting shader"
            );
        }
    }
}
