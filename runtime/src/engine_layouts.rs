//! Two real engines' G-buffers declared with this crate: Bevy's deferred G-buffer and Unity
//! HDRP's Lit G-buffer. Their layout files are `codegen/layouts/bevy_deferred.toml` and
//! `hdrp_lit.toml`; `integration-tests/tests/engine_layouts.rs` holds each against an encoder written from
//! the engine's own bit layout.
//!
//! Where the engines round in f32 (`u32(x * 255.0 + 0.5)`, Bevy's octahedral normal truncated
//! by `u32(x * 4095.0)`), this crate's exact conversions round the exact value half up, so a
//! code can differ by one; the bit positions are the engines'. HDRP spreads its 12-bit
//! octahedral coordinates over three bytes (the low eight bits of x, of y, then both top
//! nibbles); this layout keeps each coordinate whole (x in bits 0-11, y in 12-23), so the
//! normal's word differs from HDRP's while the values it decodes agree within a code.

use crate::glam::{Vec3, Vec4};
use crate::GBufferLayout;

/// Bevy's deferred G-buffer (Bevy 0.20's `bevy_pbr::deferred::functions`, in
/// `deferred/functions.wesl`; the WebGL form, which keeps depth):
/// one `Rgba32Uint` texel. Word 0: base colour (in sRGB, as Bevy stores it) and perceptual
/// roughness; word 1: emissive as rgb9e5; word 2: reflectance, metallic and occlusion in 4
/// bits each beside a 20-bit depth; word 3: a 24-bit octahedral normal beside 8 bits of flags.
#[rustfmt::skip] // one field a line, its attribute beside it: the layout reads as a table
#[allow(missing_docs)] // the fields are described above, word by word
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 128)]
pub struct BevyDeferred {
    #[pls(rgba8)]           pub base_color_roughness: Vec4,
    #[bits(32, rgb9e5)]     pub emissive: Vec3,
    #[bits(4, unorm)]       pub reflectance: f32,
    #[bits(4, unorm)]       pub metallic: f32,
    #[bits(4, unorm)]       pub occlusion: f32,
    #[bits(20, unorm)]      pub depth: f32,
    #[bits(24, octahedral)] pub normal: Vec3,
    #[bits(8, uint)]        pub flags: u32,
}

/// Unity HDRP's Lit G-buffer for the standard material (`Lit.hlsl`, `NormalBuffer.hlsl`).
/// Word 0 (RT0): base colour in sRGB and specular occlusion; word 1 (RT1): the octahedral
/// normal in 12 + 12 bits and perceptual roughness; word 2 (RT2): fresnel0 in sRGB, the
/// material feature id in 3 bits and the coat mask in 5; word 3 (RT3): baked diffuse
/// lighting and emission as `r11f_g11f_b10f`.
#[rustfmt::skip] // one field a line, its attribute beside it: the layout reads as a table
#[allow(missing_docs)] // the fields are described above, word by word
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 128)]
pub struct HdrpLit {
    #[pls(rgba8)]             pub base_color_specular_occlusion: Vec4,
    #[bits(24, octahedral)]   pub normal: Vec3,
    #[bits(8, unorm)]         pub perceptual_roughness: f32,
    #[bits(24, unorm)]        pub fresnel0: Vec3,
    #[bits(3, uint)]          pub material_feature_id: u32,
    #[bits(5, unorm)]         pub coat_mask: f32,
    #[pls(r11f_g11f_b10f)]    pub baked_diffuse_lighting: Vec3,
}

/// The engine layouts and their WGSL, as [`crate::seed_layouts::all`] lists the seeds'.
pub fn all() -> Vec<(crate::layout::Layout, &'static str)> {
    fn entry<L: GBufferLayout>() -> (crate::layout::Layout, &'static str) {
        (L::layout(), L::WGSL)
    }
    vec![entry::<BevyDeferred>(), entry::<HdrpLit>()]
}
