// hdr: encodings that fit high dynamic range colour into low dynamic range storage.
// requires:

// RGBM encode (Karis 2009): rgb / (m * range) with m the largest channel over range, rounded
// up to the 8-bit step the alpha channel stores, so rgb stays <= 1. Domain [0, range];
// black gives m = 0 and rgb = 0 (the division is guarded).
fn rgbm_encode(linear: vec3<f32>, range: f32) -> vec4<f32> {
    let largest = max(max(linear.r, linear.g), linear.b);
    let multiplier = ceil(clamp(largest / range, 0.0, 1.0) * 255.0) / 255.0;
    let scale = select(0.0, 1.0 / (multiplier * range), multiplier > 0.0);
    return vec4<f32>(clamp(linear * scale, vec3<f32>(0.0), vec3<f32>(1.0)), multiplier);
}

// RGBM decode (Karis 2009): rgb * m * range. Exact up to two roundings.
fn rgbm_decode(rgbm: vec4<f32>, range: f32) -> vec3<f32> {
    return rgbm.rgb * (rgbm.a * range);
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

// One channel's 9-bit mantissa for a shared biased exponent: round half up of
// value * 2^(24 - exponent), on the float's bits (a float add could round a half away).
fn rgb9e5_mantissa(value: f32, shared_exponent: u32) -> u32 {
    let bits = bitcast<u32>(value);
    let exponent = bits >> 23u;
    var significand = bits & 0x7fffffu;
    if exponent != 0u {
        significand |= 0x800000u;
    }
    // value = significand * 2^(max(exponent, 1) - 150); mantissa = value * 2^(24 - shared),
    // a right shift by at least 15 for values no larger than the one that set the exponent.
    let shift = 126u + shared_exponent - max(exponent, 1u);
    if shift > 24u {
        return 0u; // under half a step
    }
    return (significand + (1u << (shift - 1u))) >> shift;
}

// Shared-exponent HDR (EXT_texture_shared_exponent): r, g, b 9-bit mantissas at bits 0, 9 and
// 18, a 5-bit exponent (bias 15) at 27. Domain [0, 65408]: negatives and NaN give 0, larger
// values saturate. Exact, as the extension's equations with integer rounding.
fn rgb9e5_encode(linear: vec3<f32>) -> u32 {
    let bits = bitcast<vec3<u32>>(linear);
    // Negative or NaN (as integers, above +infinity's bits) gives 0; then saturate.
    let positive = select(linear, vec3<f32>(0.0), bits > vec3<u32>(0x7f800000u));
    let clamped = min(positive, vec3<f32>(65408.0));
    let largest = max(max(clamped.r, clamped.g), clamped.b);
    var shared_exponent = u32(max(i32(bitcast<u32>(largest) >> 23u) - 111, 0));
    if rgb9e5_mantissa(largest, shared_exponent) == 512u {
        shared_exponent += 1u;
    }
    return rgb9e5_mantissa(clamped.r, shared_exponent)
        | (rgb9e5_mantissa(clamped.g, shared_exponent) << 9u)
        | (rgb9e5_mantissa(clamped.b, shared_exponent) << 18u)
        | (shared_exponent << 27u);
}

// Shared-exponent decode: mantissa * 2^(exponent - 24), exact.
fn rgb9e5_decode(packed: u32) -> vec3<f32> {
    let mantissas = vec3<u32>(packed, packed >> 9u, packed >> 18u) & vec3<u32>(0x1ffu);
    let scale = bitcast<f32>(((packed >> 27u) + 103u) << 23u);
    return vec3<f32>(mantissas) * scale;
}
