// hdr: encodings that fit high dynamic range colour into low dynamic range storage.
// requires:
// codecs: rgbm, rgb9e5

// RGBM encode (Karis 2009) for an rgba8 target or texture: the RGBM codec's exact encode
// (gbuffer-core's codecs/rgbm.rs), its codes over 255. The multiplier m = ceil(255 max / range)
// / 255 is at least 1/255, each channel round(255 c / (m range)) / 255. Domain [0, range]:
// negatives and NaN give 0, larger values saturate. range must be a positive float with at
// most 16 significant bits (6, 8, 16, 51.5), which the exact fixed point needs.
fn rgbm_encode(linear: vec3<f32>, range: f32) -> vec4<f32> {
    return unpack4x8unorm(shading_library_rgbm_from_f32x3(linear, range));
}

// RGBM decode (Karis 2009): rgb * m * range, of four unorm values (a filtered sample too).
fn rgbm_decode(rgbm: vec4<f32>, range: f32) -> vec3<f32> {
    return shading_library_rgbm_decode(rgbm, range);
}

// RGBM of the square root, the seed's lightmap variant: more codes for dark values. Encode
// side of RGBMSqrtDecode (GPU Pro 7, Listing 2.5, range 6). Domain [0, range^2].
fn rgbm_squared_encode(linear: vec3<f32>, range: f32) -> vec4<f32> {
    return rgbm_encode(sqrt(linear), range);
}

// RGBMSqrtDecode (GPU Pro 7, Listing 2.5): (rgb * m * range)^2.
fn rgbm_squared_decode(rgbm: vec4<f32>, range: f32) -> vec3<f32> {
    let root = (rgbm.a * range) * rgbm.rgb;
    return root * root;
}

// HDR light accumulation into a unorm channel (the rgb10_a2 of the seed layouts): a linear
// scale by 1 / range, clamped to [0, 1]. Values past range saturate; the step is range / 1023.
fn scale_hdr_to_unit(linear: vec3<f32>, range: f32) -> vec3<f32> {
    return clamp(linear / range, vec3<f32>(0.0), vec3<f32>(1.0));
}

// The inverse of scale_hdr_to_unit.
fn scale_unit_to_hdr(unit: vec3<f32>, range: f32) -> vec3<f32> {
    return unit * range;
}

// Shared-exponent HDR (EXT_texture_shared_exponent): the rgb9e5 codec, exact. r, g, b 9-bit
// mantissas at bits 0, 9 and 18, a 5-bit exponent (bias 15) at 27. Domain [0, 65408]:
// negatives and NaN give 0, larger values saturate.
fn rgb9e5_encode(linear: vec3<f32>) -> u32 {
    return shading_library_f32x3_to_rgb9e5(linear);
}

// Shared-exponent decode: mantissa * 2^(exponent - 24), exact.
fn rgb9e5_decode(packed: u32) -> vec3<f32> {
    return shading_library_f32x3_from_rgb9e5(packed);
}
