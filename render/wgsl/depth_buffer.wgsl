// The depth buffer, and the position it gives the surface at a pixel
// (gbuffer_render::shaders, for lighting passes that read positions from it).

@group(0) @binding(4) var depth_buffer: texture_depth_2d;

// Where the surface at `pixel` lies: the depth buffer's depth along the camera ray.
fn surface_position(pixel: vec2<i32>, direction: vec3<f32>) -> vec3<f32> {
    let depth = textureLoad(depth_buffer, pixel, 0);
    let view_depth = CAMERA_NEAR / (1.0 - depth * (CAMERA_FAR - CAMERA_NEAR) / CAMERA_FAR);
    return SCENE_EYE + direction * (view_depth / dot(direction, normalize(SCENE_TARGET - SCENE_EYE)));
}
