// The layout's depth is an f32: it has no `.x`.
#include "../../../codegen/layouts/mobile_metallic.toml"

@fragment
fn main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let words = array<u32, 4>(1u, 2u, 3u, 4u);
    let texel = unpack_mobile_metallic(words);
    return vec4<f32>(texel.depth.x);
}
