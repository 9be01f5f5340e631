//! The reference scene, as triangles (`mesh`) that every backend rasterises and the CPU
//! reference ray-casts, so that both see the same thing at every pixel: a wall of spheres across roughness 0 to 1 (dielectric and metal rows
//! in several base colours) on a ground plane where gold meets stone through a filtered
//! metallic mask (the halo case of GPU Pro 7, Figure 2.4), with a procedural normal map and a
//! static diffuse light map; a directional sun; and a smooth procedural sky as the image-based
//! light.
//!
//! The scene is written twice, in WGSL (`SCENE_WGSL`, for the G-buffer pass) and in Rust f64
//! (for the reference), side by side: the same numbers, the same formulas.

use gbuffer_shading::reference as r;
use gbuffer_solver::{Feature, Features};
use glam::{DVec2, DVec3, DVec4};

/// Sphere grid: columns of roughness, rows of material.
pub const COLUMNS: usize = 6;
/// Rows of the sphere grid: one material each.
pub const ROWS: usize = 4;
/// The ground's object index; spheres are `0..GROUND`.
pub const GROUND: u32 = (ROWS * COLUMNS) as u32;
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
/// The near and far planes of the rasterised depth (the depth buffer's range).
pub const CAMERA_NEAR: f64 = 0.05;
/// The far plane.
pub const CAMERA_FAR: f64 = 100.0;

/// Towards the sun, and its colour.
pub const SUN_DIRECTION: [f64; 3] = [0.4, 0.8, -0.45];
/// The sun's radiance.
pub const SUN_COLOUR: [f64; 3] = [3.0, 2.85, 2.6];

/// The sphere that glows when the scene has emissive surfaces (row, column), and its emission.
pub const EMISSIVE_SPHERE: (usize, usize) = (2, 0);
/// The glowing sphere's emitted radiance.
pub const EMISSION: [f64; 3] = [4.0, 1.6, 0.5];

/// How many point lights the scene has (when it has them): each is drawn as a light volume.
pub const POINT_LIGHT_COUNT: usize = 32;
/// Distance at which a point light's windowed falloff reaches 0: its light volume's radius.
pub const POINT_LIGHT_RADIUS: f64 = 1.1;

/// The point lights: positions and colours, in four rows of eight over the ground in front of
/// the spheres and between them, in a cycle of colours.
pub fn point_lights() -> [([f64; 3], [f64; 3]); POINT_LIGHT_COUNT] {
    const COLOURS: [[f64; 3]; 4] = [
        [1.6, 0.8, 0.3],
        [0.3, 0.9, 1.6],
        [1.2, 1.4, 0.5],
        [1.4, 0.4, 1.2],
    ];
    std::array::from_fn(|index| {
        let (row, column) = (index / 8, index % 8);
        let x = -2.8 + 0.8 * column as f64 + 0.2 * (row % 2) as f64;
        let y = 0.2 + 0.5 * row as f64;
        let z = -0.55 - 0.3 * (row % 2) as f64;
        ([x, y, z], COLOURS[(index + row) % COLOURS.len()])
    })
}

/// A decal: paint that blends base colour and roughness towards its own inside an
/// axis-aligned box, fading out over the outer 30% of each half-extent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Decal {
    /// The box's centre.
    pub centre: [f64; 3],
    /// Its half-extents.
    pub half_size: [f64; 3],
    /// The paint's base colour, linear.
    pub base_colour: [f64; 3],
    /// The paint's perceptual roughness.
    pub roughness: f64,
}

/// The scene's decals: two patches of paint on the ground (one across the gold/stone edge),
/// one band across the ceramic row, one across the copper row.
pub const DECALS: [Decal; 4] = [
    Decal::new([-1.6, 0.0, -1.4], [0.9, 0.3, 0.6], [0.05, 0.35, 0.6], 0.15),
    Decal::new([1.3, 0.0, -1.7], [0.8, 0.3, 0.5], [0.9, 0.9, 0.9], 0.9),
    Decal::new([-0.8, 1.92, -0.2], [0.7, 0.08, 0.5], [0.7, 0.05, 0.05], 0.5),
    Decal::new([1.2, 2.67, -0.2], [0.6, 0.25, 0.5], [0.1, 0.1, 0.1], 0.05),
];

impl Decal {
    /// A decal: its box's centre and half-extents, and its paint's colour and roughness.
    const fn new(
        centre: [f64; 3],
        half_size: [f64; 3],
        base_colour: [f64; 3],
        roughness: f64,
    ) -> Decal {
        Decal {
            centre,
            half_size,
            base_colour,
            roughness,
        }
    }
}

/// How strongly decal `decal` paints the point: 1 inside, fading to 0 over the outer 30% of
/// each half-extent (a smooth edge, so a one-pixel difference in where a surface lies
/// changes little).
pub fn decal_weight(decal: &Decal, point: DVec3) -> f64 {
    let local = (point - v3(decal.centre)).abs() / v3(decal.half_size);
    local
        .to_array()
        .iter()
        .map(|&distance| 1.0 - smoothstep(0.7, 1.0, distance))
        .product()
}

/// The surface after the decals: each in turn blends base colour and roughness towards its
/// own by its weight (metallic stays: paint over gold is still gold underneath).
pub fn paint(surface: &mut Surface, point: DVec3) {
    for decal in &DECALS {
        let weight = decal_weight(decal, point);
        surface.base_colour = surface.base_colour.lerp(v3(decal.base_colour), weight);
        surface.roughness += (decal.roughness - surface.roughness) * weight;
    }
}

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

/// What the reference scene shows (the seed layouts and `classic` render it): metals, normal
/// maps, image-based light, light maps, the sun and the point lights.
pub fn reference_features() -> Features {
    Features::reference_scene().with(Feature::PointLights)
}

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
    /// The light accumulation's start: the static diffuse irradiance (the light map on the
    /// ground, the sky's cosine-weighted average on the spheres) times the diffuse colour
    /// before the decals (they do not change the baked light), plus the light it emits.
    pub light: DVec3,
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

/// The surface of `object` (a sphere index or [`GROUND`]) at `point`, with the mesh's
/// interpolated `normal`, as a scene of these features shows it: without metals every metallic
/// is 0, fully rough scenes have roughness 1, normal maps, light maps, image-based light and the
/// emissive sphere come and go with their features; the decals paint it.
pub fn surface_at(
    object: u32,
    point: DVec3,
    normal: DVec3,
    distance: f64,
    features: Features,
) -> Surface {
    let has = |feature| features.contains(feature);
    let metals = if has(Feature::Metals) { 1.0 } else { 0.0 };
    let sky_light = |normal: DVec3| {
        if has(Feature::ImageBasedLighting) {
            sky_irradiance(normal)
        } else {
            DVec3::ZERO
        }
    };
    // (normal, roughness, base colour, metallic, irradiance, emission)
    let (normal, roughness, base_colour, metallic, irradiance, emission) = if object < GROUND {
        let (row, column) = (object as usize / COLUMNS, object as usize % COLUMNS);
        let (base_colour, metallic) = ROW_MATERIALS[row];
        let glows = has(Feature::Emissive) && (row, column) == EMISSIVE_SPHERE;
        (
            normal,
            sphere_roughness(column),
            v3(base_colour),
            metallic * metals,
            sky_light(normal),
            if glows { v3(EMISSION) } else { DVec3::ZERO },
        )
    } else {
        let (base_colour, roughness, mask) = ground_material(point.x, point.z);
        let inside = point.x.abs() < LIGHT_MAP_EXTENT && point.z.abs() < LIGHT_MAP_EXTENT;
        (
            if has(Feature::NormalMaps) {
                ground_normal(point.x, point.z)
            } else {
                DVec3::Y
            },
            roughness,
            base_colour,
            mask * metals,
            if inside && has(Feature::LightMaps) {
                light_map(point.x, point.z)
            } else {
                sky_light(DVec3::Y)
            },
            DVec3::ZERO,
        )
    };
    let diffuse =
        r::material::metallic_workflow(base_colour, metallic, r::constants::DIELECTRIC_F0).diffuse;
    let mut surface = Surface {
        normal,
        roughness,
        base_colour,
        metallic,
        light: irradiance * diffuse + emission,
        distance,
    };
    paint(&mut surface, point);
    if has(Feature::FullyRough) {
        surface.roughness = 1.0;
    }
    surface
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
        r#"// ---- the reference scene (render/src/scene.rs) ----
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
const DECAL_COUNT: u32 = {decal_count}u;
const DECAL_CENTRES: array<vec3<f32>, {decal_count}> = array<vec3<f32>, {decal_count}>({decal_centres});
const DECAL_HALF_SIZES: array<vec3<f32>, {decal_count}> = array<vec3<f32>, {decal_count}>({decal_half_sizes});
const DECAL_COLOURS: array<vec3<f32>, {decal_count}> = array<vec3<f32>, {decal_count}>({decal_colours});
const DECAL_ROUGHNESS: array<f32, {decal_count}> = array<f32, {decal_count}>({decal_roughness});
const GROUND_OBJECT: u32 = {ground}u;
const CAMERA_NEAR: f32 = {near:?};
const CAMERA_FAR: f32 = {far:?};
// The scene's features.
const SCENE_METALS: bool = {metals};
const SCENE_NORMAL_MAPS: bool = {normal_maps};
const SCENE_EMISSIVE: bool = {emissive};
const SCENE_IMAGE_BASED_LIGHTING: bool = {image_based_lighting};
const SCENE_LIGHT_MAPS: bool = {light_maps};
const SCENE_FULLY_ROUGH: bool = {fully_rough};
const SCENE_SUN: bool = {sun_light};
const SCENE_POINT_LIGHTS: bool = {point_lights};

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

// World position to clip space for a `size` viewport: the projection `camera_ray` inverts,
// depth in [0, 1]. `y_sign` -1 renders upside down (GL's bottom-up rows, Vulkan's y-down NDC).
fn clip_position(position: vec3<f32>, size: vec2<f32>, y_sign: f32) -> vec4<f32> {{
    let forward = normalize(SCENE_TARGET - SCENE_EYE);
    let right = normalize(cross(vec3<f32>(0.0, 1.0, 0.0), forward));
    let up = cross(forward, right);
    let offset = position - SCENE_EYE;
    let depth = dot(offset, forward);
    let half_width = SCENE_HALF_HEIGHT * size.x / size.y;
    return vec4<f32>(dot(offset, right) / half_width, y_sign * dot(offset, up) / SCENE_HALF_HEIGHT, CAMERA_FAR / (CAMERA_FAR - CAMERA_NEAR) * (depth - CAMERA_NEAR), depth);
}}

// How strongly decal `decal` paints `point`: 1 inside its box, fading out over the outer 30%.
fn decal_weight(decal: u32, point: vec3<f32>) -> f32 {{
    let fade = vec3<f32>(1.0) - smoothstep(vec3<f32>(0.7), vec3<f32>(1.0), abs(point - DECAL_CENTRES[decal]) / DECAL_HALF_SIZES[decal]);
    return fade.x * fade.y * fade.z;
}}

// Decal `decal`'s paint over a base colour and roughness, by `weight`.
fn paint_base_colour(base_colour: vec3<f32>, decal: u32, weight: f32) -> vec3<f32> {{
    return mix(base_colour, DECAL_COLOURS[decal], weight);
}}

fn paint_roughness(roughness: f32, decal: u32, weight: f32) -> f32 {{
    return roughness + (DECAL_ROUGHNESS[decal] - roughness) * weight;
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
        point_light_count = POINT_LIGHT_COUNT,
        point_light_positions = point_lights()
            .map(|(position, _)| vec3(position))
            .join(", "),
        point_light_colours = point_lights().map(|(_, colour)| vec3(colour)).join(", "),
        decal_centres = DECALS.map(|decal| vec3(decal.centre)).join(", "),
        decal_half_sizes = DECALS.map(|decal| vec3(decal.half_size)).join(", "),
        decal_colours = DECALS.map(|decal| vec3(decal.base_colour)).join(", "),
        decal_roughness = DECALS
            .map(|decal| format!("{:?}", decal.roughness as f32))
            .join(", "),
        decal_count = DECALS.len(),
        ground = GROUND,
        point_light_radius = POINT_LIGHT_RADIUS as f32,
        metals = features.contains(Feature::Metals),
        normal_maps = features.contains(Feature::NormalMaps),
        emissive = features.contains(Feature::Emissive),
        image_based_lighting = features.contains(Feature::ImageBasedLighting),
        light_maps = features.contains(Feature::LightMaps),
        fully_rough = features.contains(Feature::FullyRough),
        sun_light = features.contains(Feature::Sun),
        point_lights = features.contains(Feature::PointLights),
        near = CAMERA_NEAR as f32,
        far = CAMERA_FAR as f32,
    )
}

/// `fn surface_at(object: u32, point: vec3<f32>, normal: vec3<f32>) -> Surface`: the WGSL of
/// [`surface_at`] before the decals, with the light accumulation's static light folded in, and
/// `fn paint_surface(surface: Surface) -> Surface`, the decals.
/// Its host provides `fn light_map_irradiance(uv: vec2<f32>) -> vec3<f32>` and the `Surface`
/// struct; the scene's constants come from [`scene_wgsl`].
pub const SURFACE_AT_WGSL: &str = include_str!("../wgsl/surface_at.wgsl");
