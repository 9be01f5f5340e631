// A function that returns an integer where it declares a float.
fn half_of(value: f32) -> f32 {
    return 1u;
}

@fragment
fn main() -> @location(0) vec4<f32> {
    return vec4<f32>(half_of(0.5));
}
