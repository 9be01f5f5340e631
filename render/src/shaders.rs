//! The WGSL every backend shares. wgpu compiles it as it is; the GLES and Vulkan backends
//! have naga translate it to GLSL ES and GLSL 450 and wrap it in entry points that read the
//! G-buffer by framebuffer fetch or as subpass inputs. The maths is written once, here and in
//! the shading library: nothing below is a second copy of it.

use crate::conventions::seed::SURFACE_WGSL;
use gbuffer_core::Layout;
use gbuffer_core::Named;
use gbuffer_gpu::fullscreen::FULLSCREEN_WGSL;
use gbuffer_solver::lighting::{self, Forms};
use gbuffer_solver::quantity::Quantity;
use gbuffer_solver::Solution;
use gbuffer_translate::wgsl;

use crate::gbuffers::GBuffer;
use crate::options::{IblForm, Options, SunForm, EXPOSURE};
use crate::scene::{self};

/// The library modules (`gbuffer_shading::wgsl`) composed, for the passes.
pub fn library(modules: &[&str]) -> String {
    gbuffer_shading::compose(modules).expect("the library's modules exist")
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
pub const VOLUME_WGSL: &str = include_str!("../wgsl/volume.wgsl");

/// The binding of the environment's sampler, which wraps around the sky in u (GLSL combines
/// it with the environment).
pub const ENVIRONMENT_SAMPLER_BINDING: u32 = 3;

/// The binding of the sampler of the LUT and the light map, which clamps to their edges (GLSL
/// combines it with each).
pub const CLAMPED_SAMPLER_BINDING: u32 = 6;

/// The binding of the environment texture.
pub const ENVIRONMENT_BINDING: u32 = 1;

/// The binding of the split-sum LUT.
pub const LUT_BINDING: u32 = 2;

/// The binding of the light map.
pub const LIGHT_MAP_BINDING: u32 = 5;

/// The host functions over the baked inputs that the scene and the lighting read, at group 0:
/// the environment (1), the LUT (2), the environment's sampler (3), the light map (5), the
/// sampler of the LUT and the light map (6).
pub const INPUTS_WGSL: &str = include_str!("../wgsl/inputs.wgsl");

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
    let (module, info) = wgsl::validate(wgsl, naga::valid::Capabilities::all())
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

/// The G-buffer pass's last statement for a packed layout and the type it returns:
/// `<Name>Targets`. Sky pixels keep the clear value, all ones in every word.
fn write_packed_targets(layout: &Layout) -> (String, String) {
    let symbols = layout.symbols();
    (
        format!("return {}(encode_texel(surface));", symbols.pack_targets()),
        symbols.targets(),
    )
}

/// The first binding of the G-buffer's targets in the lighting pass's group 0.
pub const GBUFFER_FIRST_BINDING: u32 = 10;

/// The lighting pass's bindings of a packed layout's targets, as the library's wgpu helpers
/// declare them (`gbuffer_codegen::wgsl::lighting_targets`), and the expression that
/// loads them at `pixel` as a `<Name>Targets`.
fn read_packed_targets(layout: &Layout) -> (String, String) {
    (
        gbuffer_codegen::wgsl::lighting_targets(
            &gbuffer_codegen::LoweredLayout::new(layout),
            0,
            GBUFFER_FIRST_BINDING,
        ),
        format!("{}(vec2<u32>(pixel))", layout.symbols().load_targets()),
    )
}

/// The G-buffer pass's WGSL for a configuration: `geometry_vertex`, and `gbuffer_main`, which
/// writes the surface with the decals painted over it. `y_sign` is the backend's clip-space y
/// (wgpu 1, GL and Vulkan -1).
pub fn gbuffer_wgsl(options: &Options, y_sign: f32) -> String {
    let (layout_wgsl, encode, output_type) = match &options.gbuffer {
        GBuffer::Packed(_) | GBuffer::LosslessScene(_) => {
            let layout = options.gbuffer.packed_layout().expect("a packed layout");
            let (encode, output_type) = write_packed_targets(&layout.layout());
            (
                format!("{}\n{}", layout.wgsl(), layout.encode_wgsl()),
                encode,
                output_type,
            )
        }
        GBuffer::Solved(solution) => {
            let (encode, output_type) = write_packed_targets(&solution.layout);
            (
                format!(
                    "{}\n{}",
                    gbuffer_solver::texel::texel_wgsl(solution),
                    solved_encode_wgsl(solution)
                ),
                encode,
                output_type,
            )
        }
        GBuffer::Classic => (
            "struct ClassicTargets {\n    @location(0) light: vec4<f32>,\n    @location(1) normal_roughness: vec4<f32>,\n    @location(2) base_colour_metallic: vec4<f32>,\n}\n".to_string(),
            "return ClassicTargets(vec4<f32>(surface.light, 1.0), vec4<f32>(normal_to_unorm(surface.normal), surface.roughness), vec4<f32>(surface.base_colour, surface.metallic));".to_string(),
            "ClassicTargets".to_string(),
        ),
    };
    format!(
        "{}\n{}\n{}\n{INPUTS_WGSL}\n{layout_wgsl}

@fragment
fn gbuffer_main(input: GeometryVarying) -> {output_type} {{
    let surface = paint_surface(surface_at(input.object, input.position, input.normal));
    {encode}
}}

// The G-buffer as the geometry writes it before the decals: the debug view every backend
// stores, to compare their words.
@fragment
fn gbuffer_unpainted_main(input: GeometryVarying) -> {output_type} {{
    let surface = surface_at(input.object, input.position, input.normal);
    {encode}
}}
",
        library(&MODULES),
        frame_wgsl(options, y_sign),
        geometry_wgsl(options),
    )
}

/// Where the lighting pass finds the position of the surface at a pixel, for the point lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Positions {
    /// From the depth buffer, sampled (`surface_position(pixel, direction)`): any layout.
    DepthBuffer,
    /// From the texel's depth or position (`texel_position(texel, direction)`): the layouts
    /// the on-tile paths keep (GLSL cannot load from a depth texture).
    Texel,
}

/// What the lighting pass of a seed or classic layout shares: the library, the scene, the
/// inputs, and with positions from the depth buffer, the buffer and `surface_position`.
fn lighting_prelude(options: &Options, positions: Positions) -> String {
    let depth_buffer = match positions {
        Positions::Texel => "",
        Positions::DepthBuffer => DEPTH_BUFFER_WGSL,
    };
    format!(
        "{}\n{}\n{}\n{SURFACE_WGSL}\n{INPUTS_WGSL}\n{}\n{}\n{FULLSCREEN_WGSL}\n{depth_buffer}",
        library(&MODULES),
        frame_wgsl(options, 1.0),
        scene::scene_wgsl(options.gbuffer.features()),
        lighting_functions_wgsl(options),
        display_wgsl(),
    )
}

/// The depth buffer, and the position it gives the surface at a pixel.
const DEPTH_BUFFER_WGSL: &str = include_str!("../wgsl/depth_buffer.wgsl");

/// The lighting pass's WGSL for a configuration: `lighting_main` (radiance) and
/// `lighting_resolve_main` (tone-mapped), reading positions from `positions`.
pub fn lighting_pass_wgsl(options: &Options, positions: Positions) -> Result<String, String> {
    // `sample_gbuffer(pixel)`: whether a surface is there, and what the lighting reads of it.
    let (bindings, sample) = match &options.gbuffer {
        GBuffer::Solved(solution) => return Ok(solved_lighting_wgsl(solution, options)),
        GBuffer::Packed(_) | GBuffer::LosslessScene(_) => {
            let layout = options.gbuffer.packed_layout().expect("a packed layout");
            let model = layout.layout();
            let (bindings, targets) = read_packed_targets(&model);
            let symbols = model.symbols();
            let (name, unpack_targets) = (symbols.texel(), symbols.unpack_targets());
            let texel_positions = match positions {
                Positions::Texel => layout.texel_position_wgsl()?,
                Positions::DepthBuffer => String::new(),
            };
            (
                format!("{}\n{}\n{texel_positions}\n{bindings}", layout.wgsl(), layout.decode_wgsl()),
                format!(
                    "struct GBufferSample {{\n    surface: bool,\n    texel: {name},\n    shading: Shading,\n}}\n\n\
                     // Sky pixels keep the G-buffer's clear value, all ones.\n\
                     fn sample_gbuffer(pixel: vec2<i32>) -> GBufferSample {{\n    \
                     let targets = {targets};\n    \
                     let texel = {unpack_targets}(targets);\n    \
                     return GBufferSample(targets.first.x != 0xffffffffu, texel, decode_texel(texel));\n}}\n"
                ),
            )
        }
        GBuffer::Classic => (
            "@group(0) @binding(10) var gbuffer_light: texture_2d<f32>;\n@group(0) @binding(11) var gbuffer_normal: texture_2d<f32>;\n@group(0) @binding(12) var gbuffer_colour: texture_2d<f32>;\n".to_string(),
            "struct GBufferSample {\n    surface: bool,\n    shading: Shading,\n}\n\n\
             // Sky pixels keep the light target's clear alpha, 0.\n\
             fn sample_gbuffer(pixel: vec2<i32>) -> GBufferSample {\n    \
             let light = textureLoad(gbuffer_light, pixel, 0);\n    \
             let normal_roughness = textureLoad(gbuffer_normal, pixel, 0);\n    \
             let colour = textureLoad(gbuffer_colour, pixel, 0);\n    \
             let colours = metallic_workflow(colour.rgb, colour.a, DIELECTRIC_F0);\n    \
             let shading = Shading(unorm_to_normal(normal_roughness.xyz), normal_roughness.w, colours.diffuse, colours.f0, light.rgb);\n    \
             return GBufferSample(light.a != 0.0, shading);\n}\n".to_string(),
        ),
    };
    Ok(format!(
        "{}\n{VOLUME_WGSL}\n{bindings}
{sample}
// The image-based light and the sun at a pixel (the sky where there is no surface).
fn pixel_radiance(position: vec4<f32>) -> vec3<f32> {{
    let pixel = vec2<i32>(position.xy);
    let direction = camera_ray(position.xy, VIEWPORT);
    let sample = sample_gbuffer(pixel);
    if !sample.surface {{
        return sky(direction);
    }}
    let view = -direction;
    // The scene's features decide the terms (a solved preset's scene held lossless).
    var radiance = select(sample.shading.light, environment_light(sample.shading, view), SCENE_IMAGE_BASED_LIGHTING);
    if SCENE_SUN {{
        radiance += sun_light(sample.shading, view);
    }}
    return radiance;
}}

// Every point light at a pixel, one after the other (the on-tile two-pass path's way).
fn pixel_point_lights(position: vec4<f32>) -> vec3<f32> {{
    let pixel = vec2<i32>(position.xy);
    let direction = camera_ray(position.xy, VIEWPORT);
    let sample = sample_gbuffer(pixel);
    if !sample.surface {{
        return vec3<f32>(0.0);
    }}
    let surface = {position};
    var radiance = vec3<f32>(0.0);
    for (var index = 0u; index < POINT_LIGHT_COUNT; index++) {{
        radiance += point_light(sample.shading, -direction, surface, index);
    }}
    return radiance;
}}

@fragment
fn lighting_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    return vec4<f32>(pixel_radiance(position), 1.0);
}}

struct LightVolume {{
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) light: u32,
}}

// Point light `light`'s volume: the screen rectangle around its reach (instance `light`).
@vertex
fn light_volume_vertex(@builtin(vertex_index) vertex: u32, @builtin(instance_index) light: u32) -> LightVolume {{
    return LightVolume(vec4<f32>(volume_rectangle(vertex, light), 0.0, 1.0), light);
}}

// Point light `light` on the surfaces it reaches in its volume, added by blending.
@fragment
fn point_light_main(volume: LightVolume) -> @location(0) vec4<f32> {{
    let pixel = vec2<i32>(volume.clip.xy);
    let direction = camera_ray(volume.clip.xy, VIEWPORT);
    let sample = sample_gbuffer(pixel);
    if !sample.surface {{
        discard;
    }}
    let surface = {position};
    if distance(POINT_LIGHT_POSITIONS[volume.light], surface) >= POINT_LIGHT_RADIUS {{
        discard;
    }}
    return vec4<f32>(point_light(sample.shading, -direction, surface, volume.light), 0.0);
}}

// Lighting and tone mapping in one pass (the on-tile backends' two-pass path).
@fragment
fn lighting_resolve_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    var radiance = pixel_radiance(position);
    if SCENE_POINT_LIGHTS {{
        radiance += pixel_point_lights(position);
    }}
    return display_colour(radiance);
}}
",
        lighting_prelude(options, positions),
        position = match positions {
            Positions::DepthBuffer => "surface_position(pixel, direction)",
            Positions::Texel => "texel_position(sample.texel, direction)",
        },
    ))
}

/// The G-buffer pass's `encode_texel` for a solved layout: the surface's values for the
/// quantities the layout stores.
fn solved_encode_wgsl(solution: &Solution) -> String {
    let mut members = String::new();
    for placement in &solution.placements {
        let value = match placement.quantity {
            Quantity::Light => "surface.light",
            Quantity::Depth => "surface.distance",
            Quantity::Normal => "surface.normal",
            Quantity::Roughness => "surface.roughness",
            Quantity::BaseColour => "surface.base_colour",
            Quantity::Metallic => "surface.metallic",
            // The scene's dielectrics all reflect 0.04: UE4's default specular.
            Quantity::Specular => "0.5",
            Quantity::Albedo => "colours.diffuse",
            Quantity::SpecularColour => "colours.f0",
        };
        members.push_str(&format!(
            "    values.{} = {value};\n",
            placement.quantity.name()
        ));
    }
    format!(
        "fn encode_texel(surface: Surface) -> {name} {{
    let colours = metallic_workflow(surface.base_colour, surface.metallic, DIELECTRIC_F0);
    var values: {values};
{members}    return {encode}(values);
}}",
        name = solution.layout.name,
        values = solution.values_type(),
        encode = solution.layout.symbols().encode_values(),
    )
}

/// The lighting pass of a solved layout: decode, then the lighting function generated for the
/// scene (`gbuffer_solver::lighting`), with only the host inputs its terms read.
pub fn solved_lighting_wgsl(solution: &Solution, options: &Options) -> String {
    let forms = Forms {
        sun: options.sun,
        ibl: options.ibl,
    };
    let layout = &solution.layout;
    let symbols = layout.symbols();
    let (target_bindings, targets) = read_packed_targets(layout);
    let position = if solution.placement(Quantity::Depth).is_some() {
        "SCENE_EYE + direction * values.depth"
    } else {
        "vec3<f32>(0.0)" // without point lights nothing reads it
    };
    format!(
        "{}\n{}\n{}\n{FULLSCREEN_WGSL}\n{INPUTS_WGSL}\n{}\n{target_bindings}
{}
@fragment
fn lighting_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    let pixel = vec2<i32>(position.xy);
    let direction = camera_ray(position.xy, VIEWPORT);
    let targets = {targets};
    // The G-buffer pass marks sky pixels with all ones in the first word (the first target
    // may be narrower than four words).
    if targets.first.x == 0xffffffffu {{
        return vec4<f32>(sky(direction), 1.0);
    }}
    let values = {decode}({unpack_targets}(targets));
    let surface_position = {position};
    return vec4<f32>({shade}(values, -direction, surface_position), 1.0);
}}
",
        library(&MODULES),
        frame_wgsl(options, 1.0),
        scene::scene_wgsl(solution.scene.features),
        gbuffer_solver::texel::texel_wgsl(solution),
        lighting::lighting_wgsl(solution, forms),
        shade = solution.layout.symbols().shade(),
        decode = symbols.decode_values(),
        unpack_targets = symbols.unpack_targets(),
    )
}

/// The tone-mapping pass: `full_screen` and `tonemap_main`, which exposes, tone maps and
/// encodes the lit HDR target for display.
pub fn tonemap_wgsl() -> String {
    format!(
        "{}\n{FULLSCREEN_WGSL}\n{}
@group(0) @binding(0) var hdr: texture_2d<f32>;

@fragment
fn tonemap_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    return display_colour(textureLoad(hdr, vec2<i32>(position.xy), 0).rgb);
}}
",
        library(&["tonemap", "colour"]),
        display_wgsl(),
    )
}
