//! The G-buffer layouts of the texts the project started from, ready to use and to compare.
//!
//! From "Physically Based Deferred Shading on Mobile" (GPU Pro 7, chapter 2): Listing 2.1
//! (specular workflow, 160 bits of which 142 used: over the 128 bits of a PowerVR Series6
//! tile, so it is declared here with a 256-bit budget), Listing 2.2 (metallic workflow,
//! 128/126), and the 256-bit layouts of Listings 2.7 and 2.8. From Arm's "deferred shading on
//! tile memory" post: its pixel local storage block.

use crate::glam::{Vec2, Vec3, Vec4};
use crate::GBufferLayout;

/// Declares layouts that begin with the same fields, as the chapter's listings do in pairs:
/// `{ the fields they share } Name(budget = bits) { its other fields } ...`. Each expands to a
/// plain `#[derive(GBufferLayout)]` struct, the shared fields first.
macro_rules! layouts_beginning_with {
    ($shared:tt $($(#[$doc:meta])* $name:ident(budget = $budget:literal) $own:tt)*) => {
        $(layouts_beginning_with!(@layout $shared $(#[$doc])* $name $budget $own);)*
    };
    (@layout { $($shared:tt)* } $(#[$doc:meta])* $name:ident $budget:literal { $($own:tt)* }) => {
        $(#[$doc])*
        #[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
        #[gbuffer(budget = $budget)]
        pub struct $name {
            $($shared)*
            $($own)*
        }
    };
}

// Listings 2.1 and 2.2 begin alike: HDR light accumulation, depth, and the normal with
// roughness; the material's colours follow, two of them in the specular workflow.
layouts_beginning_with! {
    {
        /// HDR light accumulation, scaled into 0..1.
        #[pls(rgb10a2)]
        pub light_accumulation: Vec3,
        /// Depth.
        #[pls(r32f)]
        pub depth: f32,
        /// The normal mapped to 0..1 (xyz) and roughness (w).
        #[pls(rgba8)]
        pub normals_roughness: Vec4,
    }

    /// Listing 2.1: specular workflow, 160 bits (142 used). Light accumulation is HDR (scale it
    /// into 0..1 for `rgb10_a2`); base and specular colour are stored in gamma space.
    SpecularWorkflow(budget = 256) {
        /// Base colour, in gamma space.
        #[pls(rgba8)]
        pub base_colour: Vec3,
        /// Specular colour, in gamma space.
        #[pls(rgba8)]
        pub specular_colour: Vec3,
    }

    /// Listing 2.2: metallic workflow in 128 bits (126 used), the chapter's recommended layout.
    MobileMetallic(budget = 128) {
        /// Albedo, in gamma space (rgb), and metallic (w).
        #[pls(rgba8)]
        pub albedo_metallic: Vec4,
    }
}

// The 256-bit layouts of the next PowerVR tiles: the world position at full precision, which
// spares the lighting pass reconstructing it from depth, and light accumulation's red and green
// at half precision; then everything else at half precision or in small floats, linear.
layouts_beginning_with! {
    {
        /// World position, x.
        #[pls(r32f)]
        pub position_x: f32,
        /// World position, y.
        #[pls(r32f)]
        pub position_y: f32,
        /// World position, z.
        #[pls(r32f)]
        pub position_z: f32,
        /// Light accumulation, red and green.
        #[pls(rg16f)]
        pub light_accumulation_rg: Vec2,
    }

    /// Listing 2.7: a future metallic workflow in 256 bits, world position instead of depth and
    /// everything in linear space at half precision.
    FutureMetallic(budget = 256) {
        /// Light accumulation, blue, and the normal's x.
        #[pls(rg16f)]
        pub light_accumulation_b_normal_x: Vec2,
        /// The normal's y and z.
        #[pls(rg16f)]
        pub normal_yz: Vec2,
        /// Roughness and metallic.
        #[pls(rg16f)]
        pub roughness_metallic: Vec2,
        /// Albedo (dielectrics) or reflectance (metals), linear.
        #[pls(r11f_g11f_b10f)]
        pub albedo_or_reflectance: Vec3,
    }

    /// Listing 2.8: a future specular workflow in 256 bits.
    FutureSpecular(budget = 256) {
        /// Light accumulation, blue, and roughness.
        #[pls(rg16f)]
        pub light_accumulation_b_roughness: Vec2,
        /// The normal, mapped to 0..1.
        #[pls(r11f_g11f_b10f)]
        pub normal: Vec3,
        /// Diffuse albedo, linear.
        #[pls(r11f_g11f_b10f)]
        pub albedo: Vec3,
        /// Specular reflectance, linear.
        #[pls(r11f_g11f_b10f)]
        pub reflectance: Vec3,
    }
}

/// Arm's pixel local storage block: HDR light, albedo in pseudo-gamma (square root), the
/// normal mapped to 0..1 and metallic/roughness, in 128 bits (102 used).
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 128)]
pub struct ArmTileBlock {
    /// HDR light accumulation.
    #[pls(r11f_g11f_b10f)]
    pub light: Vec3,
    /// Albedo in pseudo-gamma (square root of linear).
    #[pls(rgba8)]
    pub albedo: Vec3,
    /// The normal, mapped to 0..1.
    #[pls(rgb10_a2)]
    pub normal: Vec3,
    /// Metallic and roughness.
    #[pls(rgba8)]
    pub metallic_roughness: Vec2,
}

/// The name, report and WGSL of every seed layout, for tools that iterate over them.
pub fn all() -> Vec<(crate::layout::Layout, &'static str)> {
    fn entry<L: GBufferLayout>() -> (crate::layout::Layout, &'static str) {
        (L::layout(), L::WGSL)
    }
    vec![
        entry::<SpecularWorkflow>(),
        entry::<MobileMetallic>(),
        entry::<FutureMetallic>(),
        entry::<FutureSpecular>(),
        entry::<ArmTileBlock>(),
    ]
}
