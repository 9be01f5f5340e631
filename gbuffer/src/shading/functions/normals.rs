// Mirrors normals.wgsl.

/// The z of a unit tangent-space normal from its x and y.
pub fn reconstruct_tangent_z(xy: Vec2) -> Vec3 {
    xy.extend((1.0 - xy.dot(xy)).max(0.0).sqrt())
}

/// Tangent space to world space (MikkTSpace convention).
pub fn tangent_to_world(tangent_normal: Vec3, normal: Vec3, tangent: Vec4) -> Vec3 {
    let bitangent = normal.cross(tangent.truncate()) * tangent.w;
    (tangent.truncate() * tangent_normal.x + bitangent * tangent_normal.y + normal * tangent_normal.z).normalize()
}

/// +1 or -1 per component, +1 for zero.
pub fn sign_not_zero(value: Vec2) -> Vec2 {
    Vec2::new(if value.x >= 0.0 { 1.0 } else { -1.0 }, if value.y >= 0.0 { 1.0 } else { -1.0 })
}

/// Octahedral encode (Cigolle et al. 2014) to [-1, 1]^2.
pub fn octahedral_encode(normal: Vec3) -> Vec2 {
    let projected = Vec2::new(normal.x, normal.y) / (normal.x.abs() + normal.y.abs() + normal.z.abs());
    if normal.z >= 0.0 {
        return projected;
    }
    (Vec2::ONE - Vec2::new(projected.y, projected.x).abs()) * sign_not_zero(projected)
}

/// Octahedral decode (Cigolle et al. 2014).
pub fn octahedral_decode(encoded: Vec2) -> Vec3 {
    let z = 1.0 - encoded.x.abs() - encoded.y.abs();
    let xy = if z < 0.0 { (Vec2::ONE - Vec2::new(encoded.y, encoded.x).abs()) * sign_not_zero(encoded) } else { encoded };
    xy.extend(z).normalize()
}

/// The naive [-1, 1] to [0, 1] mapping.
pub fn normal_to_unorm(normal: Vec3) -> Vec3 {
    normal * 0.5 + Vec3::splat(0.5)
}

/// The inverse of `normal_to_unorm`, renormalized.
pub fn unorm_to_normal(encoded: Vec3) -> Vec3 {
    (encoded * 2.0 - Vec3::ONE).normalize()
}
