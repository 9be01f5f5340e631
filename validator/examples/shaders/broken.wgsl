// A shader with a mistake: d_ggx takes two arguments.
#include <gbuffer/microfacet>

@fragment
fn broken() -> @location(0) vec4<f32> {
    let d = d_ggx(0.5);
    return vec4<f32>(d);
}
