// Mirrors colour.wgsl.

/// sRGB decode, exact piecewise curve (IEC 61966-2-1).
pub fn srgb_to_linear(encoded: Vec3) -> Vec3 {
    let low = encoded / 12.92;
    let high = ((encoded + Vec3::splat(0.055)) / 1.055).powf(2.4);
    Vec3::select(encoded.cmple(Vec3::splat(0.04045)), low, high)
}

/// sRGB encode, exact piecewise curve (IEC 61966-2-1).
pub fn linear_to_srgb(linear: Vec3) -> Vec3 {
    let low = linear * 12.92;
    let high = 1.055 * linear.powf(1.0 / 2.4) - Vec3::splat(0.055);
    Vec3::select(linear.cmple(Vec3::splat(0.0031308)), low, high)
}

/// Gamma 2.2 decode (GPU Pro 7, Listing 2.3).
pub fn gamma_2_2_to_linear(encoded: Vec3) -> Vec3 {
    encoded.powf(2.2)
}

/// Gamma 2.2 encode (GPU Pro 7, Listing 2.3).
pub fn linear_to_gamma_2_2(linear: Vec3) -> Vec3 {
    linear.powf(1.0 / 2.2)
}

/// Pseudo-gamma 2.0 decode: a square (GPU Pro 7, Listing 2.4).
pub fn pseudo_gamma_to_linear(encoded: Vec3) -> Vec3 {
    encoded * encoded
}

/// Pseudo-gamma 2.0 encode: a square root (GPU Pro 7, Listing 2.4).
pub fn linear_to_pseudo_gamma(linear: Vec3) -> Vec3 {
    linear.map(Float::sqrt)
}

/// Relative luminance of linear Rec. 709 primaries.
pub fn luminance(linear: Vec3) -> Float {
    linear.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}
