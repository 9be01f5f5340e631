// textureSample needs derivatives, which compute shaders do not have.
@group(0) @binding(0) var environment: texture_2d<f32>;
@group(0) @binding(1) var linear: sampler;
@group(0) @binding(2) var<storage, read_write> result: array<vec4<f32>>;

@compute @workgroup_size(1)
fn main() {
    result[0] = textureSample(environment, linear, vec2<f32>(0.5));
}
