// Mirrors hdr.wgsl (rgb9e5 lives in `mirror::rgb9e5`: it is integer-exact).

/// RGBM encode (Karis 2009), the multiplier rounded up to its 8-bit step.
pub fn rgbm_encode(linear: Vec3, range: Float) -> Vec4 {
    let largest = linear.x.max(linear.y).max(linear.z);
    let multiplier = ((largest / range).clamp(0.0, 1.0) * 255.0).ceil() / 255.0;
    let scale = if multiplier > 0.0 { 1.0 / (multiplier * range) } else { 0.0 };
    (linear * scale).clamp(Vec3::ZERO, Vec3::ONE).extend(multiplier)
}

/// RGBM decode (Karis 2009).
pub fn rgbm_decode(rgbm: Vec4, range: Float) -> Vec3 {
    rgbm.truncate() * (rgbm.w * range)
}

/// RGBM of the square root (the encode side of GPU Pro 7, Listing 2.5).
pub fn rgbm_squared_encode(linear: Vec3, range: Float) -> Vec4 {
    rgbm_encode(linear.map(Float::sqrt), range)
}

/// RGBMSqrtDecode (GPU Pro 7, Listing 2.5).
pub fn rgbm_squared_decode(rgbm: Vec4, range: Float) -> Vec3 {
    let root = (rgbm.w * range) * rgbm.truncate();
    root * root
}

/// HDR light accumulation into a unorm channel: a scale by 1 / range, clamped to [0, 1].
pub fn scale_hdr_to_unit(linear: Vec3, range: Float) -> Vec3 {
    (linear / range).clamp(Vec3::ZERO, Vec3::ONE)
}

/// The inverse of `scale_hdr_to_unit`.
pub fn scale_unit_to_hdr(unit: Vec3, range: Float) -> Vec3 {
    unit * range
}
