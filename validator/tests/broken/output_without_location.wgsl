// A fragment output with no @location.
@fragment
fn main() -> vec4<f32> {
    return vec4<f32>(1.0);
}
