// Mirrors normals.wgsl. The octahedral map is the codec's (`codec_forms`): in the mirror the
// codec's own Rust, in the reference the textbook form.

pub use super::codec_forms::normals::*;

/// The z of a unit tangent-space normal from its x and y.
pub fn reconstruct_tangent_z(xy: Vec2) -> Vec3 {
    xy.extend((1.0 - xy.dot(xy)).max(0.0).sqrt())
}

/// Tangent space to world space (MikkTSpace convention).
pub fn tangent_to_world(tangent_normal: Vec3, normal: Vec3, tangent: Vec4) -> Vec3 {
    let bitangent = normal.cross(tangent.truncate()) * tangent.w;
    (tangent.truncate() * tangent_normal.x + bitangent * tangent_normal.y + normal * tangent_normal.z).normalize()
}

/// The naive [-1, 1] to [0, 1] mapping.
pub fn normal_to_unorm(normal: Vec3) -> Vec3 {
    normal * 0.5 + Vec3::splat(0.5)
}

/// The inverse of `normal_to_unorm`, renormalized.
pub fn unorm_to_normal(encoded: Vec3) -> Vec3 {
    (encoded * 2.0 - Vec3::ONE).normalize()
}
