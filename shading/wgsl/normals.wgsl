// normals: tangent-space normal maps and the encodings a G-buffer stores normals in.
// requires:
// codecs: octahedral

// The z of a unit tangent-space normal from its x and y (two-channel normal maps). Domain
// |xy| <= 1; outside it z is clamped to 0 rather than NaN.
fn reconstruct_tangent_z(xy: vec2<f32>) -> vec3<f32> {
    return vec3<f32>(xy, sqrt(max(0.0, 1.0 - dot(xy, xy))));
}

// Tangent space to world space (MikkTSpace convention: the bitangent is the cross product
// signed by tangent.w). Inputs need not be normalized; a zero result gives NaN.
fn tangent_to_world(tangent_normal: vec3<f32>, normal: vec3<f32>, tangent: vec4<f32>) -> vec3<f32> {
    let bitangent = cross(normal, tangent.xyz) * tangent.w;
    return normalize(tangent.xyz * tangent_normal.x + bitangent * tangent_normal.y + normal * tangent_normal.z);
}

// Octahedral encode (Cigolle et al. 2014): a unit vector to [-1, 1]^2, the lower hemisphere
// folded over the diagonals; the octahedral codec's map (gbuffer-core's codecs/octahedral.rs),
// before its quantisation. Domain: non-zero vectors (the L1 norm divides).
fn octahedral_encode(normal: vec3<f32>) -> vec2<f32> {
    return shading_library_octahedral_fold(normal);
}

// Octahedral decode (Cigolle et al. 2014): [-1, 1]^2 to a unit vector, the codec's inverse map.
fn octahedral_decode(encoded: vec2<f32>) -> vec3<f32> {
    return shading_library_octahedral_unfold(encoded);
}

// The naive mapping of a normal's [-1, 1] components to [0, 1] for unorm storage.
fn normal_to_unorm(normal: vec3<f32>) -> vec3<f32> {
    return normal * 0.5 + vec3<f32>(0.5);
}

// The inverse of normal_to_unorm, renormalized (quantization shortens the vector).
fn unorm_to_normal(encoded: vec3<f32>) -> vec3<f32> {
    return normalize(encoded * 2.0 - vec3<f32>(1.0));
}
