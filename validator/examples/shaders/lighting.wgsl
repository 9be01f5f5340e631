// A lighting pass over the Listing 2.2 G-buffer: reads the packed Rgba32Uint target, unpacks
// it with the generated code and shades it with the library.
#include <gbuffer/shading>
#include <gbuffer/colour>
#include <gbuffer/environment>
#include "../../../codegen/layouts/mobile_metallic.toml"

@group(0) @binding(0) var gbuffer: texture_2d<u32>;

@fragment
fn lighting(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let texel = unpack_mobile_metallic_targets(MobileMetallicTargets(textureLoad(gbuffer, vec2<i32>(position.xy), 0)));
    let normal = normalize(texel.normals_roughness.xyz * 2.0 - 1.0);
    let base_colour = pseudo_gamma_to_linear(texel.albedo_metallic.rgb);
    let metallic = texel.albedo_metallic.a;
    let diffuse_colour = base_colour * (1.0 - metallic);
    let f0 = mix(vec3<f32>(DIELECTRIC_F0), base_colour, metallic);
    // The split-sum (scale, bias); a renderer reads it from its LUT.
    let env_brdf = integrate_env_brdf(texel.normals_roughness.w, 1.0, 16u);
    let colour = shade_directional(normal, vec3<f32>(0.0, 0.0, 1.0), normalize(vec3<f32>(0.3, 0.5, 0.8)), vec3<f32>(3.0), diffuse_colour, f0, texel.normals_roughness.w, env_brdf);
    return vec4<f32>(colour + texel.light_accumulation, 1.0);
}
