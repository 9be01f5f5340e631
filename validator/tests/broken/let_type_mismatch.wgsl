// A float where the declaration says u32.
@fragment
fn main() -> @location(0) vec4<f32> {
    var x: f32 = 1.0;
    let y: u32 = x;
    return vec4<f32>(x);
}
