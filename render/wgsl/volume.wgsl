// Light and decal volumes (gbuffer_render::shaders::VOLUME_WGSL): the screen rectangle around a
// point light's reach or a decal's box, so a volume costs only the pixels it can touch.

fn volume_rectangle(vertex: u32, volume: u32) -> vec2<f32> {
    var centre: vec3<f32>;
    var half_size: vec3<f32>;
    if volume < POINT_LIGHT_COUNT {
        centre = POINT_LIGHT_POSITIONS[volume];
        half_size = vec3<f32>(POINT_LIGHT_RADIUS);
    } else {
        centre = DECAL_CENTRES[volume - POINT_LIGHT_COUNT];
        half_size = DECAL_HALF_SIZES[volume - POINT_LIGHT_COUNT];
    }
    var low = vec2<f32>(1.0);
    var high = vec2<f32>(-1.0);
    var behind = false;
    for (var corner = 0u; corner < 8u; corner++) {
        let sign = vec3<f32>(f32(corner & 1u), f32((corner >> 1u) & 1u), f32((corner >> 2u) & 1u)) * 2.0 - vec3<f32>(1.0);
        let clip = clip_position(centre + sign * half_size, VIEWPORT, CLIP_Y_SIGN);
        behind = behind || clip.w <= CAMERA_NEAR;
        let ndc = clip.xy / max(clip.w, 1e-6);
        low = min(low, ndc);
        high = max(high, ndc);
    }
    if behind {
        low = vec2<f32>(-1.0);
        high = vec2<f32>(1.0);
    }
    // (low, low) (high, low) (high, high), (low, low) (high, high) (low, high).
    var corners = array<vec2<f32>, 6>(vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0), vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 1.0), vec2<f32>(0.0, 1.0));
    return mix(clamp(low, vec2<f32>(-1.0), vec2<f32>(1.0)), clamp(high, vec2<f32>(-1.0), vec2<f32>(1.0)), corners[vertex]);
}
