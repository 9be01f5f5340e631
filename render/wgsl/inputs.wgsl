// The baked inputs the scene and the lighting read (gbuffer_render::shaders::INPUTS_WGSL), at
// group 0: the environment (1), the split-sum LUT (2), the environment's sampler (3), the light
// map (5), the LUT's and light map's sampler (6).
//
// Two samplers, both trilinear: the equirectangular environment wraps around the sky in u; the
// LUT and the light map clamp to their edges. One sampler repeating for all three blended the
// LUT's n.v = 1 column with its n.v = 0 one: bright discs where a surface faces the camera.

@group(0) @binding(1) var environment: texture_2d<f32>;
@group(0) @binding(2) var lut: texture_2d<f32>;
@group(0) @binding(3) var environment_sampler: sampler;
@group(0) @binding(5) var light_map: texture_2d<f32>;
@group(0) @binding(6) var clamped_sampler: sampler;

// Direction to equirectangular coordinates (u around the vertical, v from the zenith).
fn equirectangular(direction: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(atan2(direction.x, direction.z) * 0.15915494 + 0.5, acos(clamp(direction.y, -1.0, 1.0)) * 0.31830988);
}

// The prefiltered sky towards `direction` for `roughness` (its mip, Listing 2.6).
fn environment_radiance(direction: vec3<f32>, roughness: f32) -> vec3<f32> {
    let mip = ibl_mip_level(roughness, ENVIRONMENT_MIPS);
    return rgbm_decode(textureSampleLevel(environment, environment_sampler, equirectangular(direction), mip), ENVIRONMENT_RANGE);
}

// The split-sum LUT: scale and bias of f0.
fn env_brdf_lut(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    return textureSampleLevel(lut, clamped_sampler, vec2<f32>(n_dot_v, roughness), 0.0).xy;
}

// The light map's static diffuse irradiance at `uv` (RGBM squared, Listing 2.5).
fn light_map_irradiance(uv: vec2<f32>) -> vec3<f32> {
    return rgbm_squared_decode(textureSampleLevel(light_map, clamped_sampler, uv, 0.0), LIGHT_MAP_RANGE);
}
