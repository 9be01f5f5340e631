// microfacet: the terms of a Cook-Torrance specular BRDF with the GGX distribution, and
// Lambert diffuse. Roughness is perceptual: alpha = roughness^2 (Burley 2012).
// requires: constants

// GGX / Trowbridge-Reitz NDF (Walter et al. 2007): alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
// Domain n.h in [0, 1], roughness in [MIN_ROUGHNESS, 1]: at roughness 0 and n.h = 1 it is 0 / 0.
// Near n.h = 1 at low roughness the denominator cancels: f32 loses up to 0.6% at 0.045.
fn d_ggx(n_dot_h: f32, roughness: f32) -> f32 {
    let alpha = roughness * roughness;
    let alpha_squared = alpha * alpha;
    let denominator = (n_dot_h * alpha_squared - n_dot_h) * n_dot_h + 1.0;
    return alpha_squared / (PI * denominator * denominator);
}

// Height-correlated Smith-GGX visibility V = G2 / (4 n.v n.l) (Heitz 2014). Domain n.v, n.l in
// (0, 1]: both 0 divides by 0; the sqrt args stay >= alpha^2 > 0.
fn v_smith_ggx_correlated(n_dot_v: f32, n_dot_l: f32, roughness: f32) -> f32 {
    let alpha_squared = roughness * roughness * roughness * roughness;
    let view = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - alpha_squared) + alpha_squared);
    let light = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - alpha_squared) + alpha_squared);
    return 0.5 / (view + light);
}

// Separable Smith with Schlick's G1, k = alpha / 2 (Karis 2013): V = 1 / (4 (n.v (1-k) + k)
// (n.l (1-k) + k)). Domain n.v, n.l in [0, 1]; finite for roughness > 0 (k > 0).
fn v_schlick_ggx(n_dot_v: f32, n_dot_l: f32, roughness: f32) -> f32 {
    let k = roughness * roughness * 0.5;
    let view = n_dot_v * (1.0 - k) + k;
    let light = n_dot_l * (1.0 - k) + k;
    return 0.25 / (view * light);
}

// Schlick's Fresnel weight (Schlick 1994): (1 - cos)^5, the share of the grazing value in the
// reflectance at an angle whose cosine is `cos_theta`. Three multiplications, not pow(): pow is
// exp2(5 log2(x)) on most GPUs, undefined at x = 0 in WGSL and GLSL. Domain [0, 1].
fn schlick_weight(cos_theta: f32) -> f32 {
    let grazing = 1.0 - cos_theta;
    let grazing_squared = grazing * grazing;
    return grazing_squared * grazing_squared * grazing;
}

// Schlick's Fresnel (Schlick 1994): f0 + (1 - f0) (1 - v.h)^5. Domain v.h in [0, 1].
fn f_schlick(f0: vec3<f32>, v_dot_h: f32) -> vec3<f32> {
    return f0 + (vec3<f32>(1.0) - f0) * schlick_weight(v_dot_h);
}

// Schlick's Fresnel with a roughness-limited grazing value (Lagarde 2011; GPU Pro 7 Listing
// 2.6, whose smoothness is 1 - roughness). Any n.v: it is clamped to [0, 1].
fn f_schlick_roughness(f0: vec3<f32>, n_dot_v: f32, roughness: f32) -> vec3<f32> {
    let limit = max(vec3<f32>(1.0 - roughness), f0);
    return f0 + (limit - f0) * schlick_weight(clamp(n_dot_v, 0.0, 1.0));
}

// Lambert diffuse BRDF: diffuse_colour / pi. Energy conserving for diffuse_colour <= 1.
fn lambert_diffuse(diffuse_colour: vec3<f32>) -> vec3<f32> {
    return diffuse_colour * INV_PI;
}
