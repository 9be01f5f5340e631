// Mirrors environment.wgsl.

/// The prefiltered environment mip for a roughness (GPU Pro 7, Listing 2.6).
pub fn ibl_mip_level(roughness: Float, mip_count: Float) -> Float {
    roughness * mip_count
}

/// Van der Corput radical inverse in base 2.
pub fn radical_inverse(index: u32) -> Float {
    let mut bits = index.rotate_left(16);
    bits = ((bits & 0x5555_5555) << 1) | ((bits & 0xaaaa_aaaa) >> 1);
    bits = ((bits & 0x3333_3333) << 2) | ((bits & 0xcccc_cccc) >> 2);
    bits = ((bits & 0x0f0f_0f0f) << 4) | ((bits & 0xf0f0_f0f0) >> 4);
    bits = ((bits & 0x00ff_00ff) << 8) | ((bits & 0xff00_ff00) >> 8);
    bits as Float * 2.328_306_436_538_696_3e-10
}

/// Point `index` of a `count`-point Hammersley set.
pub fn hammersley(index: u32, count: u32) -> Vec2 {
    Vec2::new(index as Float / count as Float, radical_inverse(index))
}

/// A GGX-distributed half vector around +z (Karis 2013).
pub fn importance_sample_ggx(xi: Vec2, roughness: Float) -> Vec3 {
    let alpha = roughness * roughness;
    let alpha_squared = alpha * alpha;
    let phi = 2.0 * PI * xi.x;
    let denominator = (1.0 - xi.y) + alpha_squared * xi.y;
    let cos_theta = ((1.0 - xi.y) / denominator).sqrt();
    let sin_theta = (alpha_squared * xi.y / denominator).sqrt();
    Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta)
}

/// Split-sum environment BRDF (scale, bias) by importance-sampled integration (Karis 2013).
pub fn integrate_env_brdf(roughness: Float, n_dot_v: Float, sample_count: u32) -> Vec2 {
    let view = Vec3::new((1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v);
    // Each sample's (scale, bias) terms, summed in index order as the WGSL loop adds them.
    let sum: Vec2 = (0..sample_count)
        .map(|index| importance_sample_ggx(hammersley(index, sample_count), roughness))
        .filter_map(|half_vector| {
            let v_dot_h = view.dot(half_vector);
            let n_dot_l = 2.0 * v_dot_h * half_vector.z - view.z;
            (n_dot_l > 0.0).then(|| {
                let weight = 4.0 * v_smith_ggx_correlated(n_dot_v, n_dot_l, roughness) * n_dot_l * v_dot_h / half_vector.z;
                let fresnel = schlick_weight(v_dot_h);
                Vec2::new(1.0 - fresnel, fresnel) * weight
            })
        })
        .sum();
    sum / sample_count as Float
}

/// Specular IBL of the seed (GPU Pro 7, Listing 2.6).
pub fn ibl_specular_seed(radiance: Vec3, f0: Vec3, n_dot_v: Float, roughness: Float) -> Vec3 {
    radiance * f_schlick_roughness(f0, n_dot_v, roughness)
}
