// A statement without its semicolon.
@fragment
fn main() -> @location(0) vec4<f32> {
    let x = 1.0
    return vec4<f32>(x);
}
