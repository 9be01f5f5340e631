// colour: transfer curves between linear light and stored (gamma-encoded) values.
// requires:

// sRGB decode, exact piecewise curve (IEC 61966-2-1). Domain [0, 1]; pow is 2-3 ulp on GPUs.
fn srgb_to_linear(encoded: vec3<f32>) -> vec3<f32> {
    let low = encoded / 12.92;
    let high = pow((encoded + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, encoded <= vec3<f32>(0.04045));
}

// sRGB encode, exact piecewise curve (IEC 61966-2-1). Domain [0, 1]; negatives give NaN in pow.
fn linear_to_srgb(linear: vec3<f32>) -> vec3<f32> {
    let low = linear * 12.92;
    let high = 1.055 * pow(linear, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, linear <= vec3<f32>(0.0031308));
}

// Gamma 2.2 decode (Smith and Einig, GPU Pro 7, Listing 2.3, whose names are swapped). Domain
// [0, 1]; pow(0, 2.2) is 0 but pow of a negative is NaN.
fn gamma_2_2_to_linear(encoded: vec3<f32>) -> vec3<f32> {
    return pow(encoded, vec3<f32>(2.2));
}

// Gamma 2.2 encode (Listing 2.3). Domain [0, 1].
fn linear_to_gamma_2_2(linear: vec3<f32>) -> vec3<f32> {
    return pow(linear, vec3<f32>(1.0 / 2.2));
}

// Pseudo-gamma 2.0 decode: a square (Listing 2.4). Any domain; cheapest decode there is.
fn pseudo_gamma_to_linear(encoded: vec3<f32>) -> vec3<f32> {
    return encoded * encoded;
}

// Pseudo-gamma 2.0 encode: a square root (Listing 2.4). Domain [0, inf); sqrt of a negative is NaN.
fn linear_to_pseudo_gamma(linear: vec3<f32>) -> vec3<f32> {
    return sqrt(linear);
}

// Relative luminance of linear Rec. 709 / sRGB primaries (ITU-R BT.709 weights).
fn luminance(linear: vec3<f32>) -> f32 {
    return dot(linear, vec3<f32>(0.2126, 0.7152, 0.0722));
}
