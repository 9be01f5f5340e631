// shading: the light one G-buffer texel reflects, in an accurate form and in the mobile form of
// Karis 2014. Directions are unit vectors pointing away from the surface. Diffuse is scaled by
// what the specular lobe leaves (1 - its directional albedo), so that under a uniform white
// light no form reflects more than it receives (the white furnace test).
// requires: constants, microfacet, mobile

// The specular lobe's directional albedo from the split-sum (scale, bias): f0 * scale + bias.
fn specular_albedo(f0: vec3<f32>, env_brdf: vec2<f32>) -> vec3<f32> {
    return f0 * env_brdf.x + env_brdf.y;
}

// What the specular lobe leaves for diffuse: 1 - its albedo, clamped to [0, 1] because the
// mobile fit (EnvBRDFApprox) exceeds 1 for bright f0, where a negative diffuse would cancel
// the specular term.
fn diffuse_share(specular: vec3<f32>) -> vec3<f32> {
    return clamp(vec3<f32>(1.0) - specular, vec3<f32>(0.0), vec3<f32>(1.0));
}

// The unit vector halfway between view and light. When the light comes from exactly behind the
// view their sum is 0 and normalize would give NaN: the length is floored at
// MIN_HALF_VECTOR_LENGTH so the half vector comes out 0 (no specular) instead.
fn half_vector_of(view: vec3<f32>, light_direction: vec3<f32>) -> vec3<f32> {
    let sum = view + light_direction;
    return sum / max(length(sum), MIN_HALF_VECTOR_LENGTH);
}

// Directional light, accurate: (Lambert (1 - specular albedo) + GGX D * height-correlated V *
// Schlick F) * n.l, with env_brdf the split-sum (scale, bias) at (n.v, roughness) from the LUT.
// Roughness is clamped to MIN_ROUGHNESS and n.v to MIN_N_DOT_V so every input stays finite.
fn shade_directional(normal: vec3<f32>, view: vec3<f32>, light_direction: vec3<f32>, light_colour: vec3<f32>, diffuse_colour: vec3<f32>, f0: vec3<f32>, roughness: f32, env_brdf: vec2<f32>) -> vec3<f32> {
    let half_vector = half_vector_of(view, light_direction);
    let n_dot_v = max(dot(normal, view), MIN_N_DOT_V);
    let n_dot_l = clamp(dot(normal, light_direction), 0.0, 1.0);
    let n_dot_h = clamp(dot(normal, half_vector), 0.0, 1.0);
    let v_dot_h = clamp(dot(view, half_vector), 0.0, 1.0);
    let clamped_roughness = max(roughness, MIN_ROUGHNESS);
    let specular = d_ggx(n_dot_h, clamped_roughness) * v_smith_ggx_correlated(n_dot_v, n_dot_l, clamped_roughness) * f_schlick(f0, v_dot_h);
    let diffuse = lambert_diffuse(diffuse_colour) * diffuse_share(specular_albedo(f0, env_brdf));
    return (diffuse + specular) * light_colour * n_dot_l;
}

// Directional light, mobile form (Karis 2014): the lobe is D_Approx around the reflection
// vector, scaled by EnvBRDFApprox as for image-based light: (diffuse (1 - specular) + specular
// D_Approx) / pi. EnvBRDFApprox is clamped at 0, as in shade_ibl_mobile.
fn shade_directional_mobile(normal: vec3<f32>, view: vec3<f32>, light_direction: vec3<f32>, light_colour: vec3<f32>, diffuse_colour: vec3<f32>, f0: vec3<f32>, roughness: f32) -> vec3<f32> {
    let n_dot_v = max(dot(normal, view), MIN_N_DOT_V);
    let n_dot_l = clamp(dot(normal, light_direction), 0.0, 1.0);
    let reflected = 2.0 * dot(normal, view) * normal - view;
    let r_dot_l = clamp(dot(reflected, light_direction), 0.0, 1.0);
    let clamped_roughness = max(roughness, MIN_ROUGHNESS);
    let specular_colour = max(env_brdf_approx(f0, clamped_roughness, n_dot_v), vec3<f32>(0.0));
    let lobe = d_approx(clamped_roughness, r_dot_l);
    let diffuse = diffuse_colour * diffuse_share(specular_colour);
    return (diffuse + specular_colour * lobe) * (INV_PI * n_dot_l) * light_colour;
}

// Image-based light, accurate: diffuse (1 - specular albedo) irradiance + radiance (f0 scale +
// bias), with (scale, bias) from the split-sum LUT at (n.v, roughness) and radiance from the
// prefiltered mip at ibl_mip_level. `irradiance` is what a light map stores: Lambert's 1 / pi
// folded in.
fn shade_ibl(diffuse_colour: vec3<f32>, f0: vec3<f32>, irradiance: vec3<f32>, radiance: vec3<f32>, env_brdf: vec2<f32>) -> vec3<f32> {
    let specular = specular_albedo(f0, env_brdf);
    return diffuse_colour * diffuse_share(specular) * irradiance + radiance * specular;
}

// Image-based light, mobile form (Karis 2014): EnvBRDFApprox instead of the LUT. The fit dips
// below 0 (to -0.0024 for f0 = 0 at full roughness: "0.4524 f0 - 0.0024"): clamped to 0.
fn shade_ibl_mobile(diffuse_colour: vec3<f32>, f0: vec3<f32>, roughness: f32, n_dot_v: f32, irradiance: vec3<f32>, radiance: vec3<f32>) -> vec3<f32> {
    let specular = max(env_brdf_approx(f0, roughness, clamp(n_dot_v, 0.0, 1.0)), vec3<f32>(0.0));
    return diffuse_colour * diffuse_share(specular) * irradiance + radiance * specular;
}

// Point light falloff (Karis 2013, UE4): the inverse square law windowed to reach 0 at `radius`
// without a visible edge, saturate(1 - (d / radius)^4)^2 / (d^2 + 1); the + 1 (a light of unit
// size) keeps it finite at d = 0. Domain distance >= 0, radius > 0.
fn point_light_falloff(distance: f32, radius: f32) -> f32 {
    let ratio = distance / radius;
    let ratio_squared = ratio * ratio;
    let window = clamp(1.0 - ratio_squared * ratio_squared, 0.0, 1.0);
    return window * window / (distance * distance + 1.0);
}
