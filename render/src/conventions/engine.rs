//! How the renderer's [`Surface`] goes into the two engine layouts
//! ([`gbuffer_runtime::engine_layouts`]), by each engine's own conventions, so that the reference renderer
//! and the trade-off study can show what an engine's G-buffer costs the picture:
//!
//! - **Bevy** ([`BevyDeferred`], its WebGL2 form), as `bevy_pbr`'s deferred functions store
//!   and read it: base colour gamma 2.2 encoded (`pow(c, 1 / 2.2)`, not the sRGB curve) beside
//!   perceptual roughness, the light in the rgb9e5 emissive word (Bevy adds emissive and the
//!   light map's light to the lit result as the renderer adds its light accumulation), Bevy's
//!   `reflectance` (f0 = 0.16 reflectance², Filament's remapping) at 0.5 for f0 = 0.04, full
//!   occlusion, the 24-bit octahedral normal and no flags. 4 bits cannot hold 0.5: it is stored
//!   as 8/15, and read back, as Bevy's WebGL2 path reads it, less 1/30, which gives 0.5 again.
//!   The 20-bit depth is written as 0: the renderer reads positions from its depth buffer,
//!   where Bevy's WebGL2 path stores clip-space depth.
//! - **HDRP** ([`HdrpLit`], the standard material in its specular colour form): the diffuse
//!   colour in sRGB with full specular occlusion, the normal, perceptual roughness, fresnel0 in
//!   sRGB, material feature 0 with no coat, and the light in the `r11f_g11f_b10f` baked diffuse
//!   lighting word.
//!
//! As in [`super::seed`], each convention is WGSL beside its Rust mirror, in the
//! same order of operations.

use super::seed::{Shading, Surface, SurfaceConvention};
use gbuffer_runtime::engine_layouts::{BevyDeferred, HdrpLit};
use gbuffer_shading::mirror as m;

/// Bevy's `reflectance` for dielectrics: f0 = 0.16 x 0.5² = 0.04.
const BEVY_DIELECTRIC_REFLECTANCE: f32 = 0.5;

/// What Bevy's WebGL2 path takes off the 4-bit reflectance it reads (`props.r - 0.03333`), so
/// that the 8/15 that 0.5 is stored as reads as 0.5. WGSL `BEVY_WEBGL2_REFLECTANCE_BIAS`.
const BEVY_WEBGL2_REFLECTANCE_BIAS: f32 = 1.0 / 30.0;

impl SurfaceConvention for BevyDeferred {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> BevyDeferred {
    return BevyDeferred(vec4<f32>(linear_to_gamma_2_2(s.base_colour), s.roughness), s.light, 0.5, s.metallic, 1.0, 0.0, s.normal, 0u);
}";
    const DECODE_WGSL: &'static str = "const BEVY_WEBGL2_REFLECTANCE_BIAS: f32 = 1.0 / 30.0;

fn decode_texel(t: BevyDeferred) -> Shading {
    // Bevy's WebGL2 bias (0.5 is stored as 8/15), then Filament's remapping: f0 = 0.16 r^2.
    let reflectance = saturate(t.reflectance - BEVY_WEBGL2_REFLECTANCE_BIAS);
    let dielectric_f0 = 0.16 * reflectance * reflectance;
    let colours = metallic_workflow(gamma_2_2_to_linear(t.base_color_roughness.rgb), t.metallic, dielectric_f0);
    return Shading(t.normal, t.base_color_roughness.a, colours.diffuse, colours.f0, t.emissive);
}";

    fn encode(s: &Surface) -> Self {
        BevyDeferred {
            base_color_roughness: m::colour::linear_to_gamma_2_2(s.base_colour).extend(s.roughness),
            emissive: s.light,
            reflectance: BEVY_DIELECTRIC_REFLECTANCE,
            metallic: s.metallic,
            occlusion: 1.0,
            depth: 0.0,
            normal: s.normal,
            flags: 0,
        }
    }

    fn decode(&self) -> Shading {
        let reflectance = (self.reflectance - BEVY_WEBGL2_REFLECTANCE_BIAS).clamp(0.0, 1.0);
        let dielectric_f0 = 0.16 * reflectance * reflectance;
        let base_colour = m::colour::gamma_2_2_to_linear(self.base_color_roughness.truncate());
        let colours = m::material::metallic_workflow(base_colour, self.metallic, dielectric_f0);
        Shading::from_colours(
            self.normal,
            self.base_color_roughness.w,
            colours,
            self.emissive,
        )
    }
}

impl SurfaceConvention for HdrpLit {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> HdrpLit {
    let colours = metallic_workflow(s.base_colour, s.metallic, DIELECTRIC_F0);
    return HdrpLit(vec4<f32>(linear_to_srgb(colours.diffuse), 1.0), s.normal, s.roughness, linear_to_srgb(colours.f0), 0u, 0.0, s.light);
}";
    const DECODE_WGSL: &'static str = "fn decode_texel(t: HdrpLit) -> Shading {
    return Shading(t.normal, t.perceptual_roughness, srgb_to_linear(t.base_color_specular_occlusion.rgb), srgb_to_linear(t.fresnel0), t.baked_diffuse_lighting);
}";

    fn encode(s: &Surface) -> Self {
        let colours =
            m::material::metallic_workflow(s.base_colour, s.metallic, m::constants::DIELECTRIC_F0);
        HdrpLit {
            base_color_specular_occlusion: m::colour::linear_to_srgb(colours.diffuse).extend(1.0),
            normal: s.normal,
            perceptual_roughness: s.roughness,
            fresnel0: m::colour::linear_to_srgb(colours.f0),
            material_feature_id: 0,
            coat_mask: 0.0,
            baked_diffuse_lighting: s.light,
        }
    }

    fn decode(&self) -> Shading {
        Shading {
            normal: self.normal,
            roughness: self.perceptual_roughness,
            diffuse: m::colour::srgb_to_linear(self.base_color_specular_occlusion.truncate()),
            f0: m::colour::srgb_to_linear(self.fresnel0),
            light: self.baked_diffuse_lighting,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conventions::seed::round_trip;
    use gbuffer_runtime::GBufferLayout;
    use glam::Vec3;

    fn surface(metallic: f32) -> Surface {
        Surface {
            normal: Vec3::new(0.36, -0.48, 0.8),
            roughness: 0.5,
            base_colour: Vec3::new(0.8, 0.4, 0.1),
            metallic,
            light: Vec3::new(1.5, 0.25, 0.0625),
            distance: 3.0,
            position: Vec3::ZERO,
        }
    }

    /// Bevy's 4-bit reflectance stores 0.5 as 8/15 and reads it back less 1/30, as Bevy's
    /// WebGL2 path does: a dielectric's f0 comes back as 0.04.
    #[test]
    fn bevy_dielectrics_come_back_with_f0_0_04() {
        let stored = BevyDeferred::unpack(&BevyDeferred::encode(&surface(0.0)).pack());
        assert!((stored.reflectance - 8.0 / 15.0).abs() < 1e-6, "{stored:?}");
        let shading = round_trip::<BevyDeferred>(&surface(0.0));
        assert!((shading.f0.x - 0.04).abs() < 1e-6, "{shading:?}");
        assert!((shading.light - surface(0.0).light).abs().max_element() < 0.01);
    }

    /// A metal's f0 is its base colour within an 8-bit sRGB step, in both layouts.
    #[test]
    fn metals_keep_their_colour() {
        let expected = Shading::of(&surface(1.0));
        for shading in [
            round_trip::<BevyDeferred>(&surface(1.0)),
            round_trip::<HdrpLit>(&surface(1.0)),
        ] {
            assert!(
                (shading.f0 - expected.f0).abs().max_element() < 0.01,
                "{shading:?}"
            );
            assert!(shading.diffuse.max_element() < 0.01, "{shading:?}");
            assert!(
                (shading.normal - expected.normal).length() < 0.002,
                "{shading:?}"
            );
        }
    }
}
