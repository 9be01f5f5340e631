//! A deliberately coarse layout: Listing 2.2 ([`gbuffer_runtime::seed_layouts::MobileMetallic`]) with
//! its normal in 2 x 8 octahedral bits instead of three 8-bit unorm channels. The octahedral
//! map spends its codes on the sphere more evenly than three unorm components do, but 256
//! codes a coordinate leave steps of about 0.7 degrees at the octahedron's centre and twice
//! that near its edges, against about 0.45 degrees for 3 x 8 unorm: the frame table's
//! yardstick of a layout whose storage the picture should show (smooth spheres' highlights
//! band).

use crate::conventions::seed::{Shading, Surface, SurfaceConvention, LIGHT_SCALE};
use gbuffer_macros::GBufferLayout;
use gbuffer_shading::mirror as m;
use glam::{Vec3, Vec4};

/// Listing 2.2 with a 16-bit octahedral normal (8 bits a coordinate) and 8-bit roughness in
/// its third word.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 128, crate = "gbuffer_runtime")]
pub struct CoarseNormals {
    /// Light accumulation over [`LIGHT_SCALE`], as Listing 2.2.
    #[pls(rgb10_a2)]
    pub light_accumulation: Vec3,
    /// Distance from the eye.
    #[pls(r32f)]
    pub depth: f32,
    /// The unit normal, octahedral, 8 bits a coordinate.
    #[bits(16, octahedral)]
    pub normal: Vec3,
    /// Perceptual roughness.
    #[bits(8, unorm)]
    pub roughness: f32,
    /// Base colour in pseudo-gamma, and metallic, as Listing 2.2.
    #[pls(rgba8)]
    pub albedo_metallic: Vec4,
}

impl SurfaceConvention for CoarseNormals {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> CoarseNormals {
    return CoarseNormals(scale_hdr_to_unit(s.light, LIGHT_SCALE), s.distance, s.normal, s.roughness, vec4<f32>(linear_to_pseudo_gamma(s.base_colour), s.metallic));
}";
    const DECODE_WGSL: &'static str = "fn decode_texel(t: CoarseNormals) -> Shading {
    let colours = metallic_workflow(pseudo_gamma_to_linear(t.albedo_metallic.rgb), t.albedo_metallic.a, DIELECTRIC_F0);
    return Shading(t.normal, t.roughness, colours.diffuse, colours.f0, scale_unit_to_hdr(t.light_accumulation, LIGHT_SCALE));
}";

    fn encode(s: &Surface) -> Self {
        CoarseNormals {
            light_accumulation: m::hdr::scale_hdr_to_unit(s.light, LIGHT_SCALE),
            depth: s.distance,
            normal: s.normal,
            roughness: s.roughness,
            albedo_metallic: m::colour::linear_to_pseudo_gamma(s.base_colour).extend(s.metallic),
        }
    }

    fn decode(&self) -> Shading {
        let colours = m::material::metallic_workflow(
            m::colour::pseudo_gamma_to_linear(self.albedo_metallic.truncate()),
            self.albedo_metallic.w,
            m::constants::DIELECTRIC_F0,
        );
        Shading::from_colours(
            self.normal,
            self.roughness,
            colours,
            m::hdr::scale_unit_to_hdr(self.light_accumulation, LIGHT_SCALE),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conventions::seed::round_trip;
    use gbuffer_runtime::seed_layouts::MobileMetallic;

    /// Its normals come back further off than Listing 2.2's, over normals facing the viewer.
    #[test]
    fn its_normals_are_coarser_than_listing_2_2s() {
        let largest_angle = |round_trip: fn(&Surface) -> Shading| {
            (0..4096)
                .map(|index| {
                    let (u, v) = ((index % 64) as f32 / 63.0, (index / 64) as f32 / 63.0);
                    let normal = Vec3::new(u * 1.6 - 0.8, v * 1.6 - 0.8, 1.0).normalize();
                    let surface = Surface {
                        normal,
                        ..Surface::default()
                    };
                    let decoded = round_trip(&surface).normal.normalize();
                    decoded.dot(normal).clamp(-1.0, 1.0).acos().to_degrees()
                })
                .fold(0.0f32, f32::max)
        };
        let coarse = largest_angle(round_trip::<CoarseNormals>);
        let listing = largest_angle(round_trip::<MobileMetallic>);
        assert!(
            coarse > listing * 1.2,
            "coarse {coarse} degrees, Listing 2.2 {listing}"
        );
    }
}
