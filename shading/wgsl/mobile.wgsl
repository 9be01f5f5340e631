// mobile: the cheap forms of Unreal Engine 4's mobile renderer (Karis 2014, "Physically Based
// Shading on Mobile"), meant for half precision.
// requires:

// EnvBRDFApprox: an analytic fit of the split-sum environment BRDF (after Lazarov 2013),
// returning f0 * scale + bias. Domain roughness, n.v in [0, 1]; no division, finite anywhere.
fn env_brdf_approx(specular_colour: vec3<f32>, roughness: f32, n_dot_v: f32) -> vec3<f32> {
    let c0 = vec4<f32>(-1.0, -0.0275, -0.572, 0.022);
    let c1 = vec4<f32>(1.0, 0.0425, 1.04, -0.04);
    let r = roughness * c0 + c1;
    let a004 = min(r.x * r.x, exp2(-9.28 * n_dot_v)) * r.x + r.y;
    let scale_bias = vec2<f32>(-1.04, 1.04) * a004 + r.zw;
    return specular_colour * scale_bias.x + scale_bias.y;
}

// EnvBRDFApproxNonmetal: env_brdf_approx for f0 = 0.04, when metallic and specular are unset.
fn env_brdf_approx_nonmetal(roughness: f32, n_dot_v: f32) -> f32 {
    let c0 = vec2<f32>(-1.0, -0.0275);
    let c1 = vec2<f32>(1.0, 0.0425);
    let r = roughness * c0 + c1;
    return min(r.x * r.x, exp2(-9.28 * n_dot_v)) * r.x + r.y;
}

// The "fully rough" shortcut: env_brdf_approx(f0, 1, 1) = 0.4524 f0 - 0.0024, so a fully rough
// material folds its specular into diffuse as diffuse + 0.45 f0 and skips the environment map.
fn fully_rough_diffuse_colour(diffuse_colour: vec3<f32>, specular_colour: vec3<f32>) -> vec3<f32> {
    return diffuse_colour + specular_colour * 0.45;
}

// D_Approx: GGX replaced by Blinn, then Phong around the reflection vector, then a spherical
// Gaussian: (1 / alpha^2) exp2(c (r.l - 1)), c = 0.72134752 / alpha^2 + 0.39674113. It is
// pi * D; 1 / pi belongs to the light's colour. Domain roughness > 0: 1 / alpha^2 overflows
// half precision below roughness 0.0625 (f16 max 65504) and f32 at roughness 0; at low
// roughness c (r.l - 1) is a large number times a small one, so r.l's rounding shows (f32:
// about 1% at roughness 0.045).
fn d_approx(roughness: f32, r_dot_l: f32) -> f32 {
    let alpha = roughness * roughness;
    let alpha_squared = alpha * alpha;
    let inverse_alpha_squared = 1.0 / alpha_squared;
    let c = 0.72134752 * inverse_alpha_squared + 0.39674113;
    return inverse_alpha_squared * exp2(c * r_dot_l - c);
}
