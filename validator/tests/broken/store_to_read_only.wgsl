// A store into a read-only storage buffer.
@group(0) @binding(0) var<storage, read> counts: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    counts[id.x] = 1u;
}
