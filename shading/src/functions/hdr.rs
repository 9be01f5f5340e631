// Mirrors hdr.wgsl. RGBM and rgb9e5 are the codecs' (`codec_forms`): in the mirror the
// codecs' own Rust, in the reference their textbook forms.

pub use super::codec_forms::hdr::*;

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
