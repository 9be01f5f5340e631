// Mirrors microfacet.wgsl.

/// GGX / Trowbridge-Reitz NDF (Walter et al. 2007).
pub fn d_ggx(n_dot_h: Float, roughness: Float) -> Float {
    let alpha = roughness * roughness;
    let alpha_squared = alpha * alpha;
    let denominator = (n_dot_h * alpha_squared - n_dot_h) * n_dot_h + 1.0;
    alpha_squared / (PI * denominator * denominator)
}

/// Height-correlated Smith-GGX visibility (Heitz 2014).
pub fn v_smith_ggx_correlated(n_dot_v: Float, n_dot_l: Float, roughness: Float) -> Float {
    let alpha_squared = roughness * roughness * roughness * roughness;
    let view = n_dot_l * (n_dot_v * n_dot_v * (1.0 - alpha_squared) + alpha_squared).sqrt();
    let light = n_dot_v * (n_dot_l * n_dot_l * (1.0 - alpha_squared) + alpha_squared).sqrt();
    0.5 / (view + light)
}

/// Separable Smith with Schlick's G1, k = alpha / 2 (Karis 2013).
pub fn v_schlick_ggx(n_dot_v: Float, n_dot_l: Float, roughness: Float) -> Float {
    let k = roughness * roughness * 0.5;
    let view = n_dot_v * (1.0 - k) + k;
    let light = n_dot_l * (1.0 - k) + k;
    0.25 / (view * light)
}

/// Schlick's Fresnel weight (Schlick 1994): (1 - cos)^5.
pub fn schlick_weight(cos_theta: Float) -> Float {
    let grazing = 1.0 - cos_theta;
    let grazing_squared = grazing * grazing;
    grazing_squared * grazing_squared * grazing
}

/// Schlick's Fresnel (Schlick 1994).
pub fn f_schlick(f0: Vec3, v_dot_h: Float) -> Vec3 {
    f0 + (Vec3::ONE - f0) * schlick_weight(v_dot_h)
}

/// Schlick's Fresnel with a roughness-limited grazing value (Lagarde 2011; Listing 2.6).
pub fn f_schlick_roughness(f0: Vec3, n_dot_v: Float, roughness: Float) -> Vec3 {
    let limit = Vec3::splat(1.0 - roughness).max(f0);
    f0 + (limit - f0) * schlick_weight(n_dot_v.clamp(0.0, 1.0))
}

/// Lambert diffuse BRDF.
pub fn lambert_diffuse(diffuse_colour: Vec3) -> Vec3 {
    diffuse_colour * INV_PI
}
