//! The G-buffers the renderer can use: any seed layout, packed into `Rgba32Uint` targets by
//! the generated WGSL; a layout solved for a scene description, packed the same way; or the
//! classic unpacked set of native targets a user writes without this library. Each seed
//! layout brings the WGSL that stores a surface in its fields and reads the shading inputs
//! back, by the conventions of its source; a solved layout brings its own (`gbuffer_solver::texel`).

use std::sync::Arc;

use gbuffer::packing::{Layout, PackedTarget};
use gbuffer::seed_conventions::SeedConvention;
use gbuffer::seed_layouts::{
    ArmTileBlock, FutureMetallic, FutureSpecular, MobileMetallic, SpecularWorkflow,
};
use gbuffer::GBufferLayout;
use gbuffer_solver::{Features, Solution};

use crate::lossless::Lossless;

/// Where the G-buffer pass writes.
#[derive(Clone, Debug, PartialEq)]
pub enum GBuffer {
    /// A seed layout, packed into `Rgba32Uint` targets.
    Packed(SeedLayout),
    /// Separate native targets: Rgba16Float light, Rgba8Unorm normal and roughness,
    /// Rgba8UnormSrgb base colour and metallic.
    Classic,
    /// The layout solved for a scene description, packed into `Rgba32Uint` targets: the
    /// scene shows the description's features and the lighting pass has only their terms.
    Solved(Arc<Solution>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
/// The seed layouts the renderer can use.
pub enum SeedLayout {
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
    /// Not a seed layout: every quantity as an f32 ([`crate::lossless`]), what a layout's
    /// frame is held against. Not in [`SeedLayout::ALL`].
    Lossless,
}

impl SeedLayout {
    /// Every seed layout.
    pub const ALL: [SeedLayout; 5] = [
        SeedLayout::MobileMetallic,
        SeedLayout::SpecularWorkflow,
        SeedLayout::FutureMetallic,
        SeedLayout::FutureSpecular,
        SeedLayout::ArmTileBlock,
    ];

    /// The command-line name, e.g. `mobile-metallic`.
    pub fn flag(self) -> String {
        crate::flag(&self)
    }

    /// Its layout.
    pub fn layout(self) -> Layout {
        match self {
            SeedLayout::MobileMetallic => MobileMetallic::layout(),
            SeedLayout::SpecularWorkflow => SpecularWorkflow::layout(),
            SeedLayout::FutureMetallic => FutureMetallic::layout(),
            SeedLayout::FutureSpecular => FutureSpecular::layout(),
            SeedLayout::ArmTileBlock => ArmTileBlock::layout(),
            SeedLayout::Lossless => Lossless::layout(),
        }
    }

    /// Its generated WGSL.
    pub fn wgsl(self) -> &'static str {
        match self {
            SeedLayout::MobileMetallic => MobileMetallic::WGSL,
            SeedLayout::SpecularWorkflow => SpecularWorkflow::WGSL,
            SeedLayout::FutureMetallic => FutureMetallic::WGSL,
            SeedLayout::FutureSpecular => FutureSpecular::WGSL,
            SeedLayout::ArmTileBlock => ArmTileBlock::WGSL,
            SeedLayout::Lossless => Lossless::WGSL,
        }
    }

    /// `fn encode_texel(surface: Surface) -> <Name>`: the layout's convention
    /// ([`gbuffer::seed_conventions`]).
    pub fn encode_wgsl(self) -> &'static str {
        match self {
            SeedLayout::MobileMetallic => MobileMetallic::ENCODE_WGSL,
            SeedLayout::SpecularWorkflow => SpecularWorkflow::ENCODE_WGSL,
            SeedLayout::FutureMetallic => FutureMetallic::ENCODE_WGSL,
            SeedLayout::FutureSpecular => FutureSpecular::ENCODE_WGSL,
            SeedLayout::ArmTileBlock => ArmTileBlock::ENCODE_WGSL,
            SeedLayout::Lossless => Lossless::ENCODE_WGSL,
        }
    }

    /// What the on-tile paths need beyond `encode_texel` and `decode_texel`, for layouts that
    /// store where the surface is and its base colour (the decals paint base colour, the
    /// point lights need the position): `texel_position(t, direction)`, `with_light(t,
    /// light)` (the light accumulation replaced) and `paint_texel(t, decal, weight)`. The
    /// error says why another layout cannot be kept on tile by this renderer.
    pub fn on_tile_wgsl(self) -> Result<&'static str, String> {
        match self {
            SeedLayout::MobileMetallic => Ok("fn texel_position(t: MobileMetallic, direction: vec3<f32>) -> vec3<f32> {
    return SCENE_EYE + direction * t.depth;
}

fn with_light(t: MobileMetallic, light: vec3<f32>) -> MobileMetallic {
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
            SeedLayout::FutureMetallic => Ok("fn texel_position(t: FutureMetallic, direction: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(t.position_x, t.position_y, t.position_z);
}

fn with_light(t: FutureMetallic, light: vec3<f32>) -> FutureMetallic {
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
            SeedLayout::SpecularWorkflow | SeedLayout::FutureSpecular => Err(format!(
                "layout `{}` stores diffuse and specular colour, not the base colour the decals \
                 paint in place; keep mobile-metallic or future-metallic on tile",
                self.flag()
            )),
            SeedLayout::ArmTileBlock => Err(format!(
                "layout `{}` stores neither depth nor position, which the decals and point \
                 lights read on tile; keep mobile-metallic or future-metallic on tile",
                self.flag()
            )),
            SeedLayout::Lossless => Err(
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
            SeedLayout::FutureMetallic => (
                &["light_accumulation_rg", "light_accumulation_b_normal_x"],
                &["roughness_metallic", "albedo_or_reflectance"],
            ),
            _ => (
                &["light_accumulation"],
                &["normals_roughness", "albedo_metallic"],
            ),
        }
    }

    /// `fn decode_texel(t: <Name>) -> Shading`: the inverse of `encode_texel`
    /// ([`gbuffer::seed_conventions`]).
    pub fn decode_wgsl(self) -> &'static str {
        match self {
            SeedLayout::MobileMetallic => MobileMetallic::DECODE_WGSL,
            SeedLayout::SpecularWorkflow => SpecularWorkflow::DECODE_WGSL,
            SeedLayout::FutureMetallic => FutureMetallic::DECODE_WGSL,
            SeedLayout::FutureSpecular => FutureSpecular::DECODE_WGSL,
            SeedLayout::ArmTileBlock => ArmTileBlock::DECODE_WGSL,
            SeedLayout::Lossless => Lossless::DECODE_WGSL,
        }
    }
}

/// What `--layout` names: a seed layout or `classic` (the unpacked native targets).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayoutArgument {
    /// A seed layout, packed.
    Seed(SeedLayout),
    /// The classic unpacked targets.
    Classic,
}

impl clap::ValueEnum for LayoutArgument {
    fn value_variants<'a>() -> &'a [Self] {
        &[
            LayoutArgument::Seed(SeedLayout::MobileMetallic),
            LayoutArgument::Seed(SeedLayout::SpecularWorkflow),
            LayoutArgument::Seed(SeedLayout::FutureMetallic),
            LayoutArgument::Seed(SeedLayout::FutureSpecular),
            LayoutArgument::Seed(SeedLayout::ArmTileBlock),
            LayoutArgument::Seed(SeedLayout::Lossless),
            LayoutArgument::Classic,
        ]
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        match self {
            LayoutArgument::Seed(layout) => layout.to_possible_value(),
            LayoutArgument::Classic => Some(clap::builder::PossibleValue::new("classic")),
        }
    }
}

impl From<LayoutArgument> for GBuffer {
    fn from(argument: LayoutArgument) -> GBuffer {
        match argument {
            LayoutArgument::Seed(layout) => GBuffer::Packed(layout),
            LayoutArgument::Classic => GBuffer::Classic,
        }
    }
}

impl GBuffer {
    /// The name in messages: a seed layout's command-line name, `classic`, or a solved
    /// layout's name.
    pub fn name(&self) -> String {
        match self {
            GBuffer::Packed(layout) => layout.flag(),
            GBuffer::Classic => "classic".to_string(),
            GBuffer::Solved(solution) => solution.layout.name.clone(),
        }
    }

    /// The packed layout, if the G-buffer is packed.
    pub fn layout(&self) -> Option<Layout> {
        match self {
            GBuffer::Packed(layout) => Some(layout.layout()),
            GBuffer::Classic => None,
            GBuffer::Solved(solution) => Some(solution.layout.clone()),
        }
    }

    /// What the scene shows: a solved layout's features, else the reference scene's.
    pub fn features(&self) -> Features {
        match self {
            GBuffer::Solved(solution) => solution.scene.features,
            _ => crate::scene::reference_features(),
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
            Some(layout) => gbuffer::targets::packed_target_formats(layout.words()).to_vec(),
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
