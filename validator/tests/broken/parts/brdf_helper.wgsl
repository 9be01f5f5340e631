// An included helper with a mistake of its own: vec3 has no `w`.
fn tint(colour: vec3<f32>) -> f32 {
    return colour.w;
}
