//! The reference scene, analytic so that the GPU renderer and the CPU reference see the same
//! thing at every pixel: a wall of spheres across roughness 0 to 1 (dielectric and metal rows
//! in several base colours) on a ground plane where gold meets stone through a filtered
//! metallic mask (the halo case of GPU Pro 7, Figure 2.4), with a procedural normal map and a
//! static diffuse light map; a directional sun; and a smooth procedural sky as the image-based
//! light.
//!
//! The scene is written twice, in WGSL (`SCENE_WGSL`, for the G-buffer pass) and in Rust f64
//! (for the reference), side by side: the same numbers, the same formulas.

use gbuffer::glam::{DVec2, DVec3, DVec4};
use gbuffer::shading::reference as r;
use gbuffer_scenes::{Feature, Features};

/// Sphere grid: columns of roughness, rows of material.
pub const COLUMNS: usize = 6;
/// Rows of the sphere grid: one material each.
pub const ROWS: usize = 4;
/// The spheres' radius.
pub const SPHERE_RADIUS: f64 = 0.32;
/// (base colour, metallic) per row, bottom to top.
pub const ROW_MATERIALS: [([f64; 3], f64); ROWS] = [
    ([0.8, 0.1, 0.08], 0.0),      // red plastic
    ([1.0, 0.766, 0.336], 1.0),   // gold
    ([0.9, 0.9, 0.88], 0.0),      // white ceramic
    ([0.955, 0.637, 0.538], 1.0), // copper
];

/// The camera's position.
pub const EYE: [f64; 3] = [0.0, 1.6, -5.4];
/// The point the camera looks at.
pub const TARGET: [f64; 3] = [0.0, 1.25, 0.0];
/// Vertical field of view, degrees.
pub const FIELD_OF_VIEW: f64 = 42.0;

/// Towards the sun, and its colour.
pub const SUN_DIRECTION: [f64; 3] = [0.4, 0.8, -0.45];
/// The sun's radiance.
pub const SUN_COLOUR: [f64; 3] = [3.0, 2.85, 2.6];

/// The sphere that glows when the scene has emissive surfaces (row, column), and its emission.
pub const EMISSIVE_SPHERE: (usize, usize) = (2, 0);
/// The glowing sphere's emitted radiance.
pub const EMISSION: [f64; 3] = [4.0, 1.6, 0.5];

/// Point lights (when the scene has them): positions and colours, and the radius where their
/// windowed falloff reaches 0.
pub const POINT_LIGHTS: [([f64; 3], [f64; 3]); 2] = [
    ([-1.2, 0.35, -0.9], [6.0, 3.0, 1.2]),
    ([1.4, 0.5, -0.8], [1.5, 3.0, 6.0]),
];
/// Distance at which a point light's windowed falloff reaches 0.
pub const POINT_LIGHT_RADIUS: f64 = 5.0;

/// The sky: radiance A + B.d + C max(d.s, 0)^8 (a gradient and a broad glow towards the sun).
pub const SKY_A: [f64; 3] = [0.55, 0.62, 0.75];
/// The sky's gradient term B.
pub const SKY_B: [f64; 3] = [0.15, 0.45, 0.75];
/// The sky's glow term C.
pub const SKY_C: [f64; 3] = [1.2, 1.0, 0.7];

/// The light map covers the ground over x in [-4, 4], z in [-4, 4].
pub const LIGHT_MAP_EXTENT: f64 = 4.0;
/// RGBM range of the light map (squared variant, as GPU Pro 7 Listing 2.5) and of the
/// prefiltered environment (plain RGBM).
pub const LIGHT_MAP_RANGE: f64 = 6.0;
/// RGBM range of the prefiltered environment.
pub const ENVIRONMENT_RANGE: f64 = 8.0;
/// The prefiltered environment's mips: roughness r reads mip r * ENVIRONMENT_MIPS (Listing 2.6).
pub const ENVIRONMENT_MIPS: u32 = 6;

fn v3(value: [f64; 3]) -> DVec3 {
    DVec3::from_array(value)
}

/// The centre of the sphere at `column` (roughness) and `row` (material).
pub fn sphere_centre(column: usize, row: usize) -> DVec3 {
    DVec3::new(-2.0 + 0.8 * column as f64, 0.42 + 0.75 * row as f64, 0.0)
}

/// The sphere's roughness: 0 to 1 across the columns.
pub fn sphere_roughness(column: usize) -> f64 {
    column as f64 / (COLUMNS - 1) as f64
}

/// The camera ray through a pixel centre: origin and unit direction.
pub fn camera_ray(x: f64, y: f64, width: f64, height: f64) -> (DVec3, DVec3) {
    let eye = v3(EYE);
    let forward = (v3(TARGET) - eye).normalize();
    let right = DVec3::Y.cross(forward).normalize();
    let up = forward.cross(right);
    let half_height = (FIELD_OF_VIEW.to_radians() * 0.5).tan();
    let half_width = half_height * width / height;
    let ndc_x = (x + 0.5) / width * 2.0 - 1.0;
    let ndc_y = 1.0 - (y + 0.5) / height * 2.0;
    (
        eye,
        (forward + right * (ndc_x * half_width) + up * (ndc_y * half_height)).normalize(),
    )
}

/// The sky's radiance in a direction.
pub fn sky(direction: DVec3) -> DVec3 {
    let glow = direction
        .dot(v3(SUN_DIRECTION).normalize())
        .max(0.0)
        .powi(8);
    v3(SKY_A) + v3(SKY_B) * direction.y + v3(SKY_C) * glow
}

/// What a surface point carries into the G-buffer.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// The shading normal, unit length.
    pub normal: DVec3,
    /// Perceptual roughness.
    pub roughness: f64,
    /// Base colour, linear.
    pub base_colour: DVec3,
    /// Metallic, 0 or 1 (between on the gold/stone mask's edge).
    pub metallic: f64,
    /// The static diffuse irradiance (divided by pi) reaching it: the light map on the ground,
    /// the sky's cosine-weighted average on the spheres (without image-based light, only
    /// the light map).
    pub irradiance: DVec3,
    /// The light it emits.
    pub emission: DVec3,
    /// Distance from the eye along the ray.
    pub distance: f64,
}

/// The static diffuse irradiance of the sky gradient for a normal (A + 2/3 B.n: the
/// cosine-weighted mean of a linear function over the hemisphere), without the glow.
pub fn sky_irradiance(normal: DVec3) -> DVec3 {
    v3(SKY_A) + v3(SKY_B) * (2.0 / 3.0 * normal.y)
}

/// The light map's content: the sky irradiance on the ground, darkened under the spheres.
pub fn light_map(x: f64, z: f64) -> DVec3 {
    let mut visibility = 1.0;
    for row in 0..ROWS {
        for column in 0..COLUMNS {
            let centre = sphere_centre(column, row);
            let distance_squared = (x - centre.x).powi(2) + (z - centre.z).powi(2);
            let strength = 0.55 / (1.0 + 2.0 * centre.y);
            visibility *=
                1.0 - strength * (-distance_squared / (SPHERE_RADIUS * SPHERE_RADIUS * 2.0)).exp();
        }
    }
    sky_irradiance(DVec3::Y) * visibility
}

/// The ground's material at (x, z): stone and gold meeting along a wavy line, the metallic
/// mask filtered across it.
pub fn ground_material(x: f64, z: f64) -> (DVec3, f64, f64) {
    let boundary = 0.6 * (z * 1.3).sin() + 0.8;
    let metallic = smoothstep(-0.25, 0.25, x - boundary);
    let checker = if ((x * 1.5).floor() + (z * 1.5).floor()).rem_euclid(2.0) == 0.0 {
        0.42
    } else {
        0.3
    };
    let stone = DVec3::new(checker, checker * 0.95, checker * 0.9);
    let gold = DVec3::new(1.0, 0.766, 0.336);
    // Base colour and roughness filter with the mask, as their texture would.
    (
        stone * (1.0 - metallic) + gold * metallic,
        0.75 * (1.0 - metallic) + 0.28 * metallic,
        metallic,
    )
}

fn smoothstep(low: f64, high: f64, value: f64) -> f64 {
    let t = ((value - low) / (high - low)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The ground's normal map at (x, z): a tangent-space xy, z reconstructed.
pub fn ground_normal(x: f64, z: f64) -> DVec3 {
    let tangent_xy = DVec2::new(
        (x * 5.0).cos() * (z * 3.0).sin(),
        (z * 5.0).cos() * (x * 3.0).sin(),
    ) * 0.18;
    let tangent_normal = r::normals::reconstruct_tangent_z(tangent_xy);
    // The plane's tangent frame: tangent +x, normal +y (the bitangent is their cross product).
    r::normals::tangent_to_world(tangent_normal, DVec3::Y, DVec4::new(1.0, 0.0, 0.0, 1.0))
}

/// The first surface a ray meets, if any, as a scene of these features shows it: without
/// metals every metallic is 0, fully rough scenes have roughness 1, normal maps, light maps,
/// image-based light and the emissive sphere come and go with their features.
pub fn trace(origin: DVec3, direction: DVec3, features: Features) -> Option<Surface> {
    let has = |feature| features.contains(feature);
    let metals = if has(Feature::Metals) { 1.0 } else { 0.0 };
    let sky_light = |normal: DVec3| {
        if has(Feature::ImageBasedLighting) {
            sky_irradiance(normal)
        } else {
            DVec3::ZERO
        }
    };
    let roughness_of = |roughness: f64| {
        if has(Feature::FullyRough) {
            1.0
        } else {
            roughness
        }
    };
    let mut nearest: Option<(f64, usize, usize)> = None;
    for row in 0..ROWS {
        for column in 0..COLUMNS {
            let offset = origin - sphere_centre(column, row);
            let b = offset.dot(direction);
            let c = offset.dot(offset) - SPHERE_RADIUS * SPHERE_RADIUS;
            let discriminant = b * b - c;
            if discriminant > 0.0 {
                let distance = -b - discriminant.sqrt();
                if distance > 0.0 && nearest.is_none_or(|(best, _, _)| distance < best) {
                    nearest = Some((distance, column, row));
                }
            }
        }
    }
    let ground = if direction.y < 0.0 {
        Some(-origin.y / direction.y)
    } else {
        None
    };
    match (nearest, ground) {
        (Some((distance, column, row)), ground)
            if ground.is_none_or(|ground| distance < ground) =>
        {
            let point = origin + direction * distance;
            let normal = (point - sphere_centre(column, row)).normalize();
            let (base_colour, metallic) = ROW_MATERIALS[row];
            let glows = has(Feature::Emissive) && (row, column) == EMISSIVE_SPHERE;
            Some(Surface {
                normal,
                roughness: roughness_of(sphere_roughness(column)),
                base_colour: v3(base_colour),
                metallic: metallic * metals,
                irradiance: sky_light(normal),
                emission: if glows { v3(EMISSION) } else { DVec3::ZERO },
                distance,
            })
        }
        (_, Some(distance)) if distance < 40.0 => {
            let point = origin + direction * distance;
            let (base_colour, roughness, mask) = ground_material(point.x, point.z);
            let inside = point.x.abs() < LIGHT_MAP_EXTENT && point.z.abs() < LIGHT_MAP_EXTENT;
            let irradiance = if inside && has(Feature::LightMaps) {
                light_map(point.x, point.z)
            } else {
                sky_light(DVec3::Y)
            };
            let normal = if has(Feature::NormalMaps) {
                ground_normal(point.x, point.z)
            } else {
                DVec3::Y
            };
            Some(Surface {
                normal,
                roughness: roughness_of(roughness),
                base_colour,
                metallic: mask * metals,
                irradiance,
                emission: DVec3::ZERO,
                distance,
            })
        }
        _ => None,
    }
}

/// The scene in WGSL for the G-buffer pass: the same constants and functions as above, and the
/// features as constants.
pub fn scene_wgsl(features: Features) -> String {
    let components = |value: [f64; 3]| {
        format!(
            "{:?}, {:?}, {:?}",
            value[0] as f32, value[1] as f32, value[2] as f32
        )
    };
    let vec3 = |value: [f64; 3]| format!("vec3<f32>({})", components(value));
    let materials: Vec<String> = ROW_MATERIALS
        .iter()
        .map(|(colour, metallic)| {
            format!("vec4<f32>({}, {:?})", components(*colour), *metallic as f32)
        })
        .collect();
    format!(
        r#"// ---- the reference scene (examples/src/scene.rs) ----
const SCENE_COLUMNS: u32 = {COLUMNS}u;
const SCENE_ROWS: u32 = {ROWS}u;
const SPHERE_RADIUS: f32 = {SPHERE_RADIUS:?};
const SCENE_EYE: vec3<f32> = {eye};
const SCENE_TARGET: vec3<f32> = {target};
const SCENE_HALF_HEIGHT: f32 = {half_height:?};
const SUN_DIRECTION: vec3<f32> = {sun};
const SUN_COLOUR: vec3<f32> = {sun_colour};
const SKY_A: vec3<f32> = {sky_a};
const SKY_B: vec3<f32> = {sky_b};
const SKY_C: vec3<f32> = {sky_c};
const LIGHT_MAP_EXTENT: f32 = {extent:?};
const LIGHT_MAP_RANGE: f32 = {light_map_range:?};
const ENVIRONMENT_RANGE: f32 = {environment_range:?};
const ENVIRONMENT_MIPS: f32 = {mips:?};
const ROW_MATERIALS: array<vec4<f32>, {ROWS}> = array<vec4<f32>, {ROWS}>({materials});
const EMISSIVE_ROW: u32 = {emissive_row}u;
const EMISSIVE_COLUMN: u32 = {emissive_column}u;
const EMISSION: vec3<f32> = {emission};
const POINT_LIGHT_COUNT: u32 = {point_light_count}u;
const POINT_LIGHT_POSITIONS: array<vec3<f32>, {point_light_count}> = array<vec3<f32>, {point_light_count}>({point_light_positions});
const POINT_LIGHT_COLOURS: array<vec3<f32>, {point_light_count}> = array<vec3<f32>, {point_light_count}>({point_light_colours});
const POINT_LIGHT_RADIUS: f32 = {point_light_radius:?};
// The scene's features.
const SCENE_METALS: bool = {metals};
const SCENE_NORMAL_MAPS: bool = {normal_maps};
const SCENE_EMISSIVE: bool = {emissive};
const SCENE_IMAGE_BASED_LIGHTING: bool = {image_based_lighting};
const SCENE_LIGHT_MAPS: bool = {light_maps};
const SCENE_FULLY_ROUGH: bool = {fully_rough};

fn sphere_centre(column: u32, row: u32) -> vec3<f32> {{
    return vec3<f32>(-2.0 + 0.8 * f32(column), 0.42 + 0.75 * f32(row), 0.0);
}}

fn camera_ray(pixel: vec2<f32>, size: vec2<f32>) -> vec3<f32> {{
    let forward = normalize(SCENE_TARGET - SCENE_EYE);
    let right = normalize(cross(vec3<f32>(0.0, 1.0, 0.0), forward));
    let up = cross(forward, right);
    let half_width = SCENE_HALF_HEIGHT * size.x / size.y;
    let ndc = vec2<f32>(pixel.x / size.x * 2.0 - 1.0, 1.0 - pixel.y / size.y * 2.0);
    return normalize(forward + right * (ndc.x * half_width) + up * (ndc.y * SCENE_HALF_HEIGHT));
}}

fn sky(direction: vec3<f32>) -> vec3<f32> {{
    let glow = pow(max(dot(direction, SUN_DIRECTION), 0.0), 8.0);
    return SKY_A + SKY_B * direction.y + SKY_C * glow;
}}

fn sky_irradiance(normal: vec3<f32>) -> vec3<f32> {{
    return SKY_A + SKY_B * (2.0 / 3.0 * normal.y);
}}

fn ground_metallic(x: f32, z: f32) -> f32 {{
    let boundary = 0.6 * sin(z * 1.3) + 0.8;
    return smoothstep(-0.25, 0.25, x - boundary);
}}

fn ground_base_colour(x: f32, z: f32, metallic: f32) -> vec3<f32> {{
    let parity = (floor(x * 1.5) + floor(z * 1.5)) - 2.0 * floor((floor(x * 1.5) + floor(z * 1.5)) * 0.5);
    let checker = select(0.3, 0.42, parity == 0.0);
    let stone = vec3<f32>(checker, checker * 0.95, checker * 0.9);
    return stone * (1.0 - metallic) + vec3<f32>(1.0, 0.766, 0.336) * metallic;
}}

fn ground_normal(x: f32, z: f32) -> vec3<f32> {{
    let tangent_xy = vec2<f32>(cos(x * 5.0) * sin(z * 3.0), cos(z * 5.0) * sin(x * 3.0)) * 0.18;
    return tangent_to_world(reconstruct_tangent_z(tangent_xy), vec3<f32>(0.0, 1.0, 0.0), vec4<f32>(1.0, 0.0, 0.0, 1.0));
}}
"#,
        eye = vec3(EYE),
        target = vec3(TARGET),
        half_height = (FIELD_OF_VIEW.to_radians() * 0.5).tan() as f32,
        sun = vec3(v3(SUN_DIRECTION).normalize().to_array()),
        sun_colour = vec3(SUN_COLOUR),
        sky_a = vec3(SKY_A),
        sky_b = vec3(SKY_B),
        sky_c = vec3(SKY_C),
        extent = LIGHT_MAP_EXTENT as f32,
        light_map_range = LIGHT_MAP_RANGE as f32,
        environment_range = ENVIRONMENT_RANGE as f32,
        mips = ENVIRONMENT_MIPS as f32,
        materials = materials.join(", "),
        emissive_row = EMISSIVE_SPHERE.0,
        emissive_column = EMISSIVE_SPHERE.1,
        emission = vec3(EMISSION),
        point_light_count = POINT_LIGHTS.len(),
        point_light_positions = POINT_LIGHTS.map(|(position, _)| vec3(position)).join(", "),
        point_light_colours = POINT_LIGHTS.map(|(_, colour)| vec3(colour)).join(", "),
        point_light_radius = POINT_LIGHT_RADIUS as f32,
        metals = features.contains(Feature::Metals),
        normal_maps = features.contains(Feature::NormalMaps),
        emissive = features.contains(Feature::Emissive),
        image_based_lighting = features.contains(Feature::ImageBasedLighting),
        light_maps = features.contains(Feature::LightMaps),
        fully_rough = features.contains(Feature::FullyRough),
    )
}
