//! The G-buffers the renderer can use: a packed layout (a seed layout, an engine's, the coarse
//! yardstick or the lossless one) in `Rgba32Uint` targets by the generated WGSL; a layout solved
//! for a scene description, packed the same way; or the classic unpacked set of native targets a
//! user writes without this library. Each packed layout brings the WGSL that stores a surface
//! in its fields and reads the shading inputs back, by its convention
//! ([`crate::conventions::seed`], [`crate::conventions::engine`]); a solved layout brings its
//! own (`gbuffer_solver::texel`).

use std::sync::Arc;

use crate::conventions::seed::SurfaceConvention;
use gbuffer_core::Named;
use gbuffer_core::{Layout, PackedTarget};
use gbuffer_runtime::engine_layouts::{BevyDeferred, HdrpLit};
use gbuffer_runtime::seed_layouts::{
    ArmTileBlock, FutureMetallic, FutureSpecular, MobileMetallic, SpecularWorkflow,
};
use gbuffer_solver::{Features, Solution};

use crate::coarse::CoarseNormals;
use crate::lossless::Lossless;

/// Where the G-buffer pass writes.
#[derive(Clone, Debug, PartialEq)]
pub enum GBuffer {
    /// A packed layout in `Rgba32Uint` targets, the reference scene.
    Packed(PackedLayout),
    /// Separate native targets: Rgba16Float light, Rgba8Unorm normal and roughness,
    /// Rgba8UnormSrgb base colour and metallic.
    Classic,
    /// The layout solved for a scene description, packed into `Rgba32Uint` targets: the
    /// scene shows the description's features and the lighting pass has only their terms.
    Solved(Arc<Solution>),
    /// The lossless G-buffer ([`PackedLayout::Lossless`]) of a scene showing these features,
    /// lit by the full lighting pass: what a solved layout's frame is held against.
    LosslessScene(Features),
}

/// The packed layouts the renderer can use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PackedLayout {
    /// GPU Pro 7 Listing 2.2.
    MobileMetallic,
    /// GPU Pro 7 Listing 2.1.
    SpecularWorkflow,
    /// GPU Pro 7 Listing 2.7.
    FutureMetallic,
    /// GPU Pro 7 Listing 2.8.
    FutureSpecular,
    /// Arm's pixel local storage block.
    ArmTileBlock,
    /// Bevy's deferred G-buffer, its WebGL2 form ([`gbuffer_runtime::engine_layouts::BevyDeferred`]).
    BevyDeferred,
    /// Unity HDRP's Lit G-buffer ([`gbuffer_runtime::engine_layouts::HdrpLit`]).
    HdrpLit,
    /// Not a shipped layout: Listing 2.2 with 2 x 8-bit octahedral normals
    /// ([`crate::coarse`]), a layout the picture should show.
    CoarseNormals,
    /// Not a shipped layout: every quantity as an f32 ([`crate::lossless`]), what a layout's
    /// frame is held against.
    Lossless,
}

// The seeds, the engines', the coarse one and the lossless one.
gbuffer_core::named!(
    PackedLayout {
        MobileMetallic => "mobile-metallic",
        SpecularWorkflow => "specular-workflow",
        FutureMetallic => "future-metallic",
        FutureSpecular => "future-specular",
        ArmTileBlock => "arm-tile-block",
        BevyDeferred => "bevy-deferred",
        HdrpLit => "hdrp-lit",
        CoarseNormals => "coarse-normals",
        Lossless => "lossless",
    }
);

/// What the renderer takes of a layout: its model, its generated WGSL, and its convention's
/// `encode_texel` and `decode_texel`.
struct Entry {
    layout: Layout,
    wgsl: &'static str,
    encode_wgsl: &'static str,
    decode_wgsl: &'static str,
}

impl Entry {
    fn of<L: SurfaceConvention>() -> Entry {
        Entry {
            layout: L::layout(),
            wgsl: L::WGSL,
            encode_wgsl: L::ENCODE_WGSL,
            decode_wgsl: L::DECODE_WGSL,
        }
    }
}

impl PackedLayout {
    /// Every seed layout.
    pub const SEEDS: [PackedLayout; 5] = [
        PackedLayout::MobileMetallic,
        PackedLayout::SpecularWorkflow,
        PackedLayout::FutureMetallic,
        PackedLayout::FutureSpecular,
        PackedLayout::ArmTileBlock,
    ];

    /// The engine layouts.
    pub const ENGINES: [PackedLayout; 2] = [PackedLayout::BevyDeferred, PackedLayout::HdrpLit];

    fn entry(self) -> Entry {
        match self {
            PackedLayout::MobileMetallic => Entry::of::<MobileMetallic>(),
            PackedLayout::SpecularWorkflow => Entry::of::<SpecularWorkflow>(),
            PackedLayout::FutureMetallic => Entry::of::<FutureMetallic>(),
            PackedLayout::FutureSpecular => Entry::of::<FutureSpecular>(),
            PackedLayout::ArmTileBlock => Entry::of::<ArmTileBlock>(),
            PackedLayout::BevyDeferred => Entry::of::<BevyDeferred>(),
            PackedLayout::HdrpLit => Entry::of::<HdrpLit>(),
            PackedLayout::CoarseNormals => Entry::of::<CoarseNormals>(),
            PackedLayout::Lossless => Entry::of::<Lossless>(),
        }
    }

    /// Its layout.
    pub fn layout(self) -> Layout {
        self.entry().layout
    }

    /// Its generated WGSL.
    pub fn wgsl(self) -> &'static str {
        self.entry().wgsl
    }

    /// `fn encode_texel(surface: Surface) -> <Name>`: the layout's convention.
    pub fn encode_wgsl(self) -> &'static str {
        self.entry().encode_wgsl
    }

    /// `fn decode_texel(t: <Name>) -> Shading`: the inverse of `encode_texel`.
    pub fn decode_wgsl(self) -> &'static str {
        self.entry().decode_wgsl
    }

    /// `fn texel_position(t: <Name>, direction: vec3<f32>) -> vec3<f32>`: where the surface
    /// of a texel is, from the depth (distance along the view ray) or the world position the
    /// layout stores, for lighting passes that cannot read the depth buffer (the on-tile
    /// paths; wgpu's GL backend). The error says why a layout has none.
    pub fn texel_position_wgsl(self) -> Result<String, String> {
        let name = self.layout().name;
        let position = match self {
            PackedLayout::MobileMetallic
            | PackedLayout::SpecularWorkflow
            | PackedLayout::CoarseNormals
            | PackedLayout::Lossless => "SCENE_EYE + direction * t.depth",
            PackedLayout::FutureMetallic | PackedLayout::FutureSpecular => {
                "vec3<f32>(t.position_x, t.position_y, t.position_z)"
            }
            PackedLayout::ArmTileBlock | PackedLayout::BevyDeferred | PackedLayout::HdrpLit => {
                return Err(format!(
                    "layout `{}` stores neither the distance to the surface nor its position",
                    self.name()
                ))
            }
        };
        Ok(format!(
            "fn texel_position(t: {name}, direction: vec3<f32>) -> vec3<f32> {{\n    return {position};\n}}\n"
        ))
    }

    /// What the fused paths need beyond `encode_texel` and `decode_texel`, for layouts that
    /// store where the surface is and its base colour (the decals paint base colour, the
    /// point lights need the position): [`Self::texel_position_wgsl`], `with_light(t, light)`
    /// (the light accumulation replaced) and `paint_texel(t, decal, weight)`. The error says
    /// why another layout cannot be kept on tile by this renderer.
    pub fn on_tile_wgsl(self) -> Result<String, String> {
        let extras = self.on_tile_extras_wgsl()?;
        Ok(format!("{}\n{extras}", self.texel_position_wgsl()?))
    }

    fn on_tile_extras_wgsl(self) -> Result<&'static str, String> {
        match self {
            PackedLayout::MobileMetallic => Ok("fn with_light(t: MobileMetallic, light: vec3<f32>) -> MobileMetallic {
    var lit = t;
    lit.light_accumulation = scale_hdr_to_unit(light, LIGHT_SCALE);
    return lit;
}

fn paint_texel(t: MobileMetallic, decal: u32, weight: f32) -> MobileMetallic {
    var painted = t;
    let base_colour = paint_base_colour(pseudo_gamma_to_linear(t.albedo_metallic.rgb), decal, weight);
    painted.albedo_metallic = vec4<f32>(linear_to_pseudo_gamma(base_colour), t.albedo_metallic.a);
    painted.normals_roughness.w = paint_roughness(t.normals_roughness.w, decal, weight);
    return painted;
}"),
            PackedLayout::FutureMetallic => Ok("fn with_light(t: FutureMetallic, light: vec3<f32>) -> FutureMetallic {
    var lit = t;
    lit.light_accumulation_rg = light.rg;
    lit.light_accumulation_b_normal_x.x = light.b;
    return lit;
}

fn paint_texel(t: FutureMetallic, decal: u32, weight: f32) -> FutureMetallic {
    var painted = t;
    painted.albedo_or_reflectance = paint_base_colour(t.albedo_or_reflectance, decal, weight);
    painted.roughness_metallic.x = paint_roughness(t.roughness_metallic.x, decal, weight);
    return painted;
}"),
            PackedLayout::SpecularWorkflow | PackedLayout::FutureSpecular => Err(format!(
                "layout `{}` stores diffuse and specular colour, not the base colour the decals \
                 paint in place; keep mobile-metallic or future-metallic on tile",
                self.name()
            )),
            PackedLayout::BevyDeferred | PackedLayout::HdrpLit | PackedLayout::CoarseNormals => {
                Err(format!(
                    "layout `{}` is not kept on tile by this renderer (its on-tile paths need \
                     `with_light` and `paint_texel` for the layout); keep mobile-metallic or \
                     future-metallic on tile, or render it on --backend wgpu",
                    self.name()
                ))
            }
            PackedLayout::ArmTileBlock => Err(format!(
                "layout `{}` stores neither depth nor position, which the decals and point \
                 lights read on tile; keep mobile-metallic or future-metallic on tile",
                self.name()
            )),
            PackedLayout::Lossless => Err(
                "the lossless G-buffer's twelve words are more than the fused paths keep on \
                 tile: it renders on --backend wgpu"
                    .to_string(),
            ),
        }
    }

    /// The fields `with_light` changes, and those `paint_texel` changes: an on-tile draw
    /// writes only the attachments that hold them.
    pub fn on_tile_fields(self) -> (&'static [&'static str], &'static [&'static str]) {
        match self {
            PackedLayout::FutureMetallic => (
                &["light_accumulation_rg", "light_accumulation_b_normal_x"],
                &["roughness_metallic", "albedo_or_reflectance"],
            ),
            _ => (
                &["light_accumulation"],
                &["normals_roughness", "albedo_metallic"],
            ),
        }
    }
}

/// What `--layout` names: a packed layout or `classic` (the unpacked native targets).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayoutArgument {
    /// A packed layout.
    Packed(PackedLayout),
    /// The classic unpacked targets.
    Classic,
}

impl Named for LayoutArgument {
    /// Every packed layout, in its order, then the classic targets.
    const ALL: &'static [Self] = &{
        const PACKED: &[PackedLayout] = PackedLayout::ALL;
        let mut all = [LayoutArgument::Classic; PACKED.len() + 1];
        let mut index = 0;
        while index < PACKED.len() {
            all[index] = LayoutArgument::Packed(PACKED[index]);
            index += 1;
        }
        all
    };

    fn name(self) -> &'static str {
        match self {
            LayoutArgument::Packed(layout) => layout.name(),
            LayoutArgument::Classic => "classic",
        }
    }
}

impl From<LayoutArgument> for GBuffer {
    fn from(argument: LayoutArgument) -> GBuffer {
        match argument {
            LayoutArgument::Packed(layout) => GBuffer::Packed(layout),
            LayoutArgument::Classic => GBuffer::Classic,
        }
    }
}

impl GBuffer {
    /// Every G-buffer `--layout` names, in its order: each packed layout, then the classic
    /// targets.
    pub fn named() -> impl Iterator<Item = GBuffer> {
        LayoutArgument::ALL.iter().copied().map(GBuffer::from)
    }

    /// The name in messages: a packed layout's command-line name, `classic`, or a solved
    /// layout's name.
    pub fn name(&self) -> String {
        match self {
            GBuffer::Classic => "classic".to_string(),
            GBuffer::Solved(solution) => solution.layout.name.clone(),
            GBuffer::Packed(layout) => layout.name().to_string(),
            GBuffer::LosslessScene(_) => PackedLayout::Lossless.name().to_string(),
        }
    }

    /// The packed layout with its convention, if the G-buffer has one (the lossless scene's is
    /// [`PackedLayout::Lossless`]).
    pub fn packed_layout(&self) -> Option<PackedLayout> {
        match self {
            GBuffer::Packed(layout) => Some(*layout),
            GBuffer::LosslessScene(_) => Some(PackedLayout::Lossless),
            GBuffer::Classic | GBuffer::Solved(_) => None,
        }
    }

    /// The packed layout, if the G-buffer is packed.
    pub fn layout(&self) -> Option<Layout> {
        match self {
            GBuffer::Solved(solution) => Some(solution.layout.clone()),
            other => other.packed_layout().map(PackedLayout::layout),
        }
    }

    /// What the scene shows: a solved layout's features or the lossless scene's, else the
    /// reference scene's.
    pub fn features(&self) -> Features {
        match self {
            GBuffer::Solved(solution) => solution.scene.features,
            GBuffer::LosslessScene(features) => *features,
            GBuffer::Packed(_) | GBuffer::Classic => crate::scene::reference_features(),
        }
    }

    /// The packed render targets of a packed G-buffer; the error says that `classic` has none.
    pub fn packed_targets(&self) -> Result<Vec<PackedTarget>, String> {
        self.layout()
            .map(|layout| layout.packed_targets())
            .ok_or_else(|| format!("`{}` is not a packed G-buffer", self.name()))
    }

    /// The render targets of the G-buffer pass.
    pub fn target_formats(&self) -> Vec<wgpu::TextureFormat> {
        match self.layout() {
            Some(layout) => {
                gbuffer_runtime::targets::packed_target_formats(layout.words()).to_vec()
            }
            None => vec![
                wgpu::TextureFormat::Rgba16Float,
                wgpu::TextureFormat::Rgba8Unorm,
                wgpu::TextureFormat::Rgba8UnormSrgb,
            ],
        }
    }

    /// Bytes per pixel the G-buffer occupies in memory.
    pub fn bytes_per_pixel(&self) -> u32 {
        self.target_formats()
            .iter()
            .map(|format| format.block_copy_size(None).unwrap_or(0))
            .sum()
    }
}

/// Per pixel, the first `words` words of its texels in `targets` (each target's words for all
/// pixels, row by row), in target order.
pub fn texels_of(targets: &[Vec<u32>], pixels: usize, words: usize) -> Vec<u32> {
    let mut texels = Vec::with_capacity(pixels * words);
    for pixel in 0..pixels {
        let texel: Vec<u32> = targets
            .iter()
            .flat_map(|target| {
                let per_pixel = target.len() / pixels;
                target[pixel * per_pixel..(pixel + 1) * per_pixel]
                    .iter()
                    .copied()
            })
            .collect();
        texels.extend_from_slice(&texel[..words]);
    }
    texels
}
