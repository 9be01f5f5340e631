// environment: image-based lighting: the split-sum environment BRDF, GGX importance sampling
// and prefiltered mip selection.
// requires: constants, microfacet

// The mip of a prefiltered (PMREM) environment map for a roughness: roughness * mip_count
// (GPU Pro 7, Listing 2.6, with 8 mips). Linear in roughness, as the seed does.
fn ibl_mip_level(roughness: f32, mip_count: f32) -> f32 {
    return roughness * mip_count;
}

// Van der Corput radical inverse in base 2, with shifts and masks (reverseBits is missing
// from GLSL ES 3.00). Exact up to the u32-to-f32 rounding.
fn radical_inverse(index: u32) -> f32 {
    var bits = (index << 16u) | (index >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xaaaaaaaau) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xccccccccu) >> 2u);
    bits = ((bits & 0x0f0f0f0fu) << 4u) | ((bits & 0xf0f0f0f0u) >> 4u);
    bits = ((bits & 0x00ff00ffu) << 8u) | ((bits & 0xff00ff00u) >> 8u);
    return f32(bits) * 2.3283064365386963e-10;
}

// Point `index` of a `count`-point Hammersley set in [0, 1)^2.
fn hammersley(index: u32, count: u32) -> vec2<f32> {
    return vec2<f32>(f32(index) / f32(count), radical_inverse(index));
}

// A GGX-distributed half vector around +z for a uniform point xi (Karis 2013), pdf D(h) (n.h).
// Domain xi in [0, 1)^2, roughness in [0, 1]; roughness 0 gives +z. The denominator
// 1 + (alpha^2 - 1) xi.y is summed as (1 - xi.y) + alpha^2 xi.y, two positive terms, and
// sin(theta) has its own closed form: both forms of the textbook cancel near xi.y = 1.
fn importance_sample_ggx(xi: vec2<f32>, roughness: f32) -> vec3<f32> {
    let alpha = roughness * roughness;
    let alpha_squared = alpha * alpha;
    let phi = 2.0 * PI * xi.x;
    let denominator = (1.0 - xi.y) + alpha_squared * xi.y;
    let cos_theta = sqrt((1.0 - xi.y) / denominator);
    let sin_theta = sqrt(alpha_squared * xi.y / denominator);
    return vec3<f32>(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

// Split-sum environment BRDF (Karis 2013): (scale, bias) such that the hemispherical integral
// of the specular BRDF times n.l is f0 * scale + bias, by importance-sampled integration with
// height-correlated visibility. Domain n.v in (0, 1]; error falls as 1 / sample_count.
fn integrate_env_brdf(roughness: f32, n_dot_v: f32, sample_count: u32) -> vec2<f32> {
    let view = vec3<f32>(sqrt(1.0 - n_dot_v * n_dot_v), 0.0, n_dot_v);
    var scale = 0.0;
    var bias = 0.0;
    for (var index = 0u; index < sample_count; index++) {
        let half_vector = importance_sample_ggx(hammersley(index, sample_count), roughness);
        let v_dot_h = dot(view, half_vector);
        let n_dot_l = 2.0 * v_dot_h * half_vector.z - view.z;
        if n_dot_l > 0.0 {
            // BRDF * n.l / pdf, without Fresnel: 4 V n.l (v.h) / (n.h).
            let weight = 4.0 * v_smith_ggx_correlated(n_dot_v, n_dot_l, roughness) * n_dot_l * v_dot_h / half_vector.z;
            let fresnel = schlick_weight(v_dot_h);
            scale += (1.0 - fresnel) * weight;
            bias += fresnel * weight;
        }
    }
    return vec2<f32>(scale, bias) / f32(sample_count);
}

// Specular IBL of the seed (GPU Pro 7, Listing 2.6): prefiltered radiance times Lagarde's
// roughness-aware Fresnel. Cheaper than the split sum, brighter at grazing angles.
fn ibl_specular_seed(radiance: vec3<f32>, f0: vec3<f32>, n_dot_v: f32, roughness: f32) -> vec3<f32> {
    return radiance * f_schlick_roughness(f0, n_dot_v, roughness);
}
