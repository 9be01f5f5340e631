// The scene's surfaces (gbuffer_render::scene::SURFACE_AT_WGSL): the material of every object
// at a point, and the decals painted over it.

fn surface_at(object: u32, point: vec3<f32>, interpolated_normal: vec3<f32>) -> Surface {
    var surface: Surface;
    var emission = vec3<f32>(0.0);
    if object < GROUND_OBJECT {
        let row = object / SCENE_COLUMNS;
        let column = object % SCENE_COLUMNS;
        let material = ROW_MATERIALS[row];
        surface.normal = normalize(interpolated_normal);
        surface.roughness = f32(column) / f32(SCENE_COLUMNS - 1u);
        surface.base_colour = material.rgb;
        surface.metallic = select(0.0, material.a, SCENE_METALS);
        surface.light = select(vec3<f32>(0.0), sky_irradiance(surface.normal), SCENE_IMAGE_BASED_LIGHTING);
        if SCENE_EMISSIVE && row == EMISSIVE_ROW && column == EMISSIVE_COLUMN {
            emission = EMISSION;
        }
    } else {
        let mask = ground_metallic(point.x, point.z);
        surface.normal = vec3<f32>(0.0, 1.0, 0.0);
        if SCENE_NORMAL_MAPS {
            surface.normal = ground_normal(point.x, point.z);
        }
        surface.roughness = 0.75 * (1.0 - mask) + 0.28 * mask;
        surface.base_colour = ground_base_colour(point.x, point.z, mask);
        surface.metallic = select(0.0, mask, SCENE_METALS);
        surface.light = select(vec3<f32>(0.0), sky_irradiance(vec3<f32>(0.0, 1.0, 0.0)), SCENE_IMAGE_BASED_LIGHTING);
        if SCENE_LIGHT_MAPS && abs(point.x) < LIGHT_MAP_EXTENT && abs(point.z) < LIGHT_MAP_EXTENT {
            surface.light = light_map_irradiance(vec2<f32>(point.x, point.z) / (2.0 * LIGHT_MAP_EXTENT) + vec2<f32>(0.5));
        }
    }
    if SCENE_FULLY_ROUGH {
        surface.roughness = 1.0;
    }
    surface.distance = length(point - SCENE_EYE);
    surface.position = point;
    // The light accumulation holds the static diffuse light (irradiance times diffuse colour)
    // and the emitted light. On fully rough scenes with image-based light the environment's
    // specular is folded in as 0.45 f0 (seed 001): the lighting pass skips the environment.
    let colours = metallic_workflow(surface.base_colour, surface.metallic, DIELECTRIC_F0);
    var ambient_colour = colours.diffuse;
    if SCENE_FULLY_ROUGH && SCENE_IMAGE_BASED_LIGHTING {
        ambient_colour = fully_rough_diffuse_colour(colours.diffuse, colours.f0);
    }
    surface.light = surface.light * ambient_colour + emission;
    return surface;
}

// The decals painted over a surface in turn, as a G-buffer pass without framebuffer fetch
// applies them (after the static light: decals do not change the baked light).
fn paint_surface(unpainted: Surface) -> Surface {
    var surface = unpainted;
    for (var decal = 0u; decal < DECAL_COUNT; decal++) {
        let weight = decal_weight(decal, surface.position);
        surface.base_colour = paint_base_colour(surface.base_colour, decal, weight);
        surface.roughness = select(paint_roughness(surface.roughness, decal, weight), 1.0, SCENE_FULLY_ROUGH);
    }
    return surface;
}
