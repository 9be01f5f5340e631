//! The CPU reference renderer: the same triangles, decals, shading and tone mapping in f64,
//! without packing, without texture filtering, with every integral evaluated at the pixel: the full
//! model a specialised lighting pass is measured against.

use gbuffer_shading::reference as r;
use gbuffer_solver::{Feature, Features};
use glam::DVec3;

use crate::mesh::Mesh;
use crate::options::{Frame, EXPOSURE};
use crate::scene::{self, sky, Surface};

/// Importance samples per texel of the prefiltered environment and per LUT texel: the baked
/// inputs ([`crate::inputs`]) and this reference integrate with the same estimator.
pub const PREFILTER_SAMPLES: u32 = 256;

/// The GGX lobe of `roughness` around `normal` (n = v = r) integrated over the sky with the
/// renderer's estimator, at the exact roughness and direction (the GPU reads it from mips).
pub fn prefiltered_sky(normal: DVec3, roughness: f64) -> DVec3 {
    if roughness == 0.0 {
        return sky(normal);
    }
    let up = if normal.z.abs() < 0.999 {
        DVec3::Z
    } else {
        DVec3::X
    };
    let tangent = up.cross(normal).normalize();
    let bitangent = normal.cross(tangent);
    let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
    for index in 0..PREFILTER_SAMPLES {
        let local = r::environment::importance_sample_ggx(
            r::environment::hammersley(index, PREFILTER_SAMPLES),
            roughness,
        );
        let half_vector = tangent * local.x + bitangent * local.y + normal * local.z;
        let light = 2.0 * normal.dot(half_vector) * half_vector - normal;
        let n_dot_l = normal.dot(light);
        if n_dot_l > 0.0 {
            sum += sky(light) * n_dot_l;
            weight += n_dot_l;
        }
    }
    sum / weight
}

/// The linear radiance of one pixel of the scene with these features, by the full model: the
/// accurate forms, the environment's specular at every roughness, exact integrals.
pub fn radiance(
    mesh: &Mesh,
    (x, y): (u32, u32),
    (width, height): (u32, u32),
    features: Features,
) -> DVec3 {
    let (origin, direction) = scene::camera_ray(
        f64::from(x),
        f64::from(y),
        f64::from(width),
        f64::from(height),
    );
    let Some(surface) = trace(mesh, origin, direction, features) else {
        return sky(direction);
    };
    let colours = r::material::metallic_workflow(
        surface.base_colour,
        surface.metallic,
        r::constants::DIELECTRIC_F0,
    );
    let light = surface.light;
    let view = -direction;
    let normal = surface.normal;
    let n_dot_v = normal.dot(view).clamp(r::constants::MIN_N_DOT_V, 1.0);
    let reflected = 2.0 * normal.dot(view) * normal - view;
    let env_brdf =
        r::environment::integrate_env_brdf(surface.roughness, n_dot_v, PREFILTER_SAMPLES);
    let shade = |direction: DVec3, colour: DVec3| {
        r::shading::shade_directional(
            normal,
            view,
            direction,
            colour,
            colours.diffuse,
            colours.f0,
            surface.roughness,
            env_brdf,
        )
    };
    let mut radiance = if features.contains(Feature::ImageBasedLighting) {
        r::shading::shade_ibl(
            light,
            colours.f0,
            DVec3::ONE,
            prefiltered_sky(reflected, surface.roughness),
            env_brdf,
        )
    } else {
        light
    };
    if features.contains(Feature::Sun) {
        radiance += shade(
            DVec3::from_array(scene::SUN_DIRECTION).normalize(),
            DVec3::from_array(scene::SUN_COLOUR),
        );
    }
    if features.contains(Feature::PointLights) {
        let position = origin + direction * surface.distance;
        for (light_position, colour) in scene::point_lights() {
            let to_light = DVec3::from_array(light_position) - position;
            let distance = to_light.length();
            let falloff = r::shading::point_light_falloff(distance, scene::POINT_LIGHT_RADIUS);
            radiance += shade(
                to_light / distance.max(1e-4),
                DVec3::from_array(colour) * falloff,
            );
        }
    }
    radiance
}

/// Renders the frame on the CPU (rows shared between threads), calling `progress` with the
/// fraction done.
pub fn render(
    width: u32,
    height: u32,
    features: Features,
    progress: &(dyn Fn(f64) + Sync),
) -> Frame {
    let mesh = &Mesh::scene();
    let pixels = crate::parallel::rows(
        height,
        |y| {
            (0..width)
                .map(|x| display(radiance(mesh, (x, y), (width, height), features)))
                .collect()
        },
        |finished| {
            if finished % (height / 10).max(1) == 0 {
                progress(f64::from(finished) / f64::from(height));
            }
        },
    );
    Frame {
        width,
        height,
        pixels,
    }
}

/// Exposure, the ACES fit, sRGB, 8 bits: as the tone-mapping pass.
pub fn display(radiance: DVec3) -> [u8; 4] {
    let encoded = r::colour::linear_to_srgb(r::tonemap::tonemap_aces_fitted(radiance * EXPOSURE));
    let channel = |value: f64| (value.clamp(0.0, 1.0) * 255.0).round() as u8;
    [
        channel(encoded.x),
        channel(encoded.y),
        channel(encoded.z),
        255,
    ]
}

/// The first surface a ray meets on the scene's mesh, if any.
pub fn trace(mesh: &Mesh, origin: DVec3, direction: DVec3, features: Features) -> Option<Surface> {
    let hit = mesh.intersect(origin, direction)?;
    let point = origin + direction * hit.distance;
    Some(scene::surface_at(
        hit.object,
        point,
        hit.normal,
        hit.distance,
        features,
    ))
}
