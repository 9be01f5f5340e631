//! The WGSL every backend shares. wgpu compiles it as it is; the GLES and Vulkan backends
//! have naga translate it to GLSL ES and GLSL 450 and wrap it in entry points that read the
//! G-buffer by framebuffer fetch or as subpass inputs. The maths is written once, here and in
//! the shading library: nothing below is a second copy of it.

use crate::renderer::{IblForm, Options, SunForm, EXPOSURE};
use crate::scene;
use gbuffer::seed_conventions::SURFACE_WGSL;

/// The library modules (`gbuffer::modules`) composed, for the passes.
pub fn library(modules: &[&str]) -> String {
    gbuffer::modules::compose(modules).expect("the library's modules exist")
}

/// The modules every pass of the renderer draws from.
pub const MODULES: [&str; 8] = [
    "shading",
    "environment",
    "normals",
    "colour",
    "hdr",
    "material",
    "mobile",
    "tonemap",
];

/// The frame's constants: its size, and which way up clip space is (`y_sign` -1 renders
/// upside down, for GL's bottom-up rows and Vulkan's y-down clip space).
pub fn frame_wgsl(options: &Options, y_sign: f32) -> String {
    format!(
        "const VIEWPORT: vec2<f32> = vec2<f32>({:?}, {:?});\nconst CLIP_Y_SIGN: f32 = {y_sign:?};\n",
        options.width as f32,
        options.height as f32,
    )
}

/// The scene's vertex stage and the surface a fragment of it shows: `geometry_vertex`
/// (position, normal and object in, `GeometryVarying` out) and `geometry_surface(varying)`,
/// the surface before the decals. The host provides `light_map_irradiance(uv)`.
pub fn geometry_wgsl(options: &Options) -> String {
    format!(
        "{}\n{SURFACE_WGSL}\n{}
struct GeometryVarying {{
    @builtin(position) clip: vec4<f32>,
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) @interpolate(flat) object: u32,
}}

@vertex
fn geometry_vertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) object: u32) -> GeometryVarying {{
    return GeometryVarying(clip_position(position, VIEWPORT, CLIP_Y_SIGN), position, normal, object);
}}
",
        scene::scene_wgsl(options.gbuffer.features()),
        scene::SURFACE_AT_WGSL,
    )
}

/// `fn volume_rectangle(vertex: u32, volume: u32) -> vec2<f32>`: corner `vertex` (0..6, two
/// triangles) of the screen rectangle, in normalised device coordinates, around volume
/// `volume`'s box: point light `volume` (its reach) below POINT_LIGHT_COUNT, else decal
/// `volume - POINT_LIGHT_COUNT`; the whole screen when the box reaches behind the near plane.
/// Light volumes keep the cost of a light to the pixels it can reach.
pub const VOLUME_WGSL: &str = "
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
";

/// The binding of the inputs' sampler (GLSL combines it with each texture).
pub const SAMPLER_BINDING: u32 = 3;

/// The host functions over the baked inputs that the scene and the lighting read, at group 0:
/// the environment (1), the LUT (2), the sampler (3), the light map (5).
pub const INPUTS_WGSL: &str = "
@group(0) @binding(1) var environment: texture_2d<f32>;
@group(0) @binding(2) var lut: texture_2d<f32>;
@group(0) @binding(3) var linear_sampler: sampler;
@group(0) @binding(5) var light_map: texture_2d<f32>;

// Direction to equirectangular coordinates (u around the vertical, v from the zenith).
fn equirectangular(direction: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(atan2(direction.x, direction.z) * 0.15915494 + 0.5, acos(clamp(direction.y, -1.0, 1.0)) * 0.31830988);
}

// The prefiltered sky towards `direction` for `roughness` (its mip, Listing 2.6).
fn environment_radiance(direction: vec3<f32>, roughness: f32) -> vec3<f32> {
    let mip = ibl_mip_level(roughness, ENVIRONMENT_MIPS);
    return rgbm_decode(textureSampleLevel(environment, linear_sampler, equirectangular(direction), mip), ENVIRONMENT_RANGE);
}

// The split-sum LUT: scale and bias of f0.
fn env_brdf_lut(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    return textureSampleLevel(lut, linear_sampler, vec2<f32>(n_dot_v, roughness), 0.0).xy;
}

// The light map's static diffuse irradiance at `uv` (RGBM squared, Listing 2.5).
fn light_map_irradiance(uv: vec2<f32>) -> vec3<f32> {
    return rgbm_squared_decode(textureSampleLevel(light_map, linear_sampler, uv, 0.0), LIGHT_MAP_RANGE);
}
";

/// The lighting of a decoded texel, in the chosen forms: `environment_light` (the image-based
/// light over the light accumulation), `sun_light` and `point_light` (light `index` at a world
/// position), for a `Shading` seen from `view`.
pub fn lighting_functions_wgsl(options: &Options) -> String {
    let environment = match options.ibl {
        IblForm::Lut => "shade_ibl(shading.light, shading.f0, vec3<f32>(1.0), radiance, env_brdf_lut(n_dot_v, shading.roughness))",
        IblForm::Approx => "shade_ibl_mobile(shading.light, shading.f0, shading.roughness, n_dot_v, vec3<f32>(1.0), radiance)",
    };
    let direct = match options.sun {
        SunForm::Ggx => "shade_directional(shading.normal, view, direction, colour, shading.diffuse, shading.f0, shading.roughness, env_brdf_lut(n_dot_v, shading.roughness))",
        SunForm::Approx => "shade_directional_mobile(shading.normal, view, direction, colour, shading.diffuse, shading.f0, shading.roughness)",
    };
    format!(
        "
// The image-based light, over the light accumulation (static light and emission).
fn environment_light(shading: Shading, view: vec3<f32>) -> vec3<f32> {{
    let n_dot_v = clamp(dot(shading.normal, view), MIN_N_DOT_V, 1.0);
    let reflected = 2.0 * dot(shading.normal, view) * shading.normal - view;
    let radiance = environment_radiance(reflected, shading.roughness);
    return {environment};
}}

// A light from `direction` (unit, towards the light) of radiance `colour`.
fn direct_light(shading: Shading, view: vec3<f32>, direction: vec3<f32>, colour: vec3<f32>) -> vec3<f32> {{
    let n_dot_v = clamp(dot(shading.normal, view), MIN_N_DOT_V, 1.0);
    return {direct};
}}

fn sun_light(shading: Shading, view: vec3<f32>) -> vec3<f32> {{
    return direct_light(shading, view, SUN_DIRECTION, SUN_COLOUR);
}}

// Point light `index` at a surface at `position`, windowed to 0 at POINT_LIGHT_RADIUS.
fn point_light(shading: Shading, view: vec3<f32>, position: vec3<f32>, index: u32) -> vec3<f32> {{
    let to_light = POINT_LIGHT_POSITIONS[index] - position;
    let distance = length(to_light);
    if distance >= POINT_LIGHT_RADIUS {{
        return vec3<f32>(0.0); // the falloff's window is 0 from here on
    }}
    let falloff = point_light_falloff(distance, POINT_LIGHT_RADIUS);
    return direct_light(shading, view, to_light / max(distance, 1e-4), POINT_LIGHT_COLOURS[index] * falloff);
}}

"
    )
}

/// `fn display_colour(radiance: vec3<f32>) -> vec4<f32>`: exposure, the ACES fit, sRGB (the
/// resolve of every path; it needs the `tonemap` and `colour` modules).
pub fn display_wgsl() -> String {
    format!(
        "
// Linear radiance to the displayed colour: exposure, the ACES fit, sRGB.
fn display_colour(radiance: vec3<f32>) -> vec4<f32> {{
    return vec4<f32>(linear_to_srgb(tonemap_aces_fitted(radiance * {:?})), 1.0);
}}
",
        EXPOSURE as f32
    )
}

/// The bindings of group 0 that `entry_point` of `wgsl` uses: what a pipeline with a derived
/// layout expects in its bind group. The WGSL is the renderer's own, so it parses.
pub fn used_bindings(wgsl: &str, entry_point: &str) -> Vec<u32> {
    let module = naga::front::wgsl::parse_str(wgsl).expect("the renderer's WGSL parses");
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .expect("the renderer's WGSL is valid");
    let index = module
        .entry_points
        .iter()
        .position(|entry| entry.name == entry_point)
        .expect("the entry point exists");
    let uses = info.get_entry_point(index);
    module
        .global_variables
        .iter()
        .filter(|(handle, _)| !uses[*handle].is_empty())
        .filter_map(|(_, global)| global.binding.as_ref())
        .filter(|binding| binding.group == 0)
        .map(|binding| binding.binding)
        .collect()
}
