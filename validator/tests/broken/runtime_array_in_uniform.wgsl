// A runtime-sized array cannot live in a uniform buffer.
@group(0) @binding(0) var<uniform> weights: array<f32>;

@compute @workgroup_size(1)
fn main() {
    let first = weights[0];
}
