// The mistake is in the included file, and is reported there.
#include "parts/brdf_helper.wgsl"

@fragment
fn main() -> @location(0) vec4<f32> {
    return vec4<f32>(tint(vec3<f32>(1.0)));
}
