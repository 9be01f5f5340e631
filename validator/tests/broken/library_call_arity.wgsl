// d_ggx takes the cosine and the roughness.
#include <gbuffer/microfacet>

@fragment
fn main() -> @location(0) vec4<f32> {
    let d = d_ggx(0.5);
    return vec4<f32>(d);
}
