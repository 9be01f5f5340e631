// The vertex shaders of the fused on-tile paths (gbuffer_render::on_tile::VERTEX_WGSL): the
// surfaces and sky as fullscreen triangles at set depths, and the volumes' rectangles.

// Fullscreen draws over the surfaces sit here in depth; the farthest surface is well in front.
const SURFACES_DEPTH: f32 = 0.99999;

@vertex
fn surfaces_vertex(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(fullscreen_corner(vertex), SURFACES_DEPTH, 1.0);
}

@vertex
fn sky_vertex(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(fullscreen_corner(vertex), 1.0, 1.0);
}

// Volume `volume`'s screen rectangle (`volume_rectangle`), over the surfaces. The fragment
// stage reads the volume from the host (a uniform on GLES, a push constant on Vulkan).
@vertex
fn volume_vertex(@builtin(vertex_index) vertex: u32, @location(0) volume: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(volume_rectangle(vertex, volume), SURFACES_DEPTH, 1.0);
}
