//! The technique the library exists for: the G-buffer kept in tile memory and consumed there.
//! One render pass draws the whole frame:
//!
//! 1. the mesh writes the G-buffer (depth-tested);
//! 2. four decals paint base colour and roughness in place: each reads the G-buffer texel,
//!    modifies it and writes it back (programmable blending);
//! 3. a fullscreen draw over the surfaces replaces the light accumulation with the image-based
//!    light, the sun and the 32 point lights, summed in registers as the two-pass path's
//!    lighting pass sums them: one read and one write of the texel for all the light (drawn as
//!    32 light volumes after the sun, each reading and rewriting the texel the one before had
//!    just written, the fused frame took 7 times the two-pass frame's time on an NVIDIA H100
//!    and 1.8 times on lavapipe);
//! 4. the resolve tone-maps the light accumulation (or draws the sky) into the one attachment
//!    that is stored.
//!
//! The G-buffer attachments are invalidated (GLES) or never stored (Vulkan `DONT_CARE`), so on
//! a tiler they never reach memory. Beside them, each backend has a two-pass path that stores
//! the G-buffer to textures and samples it, as the wgpu renderer does.
//!
//! GLES 3.2 (EGL surfaceless, `glow`) reads the G-buffer by EXT_shader_framebuffer_fetch;
//! Vulkan (`ash`) by subpass inputs. The maths is the renderer's WGSL (`crate::shaders`, the
//! shading library, the layout's generated WGSL) translated by naga; only the entry points
//! that fetch are written here, in GLSL, around the layout's generated include.

use gbuffer_gpu::fullscreen::FULLSCREEN_WGSL;

use crate::gbuffers::{GBuffer, PackedLayout};
use crate::options::Options;
use crate::shaders::{self, library, INPUTS_WGSL, VOLUME_WGSL};

/// Which API draws the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// The wgpu renderer (`crate::wgpu`): the G-buffer through memory.
    Wgpu,
    /// GLES 3.2 through EGL surfaceless.
    Gles,
    /// Vulkan through `ash`.
    Vulkan,
}

gbuffer_core::named!(
    Backend {
        Wgpu => "wgpu",
        Gles => "gles",
        Vulkan => "vulkan",
    }
);

/// How a backend carries the G-buffer from the geometry to the lighting.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    /// GLES: framebuffer fetch over one attachment per field in its own format (the driver
    /// converts, as Arm's example does).
    FetchNative,
    /// GLES: framebuffer fetch over the packed words in `RGBA32UI` attachments.
    FetchPacked,
    /// Vulkan: one render pass, the packed words in transient `RGBA32UI` attachments read as
    /// input attachments.
    Subpass,
    /// Vulkan: the subpass path's attachments and shaders in one dynamic rendering, without
    /// render pass or framebuffer objects (`VK_KHR_dynamic_rendering_local_read`), with a
    /// by-region barrier before each draw that reads what earlier draws wrote.
    LocalRead,
    /// Vulkan: the local-read path with pipelines that read the attachments in rasterization
    /// order (`VK_EXT_rasterization_order_attachment_access`): no barrier between the draws.
    LocalReadOrdered,
    /// GLES or Vulkan: the G-buffer stored to textures and sampled by a second pass.
    TwoPass,
}

gbuffer_core::named!(
    Path {
        FetchNative => "fetch-native",
        FetchPacked => "fetch-packed",
        Subpass => "subpass",
        LocalRead => "local-read",
        LocalReadOrdered => "local-read-ordered",
        TwoPass => "two-pass",
    }
);

impl Backend {
    /// The paths the backend offers, the default first.
    pub fn paths(self) -> &'static [Path] {
        match self {
            Backend::Wgpu => &[],
            Backend::Gles => &[Path::FetchNative, Path::FetchPacked, Path::TwoPass],
            Backend::Vulkan => &[
                Path::Subpass,
                Path::LocalRead,
                Path::LocalReadOrdered,
                Path::TwoPass,
            ],
        }
    }
}

impl Path {
    /// Whether the G-buffer stays in the render pass (the fused paths).
    pub fn is_fused(self) -> bool {
        self != Path::TwoPass
    }
}

/// What an on-tile frame is drawn with: the renderer's options and the path.
#[derive(Clone, Debug, PartialEq)]
pub struct TileOptions {
    /// Layout, forms and size.
    pub options: Options,
    /// How the G-buffer travels.
    pub path: Path,
}

/// The draws of a fused frame, in order: the mesh, the decals, the lighting (the environment,
/// the sun and the point lights), the resolve of the surfaces and the sky.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// The mesh writes the G-buffer.
    Geometry,
    /// A decal volume paints the texels under it.
    Decal,
    /// A fullscreen draw replaces the light accumulation with the environment, the sun and
    /// every point light.
    Lighting,
    /// A fullscreen draw tone-maps the surfaces' light into the output.
    Resolve,
    /// A fullscreen draw puts the sky in the output where there is no surface.
    Sky,
}

/// What a volume's fragment does where its decal or light does not reach.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Unreached {
    /// `discard`, as framebuffer fetch and subpasses allow.
    Discard,
    /// Nothing: it stores no texel (pixel local storage forbids `discard`).
    StoreNothing,
}

/// The G-buffer pass's fragment inputs, as naga names `geometry_vertex`'s outputs: their
/// interpolation, type and name, at locations 0, 1, 2.
const GEOMETRY_INPUTS: [(&str, &str, &str); 3] = [
    ("smooth", "highp vec3", "_vs2fs_location0"),
    ("smooth", "highp vec3", "_vs2fs_location1"),
    ("flat", "highp uint", "_vs2fs_location2"),
];

/// The declarations of [`GEOMETRY_INPUTS`], each with its location or (GLSL ES 3.00, which
/// matches varyings by name) without.
fn geometry_inputs(with_locations: bool) -> String {
    let mut out = String::new();
    for (location, (interpolation, ty, name)) in GEOMETRY_INPUTS.iter().enumerate() {
        if with_locations {
            out += &format!("layout(location = {location}) ");
        }
        out += &format!("{interpolation} in {ty} {name};\n");
    }
    out
}

// Every stage, in drawing order.
gbuffer_core::named!(
    /// Its name in recordings and messages.
    Stage {
        Geometry => "geometry",
        Decal => "decal",
        Lighting => "lighting",
        Resolve => "resolve",
        Sky => "sky",
    }
);

impl Stage {
    /// Whether its fragments read the G-buffer texel under them (every stage but the mesh,
    /// which writes it first, and the sky, drawn where there is no surface): a draw of it must
    /// wait, by region, for the draws before it.
    pub fn reads_gbuffer(self) -> bool {
        !matches!(self, Stage::Geometry | Stage::Sky)
    }

    /// The vertex entry point of [`VERTEX_WGSL`] (or the scene's) it draws with.
    pub fn vertex_entry(self) -> &'static str {
        match self {
            Stage::Geometry => "geometry_vertex",
            Stage::Decal => "volume_vertex",
            Stage::Lighting | Stage::Resolve => "surfaces_vertex",
            Stage::Sky => "sky_vertex",
        }
    }

    /// Which colour attachments it writes, the G-buffer's (`words_per_attachment` words each)
    /// then the output: a draw writes back only what it changes, which spares the attachments
    /// it does not (and keeps them out of a llvmpipe bug, see the guide's fused renderer chapter).
    pub fn writes(
        self,
        layout: PackedLayout,
        attachments: usize,
        words_per_attachment: usize,
    ) -> Vec<bool> {
        let model = layout.layout();
        let locations = model.field_locations();
        let (light_fields, painted_fields) = layout.on_tile_fields();
        let mut writes = vec![false; attachments + 1];
        let mut holding = |fields: &[&str]| {
            for name in fields {
                let field = model
                    .fields
                    .iter()
                    .position(|field| field.name == *name)
                    .expect("the on-tile fields are the layout's");
                writes[locations[field].0 / words_per_attachment] = true;
            }
        };
        match self {
            Stage::Geometry => writes[..attachments].fill(true),
            Stage::Decal => holding(painted_fields),
            Stage::Lighting => holding(light_fields),
            Stage::Resolve | Stage::Sky => writes[attachments] = true,
        }
        writes
    }

    /// The GLSL `main` of its fragment stage, over the layout's include (`load`, its
    /// [`gbuffer_core::Symbols::load`]),
    /// the translated stage functions and what the backend declares: `frame_colour` (the
    /// output), `volume_index` (the volume drawn), and `store`, statements writing `texel`.
    /// A decal's fragments that it does not paint are discarded.
    pub fn fragment_main(self, texel: &str, load: &str, store: &str) -> String {
        self.main(texel, load, store, Unreached::Discard)
    }

    /// [`Stage::fragment_main`] for pixel local storage, which forbids `discard`: an unreached
    /// fragment stores nothing, and the G-buffer's varyings carry no locations (GLSL ES 3.00
    /// matches them by name).
    pub fn pixel_local_storage_main(self, texel: &str, load: &str, store: &str) -> String {
        self.main(texel, load, store, Unreached::StoreNothing)
    }

    fn main(self, texel: &str, load: &str, store: &str, unreached: Unreached) -> String {
        // A volume's fragment: when it is not reached (discarded) or when it is (the texel
        // changed and stored), and the statements that change the texel.
        let reached = |(not_reached, reached): (&str, &str), change: &str| match unreached {
            Unreached::Discard => {
                format!("    if ({not_reached}) {{\n        discard;\n    }}\n{change}{store}")
            }
            Unreached::StoreNothing => {
                let indented: String = format!("{change}{store}")
                    .lines()
                    .map(|line| format!("    {line}\n"))
                    .collect();
                format!("    if ({reached}) {{\n{indented}    }}\n")
            }
        };
        let body = match self {
            Stage::Geometry => format!(
                "    {texel} texel = geometry_texel(_vs2fs_location2, _vs2fs_location0, _vs2fs_location1);\n{store}"
            ),
            Stage::Decal => format!(
                "    {texel} texel = {load}();\n    uint decal = volume_index - POINT_LIGHT_COUNT;\n    float weight = decal_weight_at(texel, gl_FragCoord.xy, decal);\n{}",
                reached(
                    ("weight <= 0.0", "weight > 0.0"),
                    "    texel = paint_texel(texel, decal, weight);\n"
                )
            ),
            Stage::Lighting => format!(
                "    {texel} texel = lit_texel({load}(), gl_FragCoord.xy);\n{store}"
            ),
            Stage::Resolve => format!("    frame_colour = resolve_colour({load}());\n"),
            Stage::Sky => "    frame_colour = sky_colour(gl_FragCoord.xy);\n".to_string(),
        };
        let inputs = match (self, unreached) {
            (Stage::Geometry, Unreached::Discard) => geometry_inputs(true),
            (Stage::Geometry, Unreached::StoreNothing) => geometry_inputs(false),
            _ => String::new(),
        };
        format!("{inputs}void main() {{\n{body}}}\n")
    }
}

/// The seed layout of `options`, if it can be kept on tile (the error says why not).
pub fn tile_layout(options: &Options) -> Result<PackedLayout, String> {
    match &options.gbuffer {
        GBuffer::Packed(layout) => layout.on_tile_wgsl().map(|_| *layout),
        GBuffer::LosslessScene(_) => PackedLayout::Lossless.on_tile_wgsl().map(|_| PackedLayout::Lossless),
        other => Err(format!(
            "the on-tile paths render the seed layouts mobile-metallic and future-metallic, not `{}`",
            other.name()
        )),
    }
}

/// Vertex shaders of the fused paths, in WGSL: the mesh (`geometry_vertex`), a fullscreen
/// triangle over the surfaces (`surfaces_vertex`: just in front of the far plane, drawn with a
/// GREATER depth test) or over the sky (`sky_vertex`: on the far plane, EQUAL), and a volume's
/// screen rectangle (`volume_vertex`: point light `volume` below POINT_LIGHT_COUNT, else decal
/// `volume - POINT_LIGHT_COUNT`), drawn over the surfaces.
pub const VERTEX_WGSL: &str = include_str!("../wgsl/fused_vertices.wgsl");

/// The fragment entry point that calls every stage's function: the on-tile backends translate
/// what it reaches ([`crate::glsl::fragment_declarations`]), and their hand-written entry
/// points replace it.
pub const TRANSLATION_ENTRY: &str = "translation_entry";

/// The fragment stages' functions, in WGSL, over the layout's texel `T`: what the hand-written
/// entry points call between reading the G-buffer and writing it.
fn stages_wgsl(texel: &str) -> String {
    format!(
        "
// The texel a fragment of the mesh writes: the surface before the decals.
fn geometry_texel(object: u32, position: vec3<f32>, normal: vec3<f32>) -> {texel} {{
    return encode_texel(surface_at(object, position, normal));
}}

// How strongly decal `decal` paints the texel at `pixel` (0 outside its box).
fn decal_weight_at(texel: {texel}, pixel: vec2<f32>, decal: u32) -> f32 {{
    return decal_weight(decal, texel_position(texel, camera_ray(pixel, VIEWPORT)));
}}

// The light accumulation replaced by what the scene lights the surface with: the image-based
// light (or the static light where there is none), the sun and every point light, summed here
// as the two-pass lighting pass sums them, then encoded once.
fn lit_texel(texel: {texel}, pixel: vec2<f32>) -> {texel} {{
    let shading = decode_texel(texel);
    let direction = camera_ray(pixel, VIEWPORT);
    let view = -direction;
    var light = select(shading.light, environment_light(shading, view), SCENE_IMAGE_BASED_LIGHTING);
    if SCENE_SUN {{
        light += sun_light(shading, view);
    }}
    if SCENE_POINT_LIGHTS {{
        let position = texel_position(texel, direction);
        for (var index = 0u; index < POINT_LIGHT_COUNT; index++) {{
            light += point_light(shading, view, position, index);
        }}
    }}
    return with_light(texel, light);
}}

// The displayed colour of a surface: its light accumulation, tone-mapped.
fn resolve_colour(texel: {texel}) -> vec4<f32> {{
    return display_colour(decode_texel(texel).light);
}}

// The displayed colour of the sky at `pixel`.
fn sky_colour(pixel: vec2<f32>) -> vec4<f32> {{
    return display_colour(sky(camera_ray(pixel, VIEWPORT)));
}}

// Calls every stage, so that the translation keeps them all (it declares what this entry
// point reaches); the hand-written entry points replace it.
@fragment
fn {TRANSLATION_ENTRY}(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    var texel = geometry_texel(0u, position.xyz, position.xyz);
    texel = paint_texel(texel, 0u, decal_weight_at(texel, position.xy, 0u));
    texel = lit_texel(texel, position.xy);
    return resolve_colour(texel) + sky_colour(position.xy);
}}
"
    )
}

/// The WGSL the fused paths translate: the library, the scene, the inputs, the layout and its
/// on-tile functions, the lighting, the vertex shaders and the stages. `y_sign` is the
/// backend's clip-space y (both GL and Vulkan render with -1).
pub fn fused_wgsl(options: &Options, layout: PackedLayout, y_sign: f32) -> String {
    let on_tile = layout
        .on_tile_wgsl()
        .expect("tile_layout checked the layout");
    format!(
        "{}\n{}\n{}\n{INPUTS_WGSL}\n{}\n{}\n{}\n{on_tile}\n{}\n{}\n{VOLUME_WGSL}\n{FULLSCREEN_WGSL}\n{VERTEX_WGSL}\n{}",
        library(&shaders::MODULES),
        shaders::frame_wgsl(options, y_sign),
        shaders::geometry_wgsl(options),
        layout.wgsl(),
        layout.encode_wgsl(),
        layout.decode_wgsl(),
        shaders::lighting_functions_wgsl(options),
        shaders::display_wgsl(),
        stages_wgsl(&layout.layout().name),
    )
}
