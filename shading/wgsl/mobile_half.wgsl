enable f16;
// mobile_half: the mobile forms in half precision (f16), as mobile GPUs run them fastest. Needs
// the adapter's SHADER_F16 feature (wgpu) / `enable f16`. Every clamp that keeps a form finite
// in f16 (largest finite value 65504) is named here.
// requires:

// The smallest roughness the half-precision forms are fed: D_Approx's 1 / roughness^4 is
// 65536 at roughness 0.0625, past f16's largest finite value; at 0.065 it is 56020.
const MIN_ROUGHNESS_HALF: f16 = 0.065h;

// The smallest n.v the half-precision forms are fed (f16's smallest normal is 6.1e-5).
const MIN_N_DOT_V_HALF: f16 = 0.0001h;

// The largest radiance the half-precision composites return: f16's largest finite value, so a
// highlight saturates instead of becoming infinity.
const MAX_RADIANCE_HALF: f16 = 65504.0h;

const INV_PI_HALF: f16 = 0.31830988h;

// env_brdf_approx in f16 (Karis 2014 writes it with half). No division; finite anywhere.
fn env_brdf_approx_half(specular_colour: vec3<f16>, roughness: f16, n_dot_v: f16) -> vec3<f16> {
    let c0 = vec4<f16>(-1.0h, -0.0275h, -0.572h, 0.022h);
    let c1 = vec4<f16>(1.0h, 0.0425h, 1.04h, -0.04h);
    let r = roughness * c0 + c1;
    let a004 = min(r.x * r.x, exp2(-9.28h * n_dot_v)) * r.x + r.y;
    let scale_bias = vec2<f16>(-1.04h, 1.04h) * a004 + r.zw;
    return specular_colour * scale_bias.x + scale_bias.y;
}

// env_brdf_approx_nonmetal in f16.
fn env_brdf_approx_nonmetal_half(roughness: f16, n_dot_v: f16) -> f16 {
    let c0 = vec2<f16>(-1.0h, -0.0275h);
    let c1 = vec2<f16>(1.0h, 0.0425h);
    let r = roughness * c0 + c1;
    return min(r.x * r.x, exp2(-9.28h * n_dot_v)) * r.x + r.y;
}

// d_approx in f16, roughness clamped to MIN_ROUGHNESS_HALF so 1 / alpha^2 stays finite.
fn d_approx_half(roughness: f16, r_dot_l: f16) -> f16 {
    let clamped_roughness = max(roughness, MIN_ROUGHNESS_HALF);
    let alpha = clamped_roughness * clamped_roughness;
    let inverse_alpha_squared = 1.0h / (alpha * alpha);
    let c = 0.72134752h * inverse_alpha_squared + 0.39674113h;
    return inverse_alpha_squared * exp2(c * r_dot_l - c);
}

// shade_directional_mobile in f16, with the half clamps; the result saturates at
// MAX_RADIANCE_HALF.
fn shade_directional_mobile_half(normal: vec3<f16>, view: vec3<f16>, light_direction: vec3<f16>, light_colour: vec3<f16>, diffuse_colour: vec3<f16>, f0: vec3<f16>, roughness: f16) -> vec3<f16> {
    let n_dot_v = max(dot(normal, view), MIN_N_DOT_V_HALF);
    let n_dot_l = clamp(dot(normal, light_direction), 0.0h, 1.0h);
    let reflected = 2.0h * dot(normal, view) * normal - view;
    let r_dot_l = clamp(dot(reflected, light_direction), 0.0h, 1.0h);
    let clamped_roughness = max(roughness, MIN_ROUGHNESS_HALF);
    let specular_colour = max(env_brdf_approx_half(f0, clamped_roughness, n_dot_v), vec3<f16>(0.0h));
    let lobe = d_approx_half(clamped_roughness, r_dot_l);
    let diffuse = diffuse_colour * clamp(vec3<f16>(1.0h) - specular_colour, vec3<f16>(0.0h), vec3<f16>(1.0h));
    // Scale before adding the lobe, then saturate: the product can pass 65504 for bright lights.
    let scale = (INV_PI_HALF * n_dot_l) * light_colour;
    return min(diffuse * scale + specular_colour * min(lobe * scale, vec3<f16>(MAX_RADIANCE_HALF)), vec3<f16>(MAX_RADIANCE_HALF));
}
