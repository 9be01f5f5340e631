//! The specialised lighting shader: `shade_<name>(values, view, position)` with only the terms
//! the scene uses. A term is not switched off at run time: it is never generated, so an
//! unused feature costs no instruction (the tests count them with naga).
//!
//! The function reads what the host shader provides, and only what its terms use:
//!
//! | term                              | host items                                          |
//! |-----------------------------------|-----------------------------------------------------|
//! | environment specular              | `fn environment_radiance(direction, roughness) -> vec3<f32>` |
//! | split-sum LUT (accurate forms)    | `fn env_brdf_lut(n_dot_v, roughness) -> vec2<f32>`  |
//! | sun                               | `const SUN_DIRECTION`, `const SUN_COLOUR: vec3<f32>` |
//! | point lights                      | `const POINT_LIGHT_COUNT: u32`, `POINT_LIGHT_POSITIONS` and `POINT_LIGHT_COLOURS: array<vec3<f32>, N>`, `POINT_LIGHT_RADIUS: f32` |
//!
//! `position` (world space) is read by point lights only; `view` points from the surface to
//! the eye.

use std::fmt::Write as _;

use crate::description::{Feature, MaterialModel};
use crate::quantity::Quantity;
use crate::solver::Solution;

/// How the sun and point lights are shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SunForm {
    /// GGX, height-correlated Smith, Schlick (`shade_directional`).
    Ggx,
    /// D_Approx around the reflection vector with EnvBRDFApprox (`shade_directional_mobile`).
    Approx,
}

gbuffer_core::named!(
    SunForm {
        Ggx => "ggx",
        Approx => "approx",
    }
);

/// How image-based light is shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IblForm {
    /// The split-sum LUT (`shade_ibl`).
    Lut,
    /// EnvBRDFApprox (`shade_ibl_mobile`; `env_brdf_approx_nonmetal` when f0 is constant).
    Approx,
}

gbuffer_core::named!(
    IblForm {
        Lut => "lut",
        Approx => "approx",
    }
);

/// The forms of the lighting terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Forms {
    /// The sun's specular term: GGX or its mobile approximation.
    pub sun: SunForm,
    /// The image-based light's BRDF: the split-sum LUT or EnvBRDFApprox.
    pub ibl: IblForm,
}

impl Forms {
    /// The accurate forms: GGX and the LUT.
    pub const ACCURATE: Forms = Forms {
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
    };

    /// The mobile forms of Karis 2014: D_Approx and EnvBRDFApprox.
    pub const MOBILE: Forms = Forms {
        sun: SunForm::Approx,
        ibl: IblForm::Approx,
    };
}

/// The shading library modules the lighting function calls.
pub fn lighting_modules() -> Vec<&'static str> {
    vec!["shading", "material"]
}

/// What the lighting function reads from the host beyond constants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HostInputs {
    /// `environment_radiance`: the environment's specular reflection is shaded.
    pub environment: bool,
    /// `env_brdf_lut`: an accurate form needs the split-sum LUT.
    pub env_brdf_lut: bool,
}

/// What the host must bind for the lighting of `solution` in `forms`.
pub fn host_inputs(solution: &Solution, forms: Forms) -> HostInputs {
    let features = solution.scene.features;
    let environment = features.environment_specular();
    HostInputs {
        environment,
        env_brdf_lut: (features.direct_light() && forms.sun == SunForm::Ggx)
            || (environment && forms.ibl == IblForm::Lut),
    }
}

/// The lighting terms a scene uses, in words, for comments and reports.
pub fn terms(solution: &Solution) -> Vec<&'static str> {
    let features = solution.scene.features;
    let mut terms = Vec::new();
    if features.environment_specular() {
        terms.push("image-based light (environment specular)");
    }
    if solution.placement(Quantity::Light).is_some() {
        terms.push("light accumulation");
    }
    if features.contains(Feature::Sun) {
        terms.push("sun");
    }
    if features.contains(Feature::PointLights) {
        terms.push("point lights");
    }
    terms
}

/// `fn shade_<snake>(values: <Name>Values, view: vec3<f32>, position: vec3<f32>) -> vec3<f32>`.
pub fn lighting_wgsl(solution: &Solution, forms: Forms) -> String {
    let features = solution.scene.features;
    let stores = |quantity| solution.placement(quantity).is_some();
    let direct = features.direct_light();
    let environment = features.environment_specular();
    let needs_lut =
        (direct && forms.sun == SunForm::Ggx) || (environment && forms.ibl == IblForm::Lut);
    let constant_f0 = !stores(Quantity::Specular)
        && !stores(Quantity::Metallic)
        && !stores(Quantity::SpecularColour);

    let mut body = String::new();
    let mut line = |text: String| {
        body.push_str("    ");
        body.push_str(&text);
        body.push('\n');
    };
    // The constant-f0 form of EnvBRDFApprox reads no material.
    let nonmetal_approx = environment && forms.ibl == IblForm::Approx && constant_f0;
    let needs_colours = direct || (environment && !nonmetal_approx);
    if direct || environment {
        // The material: diffuse colour and f0, from what the layout stores.
        let dielectric_f0 = if stores(Quantity::Specular) {
            "dielectric_f0_from_specular(values.specular)"
        } else {
            "DIELECTRIC_F0"
        };
        match solution.scene.model {
            _ if !needs_colours => {}
            MaterialModel::Metallic if stores(Quantity::Metallic) => {
                line(format!(
                    "let colours = metallic_workflow(values.base_colour, values.metallic, {dielectric_f0});"
                ));
            }
            MaterialModel::Metallic => {
                line(
                    "// No metals: f0 is the dielectric's, the base colour is all diffuse.".into(),
                );
                let diffuse = if stores(Quantity::BaseColour) {
                    "values.base_colour"
                } else {
                    "vec3<f32>(0.0)"
                };
                line(format!(
                    "let colours = MaterialColours({diffuse}, vec3<f32>({dielectric_f0}));"
                ));
            }
            MaterialModel::Specular => {
                let f0 = if stores(Quantity::SpecularColour) {
                    "values.specular_colour".to_string()
                } else {
                    format!("vec3<f32>({dielectric_f0})")
                };
                let albedo = if stores(Quantity::Albedo) {
                    "values.albedo"
                } else {
                    "vec3<f32>(0.0)"
                };
                // The albedo is stored as the diffuse colour, as Listing 2.8 stores it.
                line(format!("let colours = MaterialColours({albedo}, {f0});"));
            }
        }
        line("let normal = values.normal;".into());
        if stores(Quantity::Roughness) {
            line("let roughness = values.roughness;".into());
        } else {
            line("let roughness = 1.0; // every surface is fully rough".into());
        }
        line("let n_dot_v = clamp(dot(normal, view), MIN_N_DOT_V, 1.0);".into());
        if needs_lut {
            line("let env_brdf = env_brdf_lut(n_dot_v, roughness);".into());
        }
    }
    line("var colour = vec3<f32>(0.0);".into());
    if environment {
        line("// Image-based light: the light accumulation holds its diffuse part.".into());
        line("let reflected = 2.0 * dot(normal, view) * normal - view;".into());
        line("let radiance = environment_radiance(reflected, roughness);".into());
        match forms.ibl {
            IblForm::Lut => line(
                "colour += shade_ibl(values.light, colours.f0, vec3<f32>(1.0), radiance, env_brdf);"
                    .into(),
            ),
            IblForm::Approx if nonmetal_approx => {
                line("// f0 is 0.04 everywhere: the non-metal EnvBRDFApprox (seed 001).".into());
                line("let specular = max(env_brdf_approx_nonmetal(roughness, n_dot_v), 0.0);".into());
                line(
                    "colour += values.light * diffuse_share(vec3<f32>(specular)) + radiance * specular;"
                        .into(),
                );
            }
            IblForm::Approx => line(
                "colour += shade_ibl_mobile(values.light, colours.f0, roughness, n_dot_v, vec3<f32>(1.0), radiance);"
                    .into(),
            ),
        }
    } else if stores(Quantity::Light) {
        line(
            "// Baked, emissive and (folded) image-based light, as the G-buffer pass stored it."
                .into(),
        );
        line("colour += values.light;".into());
    }
    let shade = |direction: &str, light_colour: &str| {
        match forms.sun {
        SunForm::Ggx => format!(
            "shade_directional(normal, view, {direction}, {light_colour}, colours.diffuse, colours.f0, roughness, env_brdf)"
        ),
        SunForm::Approx => format!(
            "shade_directional_mobile(normal, view, {direction}, {light_colour}, colours.diffuse, colours.f0, roughness)"
        ),
    }
    };
    if features.contains(Feature::Sun) {
        line("// The sun.".into());
        line(format!(
            "colour += {};",
            shade("SUN_DIRECTION", "SUN_COLOUR")
        ));
    }
    if features.contains(Feature::PointLights) {
        line("// Point lights, at the position reconstructed from depth.".into());
        line("for (var index = 0u; index < POINT_LIGHT_COUNT; index++) {".into());
        line("    let to_light = POINT_LIGHT_POSITIONS[index] - position;".into());
        line("    let distance = length(to_light);".into());
        line(
            "    let arriving = POINT_LIGHT_COLOURS[index] * point_light_falloff(distance, POINT_LIGHT_RADIUS);"
                .into(),
        );
        line(format!(
            "    colour += {};",
            shade("to_light / max(distance, 1e-4)", "arriving")
        ));
        line("}".into());
    }
    line("return colour;".into());

    let mut out = String::new();
    let _ = writeln!(
        out,
        "// Lighting for {} (generated by `scenes`): {}; {:?} direct light, {:?} image-based light.",
        solution.layout.name,
        terms(solution).join(", "),
        forms.sun,
        forms.ibl
    );
    let _ = writeln!(
        out,
        "// Terms the scene does not use are not generated. `view` points to the eye; `position` is read by point lights only."
    );
    let _ = write!(
        out,
        "fn {}(values: {}, view: vec3<f32>, position: vec3<f32>) -> vec3<f32> {{\n{body}}}\n",
        solution.layout.symbols().shade(),
        solution.values_type()
    );
    out
}
