//! How each seed layout holds a surface: where every quantity goes, and the curves it passes
//! through on the way (light accumulation scaled by [`LIGHT_SCALE`] into `rgb10_a2`, 8-bit
//! colours in pseudo-gamma, normals in unsigned formats mapped to [0, 1]). The renderer, the
//! trade-off study and the tests all read these, so what the study measures is what the
//! renderer stores.
//!
//! Each convention is written twice, side by side: as WGSL (`encode_texel` from a [`Surface`],
//! `decode_texel` to the [`Shading`] the lighting pass reads, over the shading library's
//! `colour`, `hdr`, `normals`, `material` and `constants` modules and [`SURFACE_WGSL`]) and as
//! its Rust mirror ([`SurfaceConvention::encode`], [`SurfaceConvention::decode`]) over
//! [`gbuffer_shading::mirror`], in the same order of operations.

use gbuffer_runtime::seed_layouts::{
    ArmTileBlock, FutureMetallic, FutureSpecular, MobileMetallic, SpecularWorkflow,
};
use gbuffer_runtime::GBufferLayout;
use gbuffer_shading::mirror as m;
use glam::{Vec2, Vec3};

/// Light accumulation stored in unorm channels (`rgb10_a2`) is stored as light / this, so
/// light up to 4 (the brightest light map and emissive of the reference scene) survives;
/// brighter light is clipped there. GPU Pro 7 leaves the range to the application.
pub const LIGHT_SCALE: f32 = 4.0;

/// The WGSL structs [`Surface`] and [`Shading`], and `LIGHT_SCALE`.
pub const SURFACE_WGSL: &str = "
// How far rgb10_a2 light accumulation is scaled down (LIGHT_SCALE beside this text).
const LIGHT_SCALE: f32 = 4.0;

// What the G-buffer pass stores of a surface point.
struct Surface {
    normal: vec3<f32>,
    roughness: f32,
    base_colour: vec3<f32>,
    metallic: f32,
    // The static diffuse light it receives, times its diffuse colour (light accumulation).
    light: vec3<f32>,
    distance: f32,
    position: vec3<f32>,
}

// What the lighting pass reads back.
struct Shading {
    normal: vec3<f32>,
    roughness: f32,
    diffuse: vec3<f32>,
    f0: vec3<f32>,
    light: vec3<f32>,
}
";

/// What the G-buffer pass stores of a surface point (WGSL `Surface`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Surface {
    /// The unit normal.
    pub normal: Vec3,
    /// Perceptual roughness, 0..1.
    pub roughness: f32,
    /// Linear base colour.
    pub base_colour: Vec3,
    /// Metallic, 0..1.
    pub metallic: f32,
    /// The static light it receives times its diffuse colour (light accumulation), linear HDR.
    pub light: Vec3,
    /// Distance from the eye along the view ray (what the 128-bit layouts store as depth).
    pub distance: f32,
    /// World position (what the 256-bit layouts store).
    pub position: Vec3,
}

/// What the lighting pass reads back (WGSL `Shading`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Shading {
    /// The unit normal.
    pub normal: Vec3,
    /// Perceptual roughness.
    pub roughness: f32,
    /// Diffuse colour.
    pub diffuse: Vec3,
    /// Reflectance at normal incidence.
    pub f0: Vec3,
    /// Light accumulation, linear HDR.
    pub light: Vec3,
}

impl Shading {
    /// A shading with the diffuse colour and reflectance at normal incidence of `colours`
    /// (what the metallic workflow gives), in the order of the WGSL constructor
    /// `Shading(normal, roughness, colours.diffuse, colours.f0, light)`.
    pub fn from_colours(
        normal: Vec3,
        roughness: f32,
        colours: m::material::MaterialColours,
        light: Vec3,
    ) -> Shading {
        Shading {
            normal,
            roughness,
            diffuse: colours.diffuse,
            f0: colours.f0,
            light,
        }
    }

    /// What a G-buffer that stored `surface` exactly would give back: the metallic workflow
    /// with dielectrics at [`gbuffer_shading::mirror::constants::DIELECTRIC_F0`].
    pub fn of(surface: &Surface) -> Shading {
        let colours = metallic_workflow(surface.base_colour, surface.metallic);
        Shading::from_colours(surface.normal, surface.roughness, colours, surface.light)
    }
}

fn metallic_workflow(base_colour: Vec3, metallic: f32) -> m::material::MaterialColours {
    m::material::metallic_workflow(base_colour, metallic, m::constants::DIELECTRIC_F0)
}

/// A layout's convention: how a [`Surface`] goes into it and a [`Shading`] comes out (the seed
/// layouts' here, the engine layouts' in [`super::engine`]).
pub trait SurfaceConvention: GBufferLayout {
    /// `fn encode_texel(s: Surface) -> <Layout>`.
    const ENCODE_WGSL: &'static str;
    /// `fn decode_texel(t: <Layout>) -> Shading`.
    const DECODE_WGSL: &'static str;
    /// The Rust mirror of `encode_texel`.
    fn encode(surface: &Surface) -> Self;
    /// The Rust mirror of `decode_texel`.
    fn decode(&self) -> Shading;
}

impl SurfaceConvention for MobileMetallic {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> MobileMetallic {
    return MobileMetallic(scale_hdr_to_unit(s.light, LIGHT_SCALE), s.distance, vec4<f32>(normal_to_unorm(s.normal), s.roughness), vec4<f32>(linear_to_pseudo_gamma(s.base_colour), s.metallic));
}";
    const DECODE_WGSL: &'static str = "fn decode_texel(t: MobileMetallic) -> Shading {
    let colours = metallic_workflow(pseudo_gamma_to_linear(t.albedo_metallic.rgb), t.albedo_metallic.a, DIELECTRIC_F0);
    return Shading(unorm_to_normal(t.normals_roughness.xyz), t.normals_roughness.w, colours.diffuse, colours.f0, scale_unit_to_hdr(t.light_accumulation, LIGHT_SCALE));
}";

    fn encode(s: &Surface) -> Self {
        MobileMetallic {
            light_accumulation: m::hdr::scale_hdr_to_unit(s.light, LIGHT_SCALE),
            depth: s.distance,
            normals_roughness: m::normals::normal_to_unorm(s.normal).extend(s.roughness),
            albedo_metallic: m::colour::linear_to_pseudo_gamma(s.base_colour).extend(s.metallic),
        }
    }

    fn decode(&self) -> Shading {
        let colours = metallic_workflow(
            m::colour::pseudo_gamma_to_linear(self.albedo_metallic.truncate()),
            self.albedo_metallic.w,
        );
        Shading::from_colours(
            m::normals::unorm_to_normal(self.normals_roughness.truncate()),
            self.normals_roughness.w,
            colours,
            m::hdr::scale_unit_to_hdr(self.light_accumulation, LIGHT_SCALE),
        )
    }
}

impl SurfaceConvention for SpecularWorkflow {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> SpecularWorkflow {
    let colours = metallic_workflow(s.base_colour, s.metallic, DIELECTRIC_F0);
    return SpecularWorkflow(scale_hdr_to_unit(s.light, LIGHT_SCALE), s.distance, vec4<f32>(normal_to_unorm(s.normal), s.roughness), linear_to_pseudo_gamma(colours.diffuse), linear_to_pseudo_gamma(colours.f0));
}";
    const DECODE_WGSL: &'static str = "fn decode_texel(t: SpecularWorkflow) -> Shading {
    return Shading(unorm_to_normal(t.normals_roughness.xyz), t.normals_roughness.w, pseudo_gamma_to_linear(t.base_colour), pseudo_gamma_to_linear(t.specular_colour), scale_unit_to_hdr(t.light_accumulation, LIGHT_SCALE));
}";

    fn encode(s: &Surface) -> Self {
        let colours = metallic_workflow(s.base_colour, s.metallic);
        SpecularWorkflow {
            light_accumulation: m::hdr::scale_hdr_to_unit(s.light, LIGHT_SCALE),
            depth: s.distance,
            normals_roughness: m::normals::normal_to_unorm(s.normal).extend(s.roughness),
            base_colour: m::colour::linear_to_pseudo_gamma(colours.diffuse),
            specular_colour: m::colour::linear_to_pseudo_gamma(colours.f0),
        }
    }

    fn decode(&self) -> Shading {
        Shading {
            normal: m::normals::unorm_to_normal(self.normals_roughness.truncate()),
            roughness: self.normals_roughness.w,
            diffuse: m::colour::pseudo_gamma_to_linear(self.base_colour),
            f0: m::colour::pseudo_gamma_to_linear(self.specular_colour),
            light: m::hdr::scale_unit_to_hdr(self.light_accumulation, LIGHT_SCALE),
        }
    }
}

impl SurfaceConvention for FutureMetallic {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> FutureMetallic {
    return FutureMetallic(s.position.x, s.position.y, s.position.z, s.light.rg, vec2<f32>(s.light.b, s.normal.x), s.normal.yz, vec2<f32>(s.roughness, s.metallic), s.base_colour);
}";
    const DECODE_WGSL: &'static str = "fn decode_texel(t: FutureMetallic) -> Shading {
    let colours = metallic_workflow(t.albedo_or_reflectance, t.roughness_metallic.y, DIELECTRIC_F0);
    let normal = normalize(vec3<f32>(t.light_accumulation_b_normal_x.y, t.normal_yz));
    return Shading(normal, t.roughness_metallic.x, colours.diffuse, colours.f0, vec3<f32>(t.light_accumulation_rg, t.light_accumulation_b_normal_x.x));
}";

    fn encode(s: &Surface) -> Self {
        FutureMetallic {
            position_x: s.position.x,
            position_y: s.position.y,
            position_z: s.position.z,
            light_accumulation_rg: Vec2::new(s.light.x, s.light.y),
            light_accumulation_b_normal_x: Vec2::new(s.light.z, s.normal.x),
            normal_yz: Vec2::new(s.normal.y, s.normal.z),
            roughness_metallic: Vec2::new(s.roughness, s.metallic),
            albedo_or_reflectance: s.base_colour,
        }
    }

    fn decode(&self) -> Shading {
        let colours = metallic_workflow(self.albedo_or_reflectance, self.roughness_metallic.y);
        let normal = Vec3::new(
            self.light_accumulation_b_normal_x.y,
            self.normal_yz.x,
            self.normal_yz.y,
        )
        .normalize();
        Shading::from_colours(
            normal,
            self.roughness_metallic.x,
            colours,
            self.light_accumulation_rg
                .extend(self.light_accumulation_b_normal_x.x),
        )
    }
}

impl SurfaceConvention for FutureSpecular {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> FutureSpecular {
    let colours = metallic_workflow(s.base_colour, s.metallic, DIELECTRIC_F0);
    return FutureSpecular(s.position.x, s.position.y, s.position.z, s.light.rg, vec2<f32>(s.light.b, s.roughness), normal_to_unorm(s.normal), colours.diffuse, colours.f0);
}";
    const DECODE_WGSL: &'static str = "fn decode_texel(t: FutureSpecular) -> Shading {
    return Shading(unorm_to_normal(t.normal), t.light_accumulation_b_roughness.y, t.albedo, t.reflectance, vec3<f32>(t.light_accumulation_rg, t.light_accumulation_b_roughness.x));
}";

    fn encode(s: &Surface) -> Self {
        let colours = metallic_workflow(s.base_colour, s.metallic);
        FutureSpecular {
            position_x: s.position.x,
            position_y: s.position.y,
            position_z: s.position.z,
            light_accumulation_rg: Vec2::new(s.light.x, s.light.y),
            light_accumulation_b_roughness: Vec2::new(s.light.z, s.roughness),
            // r11f_g11f_b10f holds no negatives: the normal is mapped to [0, 1].
            normal: m::normals::normal_to_unorm(s.normal),
            albedo: colours.diffuse,
            reflectance: colours.f0,
        }
    }

    fn decode(&self) -> Shading {
        Shading {
            normal: m::normals::unorm_to_normal(self.normal),
            roughness: self.light_accumulation_b_roughness.y,
            diffuse: self.albedo,
            f0: self.reflectance,
            light: self
                .light_accumulation_rg
                .extend(self.light_accumulation_b_roughness.x),
        }
    }
}

impl SurfaceConvention for ArmTileBlock {
    const ENCODE_WGSL: &'static str = "fn encode_texel(s: Surface) -> ArmTileBlock {
    return ArmTileBlock(s.light, linear_to_pseudo_gamma(s.base_colour), normal_to_unorm(s.normal), vec2<f32>(s.metallic, s.roughness));
}";
    const DECODE_WGSL: &'static str = "fn decode_texel(t: ArmTileBlock) -> Shading {
    let colours = metallic_workflow(pseudo_gamma_to_linear(t.albedo), t.metallic_roughness.x, DIELECTRIC_F0);
    return Shading(unorm_to_normal(t.normal), t.metallic_roughness.y, colours.diffuse, colours.f0, t.light);
}";

    fn encode(s: &Surface) -> Self {
        ArmTileBlock {
            light: s.light,
            albedo: m::colour::linear_to_pseudo_gamma(s.base_colour),
            normal: m::normals::normal_to_unorm(s.normal),
            metallic_roughness: Vec2::new(s.metallic, s.roughness),
        }
    }

    fn decode(&self) -> Shading {
        let colours = metallic_workflow(
            m::colour::pseudo_gamma_to_linear(self.albedo),
            self.metallic_roughness.x,
        );
        Shading::from_colours(
            m::normals::unorm_to_normal(self.normal),
            self.metallic_roughness.y,
            colours,
            self.light,
        )
    }
}

/// A surface through a seed layout as stored: encoded, packed, unpacked and decoded, the Rust
/// mirror of what the G-buffer and lighting passes do to it.
pub fn round_trip<L: SurfaceConvention>(surface: &Surface) -> Shading {
    L::unpack(&L::encode(surface).pack()).decode()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn surface() -> Surface {
        Surface {
            normal: Vec3::new(0.48, 0.6, 0.64),
            roughness: 0.5,
            base_colour: Vec3::new(0.8, 0.4, 0.2),
            metallic: 0.0,
            light: Vec3::new(0.5, 1.0, 2.0),
            distance: 3.0,
            position: Vec3::new(1.0, 2.0, 3.0),
        }
    }

    /// Every layout gives back what it stored, within its storage's precision (8-bit pseudo
    /// gamma colours are the coarsest: a few hundredths at most).
    #[test]
    fn every_seed_layout_gives_back_the_surface_it_stored() {
        let exact = Shading::of(&surface());
        for (name, shading) in [
            ("MobileMetallic", round_trip::<MobileMetallic>(&surface())),
            (
                "SpecularWorkflow",
                round_trip::<SpecularWorkflow>(&surface()),
            ),
            ("FutureMetallic", round_trip::<FutureMetallic>(&surface())),
            ("FutureSpecular", round_trip::<FutureSpecular>(&surface())),
            ("ArmTileBlock", round_trip::<ArmTileBlock>(&surface())),
        ] {
            let vectors = [
                (shading.normal, exact.normal),
                (shading.diffuse, exact.diffuse),
                (shading.f0, exact.f0),
                (shading.light, exact.light),
            ];
            for (got, want) in vectors {
                assert!(
                    (got - want).abs().max_element() < 0.02,
                    "{name}: {got} for {want}"
                );
            }
            assert!((shading.roughness - exact.roughness).abs() < 0.01, "{name}");
        }
    }

    /// Light past the scale is clipped there by the 128- and 160-bit layouts, kept by the
    /// float ones.
    #[test]
    fn light_above_the_scale_clips_only_in_unorm_storage() {
        let bright = Surface {
            light: Vec3::splat(2.0 * LIGHT_SCALE),
            ..surface()
        };
        let clipped = round_trip::<MobileMetallic>(&bright).light;
        assert!((clipped - Vec3::splat(LIGHT_SCALE)).abs().max_element() < 1e-6);
        let kept = round_trip::<FutureMetallic>(&bright).light;
        assert_eq!(kept, Vec3::splat(2.0 * LIGHT_SCALE));
    }

    #[test]
    fn the_wgsl_constant_is_the_rust_one() {
        assert!(SURFACE_WGSL.contains(&format!("const LIGHT_SCALE: f32 = {LIGHT_SCALE:?};")));
    }
}
