// Mirrors tonemap.wgsl.

/// Reinhard (Reinhard et al. 2002), per channel.
pub fn tonemap_reinhard(linear: Vec3) -> Vec3 {
    linear / (Vec3::ONE + linear)
}

/// The ACES filmic curve fitted by Narkowicz (2015).
pub fn tonemap_aces_fitted(linear: Vec3) -> Vec3 {
    let numerator = linear * (2.51 * linear + Vec3::splat(0.03));
    let denominator = linear * (2.43 * linear + Vec3::splat(0.59)) + Vec3::splat(0.14);
    (numerator / denominator).clamp(Vec3::ZERO, Vec3::ONE)
}
