// Mirrors shading.wgsl.

/// The specular lobe's directional albedo from the split-sum (scale, bias).
pub fn specular_albedo(f0: Vec3, env_brdf: Vec2) -> Vec3 {
    f0 * env_brdf.x + Vec3::splat(env_brdf.y)
}

/// What the specular lobe leaves for diffuse: 1 - its albedo, clamped to [0, 1].
pub fn diffuse_share(specular: Vec3) -> Vec3 {
    (Vec3::ONE - specular).clamp(Vec3::ZERO, Vec3::ONE)
}

/// The unit vector halfway between view and light; 0 when they are opposite.
pub fn half_vector_of(view: Vec3, light_direction: Vec3) -> Vec3 {
    let sum = view + light_direction;
    sum / sum.length().max(MIN_HALF_VECTOR_LENGTH)
}

/// Directional light, accurate: (Lambert (1 - specular albedo) + GGX D V F) * n.l.
#[allow(clippy::too_many_arguments)]
pub fn shade_directional(normal: Vec3, view: Vec3, light_direction: Vec3, light_colour: Vec3, diffuse_colour: Vec3, f0: Vec3, roughness: Float, env_brdf: Vec2) -> Vec3 {
    let half_vector = half_vector_of(view, light_direction);
    let n_dot_v = normal.dot(view).max(MIN_N_DOT_V);
    let n_dot_l = normal.dot(light_direction).clamp(0.0, 1.0);
    let n_dot_h = normal.dot(half_vector).clamp(0.0, 1.0);
    let v_dot_h = view.dot(half_vector).clamp(0.0, 1.0);
    let clamped_roughness = roughness.max(MIN_ROUGHNESS);
    let specular = d_ggx(n_dot_h, clamped_roughness) * v_smith_ggx_correlated(n_dot_v, n_dot_l, clamped_roughness) * f_schlick(f0, v_dot_h);
    let diffuse = lambert_diffuse(diffuse_colour) * diffuse_share(specular_albedo(f0, env_brdf));
    (diffuse + specular) * light_colour * n_dot_l
}

/// Directional light, mobile form (Karis 2014).
#[allow(clippy::too_many_arguments)]
pub fn shade_directional_mobile(normal: Vec3, view: Vec3, light_direction: Vec3, light_colour: Vec3, diffuse_colour: Vec3, f0: Vec3, roughness: Float) -> Vec3 {
    let n_dot_v = normal.dot(view).max(MIN_N_DOT_V);
    let n_dot_l = normal.dot(light_direction).clamp(0.0, 1.0);
    let reflected = 2.0 * normal.dot(view) * normal - view;
    let r_dot_l = reflected.dot(light_direction).clamp(0.0, 1.0);
    let clamped_roughness = roughness.max(MIN_ROUGHNESS);
    let specular_colour = env_brdf_approx(f0, clamped_roughness, n_dot_v).max(Vec3::ZERO);
    let lobe = d_approx(clamped_roughness, r_dot_l);
    let diffuse = diffuse_colour * diffuse_share(specular_colour);
    (diffuse + specular_colour * lobe) * (INV_PI * n_dot_l) * light_colour
}

/// Image-based light, accurate (split-sum LUT).
pub fn shade_ibl(diffuse_colour: Vec3, f0: Vec3, irradiance: Vec3, radiance: Vec3, env_brdf: Vec2) -> Vec3 {
    let specular = specular_albedo(f0, env_brdf);
    diffuse_colour * diffuse_share(specular) * irradiance + radiance * specular
}

/// Image-based light, mobile form (EnvBRDFApprox).
pub fn shade_ibl_mobile(diffuse_colour: Vec3, f0: Vec3, roughness: Float, n_dot_v: Float, irradiance: Vec3, radiance: Vec3) -> Vec3 {
    let specular = env_brdf_approx(f0, roughness, n_dot_v.clamp(0.0, 1.0)).max(Vec3::ZERO);
    diffuse_colour * diffuse_share(specular) * irradiance + radiance * specular
}

/// Point light falloff (Karis 2013): the inverse square law windowed to 0 at `radius`.
pub fn point_light_falloff(distance: Float, radius: Float) -> Float {
    let ratio = distance / radius;
    let ratio_squared = ratio * ratio;
    let window = (1.0 - ratio_squared * ratio_squared).clamp(0.0, 1.0);
    window * window / (distance * distance + 1.0)
}
