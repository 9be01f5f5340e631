// Mirrors mobile.wgsl.

/// EnvBRDFApprox (Karis 2014): f0 * scale + bias of the split-sum environment BRDF, fitted.
pub fn env_brdf_approx(specular_colour: Vec3, roughness: Float, n_dot_v: Float) -> Vec3 {
    let c0 = Vec4::new(-1.0, -0.0275, -0.572, 0.022);
    let c1 = Vec4::new(1.0, 0.0425, 1.04, -0.04);
    let r = roughness * c0 + c1;
    let a004 = (r.x * r.x).min((-9.28 * n_dot_v).exp2()) * r.x + r.y;
    let scale_bias = Vec2::new(-1.04, 1.04) * a004 + Vec2::new(r.z, r.w);
    specular_colour * scale_bias.x + Vec3::splat(scale_bias.y)
}

/// EnvBRDFApproxNonmetal (Karis 2014): `env_brdf_approx` for f0 = 0.04.
pub fn env_brdf_approx_nonmetal(roughness: Float, n_dot_v: Float) -> Float {
    let c0 = Vec2::new(-1.0, -0.0275);
    let c1 = Vec2::new(1.0, 0.0425);
    let r = roughness * c0 + c1;
    (r.x * r.x).min((-9.28 * n_dot_v).exp2()) * r.x + r.y
}

/// The "fully rough" shortcut (Karis 2014): specular folded into diffuse as 0.45 f0.
pub fn fully_rough_diffuse_colour(diffuse_colour: Vec3, specular_colour: Vec3) -> Vec3 {
    diffuse_colour + specular_colour * 0.45
}

/// D_Approx (Karis 2014): pi * GGX approximated by a spherical Gaussian around r.
pub fn d_approx(roughness: Float, r_dot_l: Float) -> Float {
    let alpha = roughness * roughness;
    let alpha_squared = alpha * alpha;
    let inverse_alpha_squared = 1.0 / alpha_squared;
    let c = 0.721_347_52 * inverse_alpha_squared + 0.396_741_13;
    inverse_alpha_squared * (c * r_dot_l - c).exp2()
}
