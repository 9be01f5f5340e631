// tonemap: HDR scene colour to displayable [0, 1].
// requires:

// Reinhard (Reinhard et al. 2002), per channel: c / (1 + c). Domain [0, inf).
fn tonemap_reinhard(linear: vec3<f32>) -> vec3<f32> {
    return linear / (vec3<f32>(1.0) + linear);
}

// The ACES filmic curve fitted by Narkowicz (2015), input pre-exposed (x 0.6 matches the
// reference ACES). Domain [0, inf); clamped to [0, 1].
fn tonemap_aces_fitted(linear: vec3<f32>) -> vec3<f32> {
    let numerator = linear * (2.51 * linear + vec3<f32>(0.03));
    let denominator = linear * (2.43 * linear + vec3<f32>(0.59)) + vec3<f32>(0.14);
    return clamp(numerator / denominator, vec3<f32>(0.0), vec3<f32>(1.0));
}
