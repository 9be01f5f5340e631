//! The lossless G-buffer: every quantity the G-buffer pass stores, as an f32 in an `r32f`
//! word, rasterised, decaled and lit by the same passes as the packed layouts. A frame through
//! a packed layout differs from one through this G-buffer by what the layout's storage loses,
//! and nothing else: the yardstick of a layout's cost in the picture (`--reference`'s first
//! line), apart from the renderer's own error against the CPU reference (its second).
//!
//! Twelve words (384 bits) are more than the fused paths keep on tile (their attachments), so
//! it renders on wgpu, through memory.

use crate::conventions::seed::{Shading, Surface, SurfaceConvention};
use gbuffer_macros::GBufferLayout;
use gbuffer_shading::mirror as m;
use glam::Vec3;

/// Every quantity of a [`Surface`] the lighting reads, as an f32.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 384, crate = "gbuffer_runtime")]
pub struct Lossless {
    /// Light accumulation, red (linear HDR).
    #[pls(r32f)]
    pub light_red: f32,
    /// Light accumulation, green.
    #[pls(r32f)]
    pub light_green: f32,
    /// Light accumulation, blue.
    #[pls(r32f)]
    pub light_blue: f32,
    /// Distance from the eye along the view ray.
    #[pls(r32f)]
    pub depth: f32,
    /// The unit normal, x.
    #[pls(r32f)]
    pub normal_x: f32,
    /// The unit normal, y.
    #[pls(r32f)]
    pub normal_y: f32,
    /// The unit normal, z.
    #[pls(r32f)]
    pub normal_z: f32,
    /// Perceptual roughness.
    #[pls(r32f)]
    pub roughness: f32,
    /// Linear base colour, red.
    #[pls(r32f)]
    pub base_red: f32,
    /// Linear base colour, green.
    #[pls(r32f)]
    pub base_green: f32,
    /// Linear base colour, blue.
    #[pls(r32f)]
    pub base_blue: f32,
    /// Metallic.
    #[pls(r32f)]
    pub metallic: f32,
}

impl SurfaceConvention for Lossless {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> Lossless {
    return Lossless(s.light.r, s.light.g, s.light.b, s.distance, s.normal.x, s.normal.y, s.normal.z, s.roughness, s.base_colour.r, s.base_colour.g, s.base_colour.b, s.metallic);
}";
    const DECODE_WGSL: &'static str = "fn decode_texel(t: Lossless) -> Shading {
    let colours = metallic_workflow(vec3<f32>(t.base_red, t.base_green, t.base_blue), t.metallic, DIELECTRIC_F0);
    return Shading(vec3<f32>(t.normal_x, t.normal_y, t.normal_z), t.roughness, colours.diffuse, colours.f0, vec3<f32>(t.light_red, t.light_green, t.light_blue));
}";

    fn encode(s: &Surface) -> Self {
        Lossless {
            light_red: s.light.x,
            light_green: s.light.y,
            light_blue: s.light.z,
            depth: s.distance,
            normal_x: s.normal.x,
            normal_y: s.normal.y,
            normal_z: s.normal.z,
            roughness: s.roughness,
            base_red: s.base_colour.x,
            base_green: s.base_colour.y,
            base_blue: s.base_colour.z,
            metallic: s.metallic,
        }
    }

    fn decode(&self) -> Shading {
        let base_colour = Vec3::new(self.base_red, self.base_green, self.base_blue);
        let colours =
            m::material::metallic_workflow(base_colour, self.metallic, m::constants::DIELECTRIC_F0);
        Shading::from_colours(
            Vec3::new(self.normal_x, self.normal_y, self.normal_z),
            self.roughness,
            colours,
            Vec3::new(self.light_red, self.light_green, self.light_blue),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gbuffer_runtime::GBufferLayout;

    /// The round trip is the identity: what goes in comes out, bit for bit (a test of the
    /// layout's r32f words, which hold an f32 unchanged).
    #[test]
    fn a_surface_comes_back_unchanged() {
        let surface = Surface {
            normal: Vec3::new(0.36, -0.48, 0.8),
            roughness: 0.123_456_79,
            base_colour: Vec3::new(0.9, 1e-7, 0.5),
            metallic: 0.3,
            light: Vec3::new(65000.0, 3.0e-9, 1.5),
            distance: 12.345_678,
            position: Vec3::ZERO,
        };
        let texel = Lossless::encode(&surface);
        let words = texel.pack();
        assert_eq!(Lossless::unpack(&words), texel);
        let shading = texel.decode();
        assert_eq!(shading.normal, surface.normal);
        assert_eq!(shading.light, surface.light);
        assert_eq!(shading.roughness, surface.roughness);
    }
}
