// An unsigned integer passed where the function takes a float.
fn double(value: f32) -> f32 {
    return value * 2.0;
}

@fragment
fn main() -> @location(0) vec4<f32> {
    let twice = double(1u);
    return vec4<f32>(twice);
}
