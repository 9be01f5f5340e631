//! The physically based shading library: its WGSL ([`wgsl`], composed by module name with
//! [`compose`]) and its Rust side, twice over:
//!
//! - [`mirror`]: f32, the same formula in the same order of operations as the WGSL, for tests
//!   and CPU tools; on a conforming adapter the two agree within a few ulp;
//! - [`reference`](mod@reference): the same functions in f64, the ground truth the f32 forms (and the
//!   approximations among them) are measured against.
//!
//! - [`half_precision`]: the mobile forms of `mobile_half.wgsl`, rounded to f16 at every step;
//! - [`env_brdf_lut`]: the split-sum LUT the image-based lighting reads, baked on the CPU.
//!
//! ```
//! use gbuffer_shading::{compose, mirror};
//!
//! // The GGX terms and their dependencies (the constants), as one WGSL source:
//! let wgsl = compose(&["microfacet"]).unwrap();
//! assert!(wgsl.contains("fn d_ggx("));
//! // The same function on the CPU, in the same order of operations:
//! let peak = mirror::microfacet::d_ggx(1.0, 0.5);
//! assert!((peak - 1.0 / (std::f32::consts::PI * 0.0625)).abs() < 1e-5);
//! ```
//!
//! The mirror and the reference are compiled from one source per module (`functions/<module>.rs`, included with the
//! float type set to f32 or f64), so the formulas cannot drift apart. Module and function names
//! are the WGSL's.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

/// The f32 mirrors of the WGSL functions.
// The literals are the WGSL's, written as the shared source needs them for f64.
#[allow(clippy::excessive_precision)]
pub mod mirror {
    #[allow(unused_imports)]
    use glam::{BVec3, Vec2, Vec3, Vec4};
    type Float = f32;
    include!("functions/mod.rs");

    /// The functions the WGSL takes from the layouts' codecs (`gbuffer_core::codecs`): their
    /// mirrors are the codecs' own.
    mod codec_forms {
        /// `hdr`'s codec functions.
        pub mod hdr {
            use gbuffer_core::codecs::{rgb9e5, rgbm};
            use glam::{Vec3, Vec4};

            /// RGBM encode for an rgba8 target: the RGBM codec's exact encode, its codes over
            /// 255.
            pub fn rgbm_encode(linear: Vec3, range: f32) -> Vec4 {
                let word = rgbm::rgbm_from_f32(linear.to_array(), range);
                Vec4::from_array(rgbm::unit_from_word(word))
            }

            /// RGBM decode of four unorm values: the RGBM codec's.
            pub fn rgbm_decode(rgbm: Vec4, range: f32) -> Vec3 {
                Vec3::from_array(rgbm::rgbm_decode(rgbm.to_array(), range))
            }

            /// Shared-exponent encode: the rgb9e5 codec (integer-exact, so the f32 form is its
            /// own reference; `gbuffer_core`'s tests hold it against the extension's text).
            pub fn rgb9e5_encode(linear: Vec3) -> u32 {
                rgb9e5::rgb9e5_from_f32(linear.to_array())
            }

            /// Shared-exponent decode: the rgb9e5 codec.
            pub fn rgb9e5_decode(packed: u32) -> Vec3 {
                Vec3::from_array(rgb9e5::f32_from_rgb9e5(packed))
            }
        }

        /// `normals`' codec functions.
        pub mod normals {
            use gbuffer_core::codecs::octahedral;
            use glam::{Vec2, Vec3};

            /// Octahedral encode: the octahedral codec's map.
            pub fn octahedral_encode(normal: Vec3) -> Vec2 {
                Vec2::from_array(octahedral::octahedral_fold(normal.to_array()))
            }

            /// Octahedral decode: the octahedral codec's inverse map.
            pub fn octahedral_decode(encoded: Vec2) -> Vec3 {
                Vec3::from_array(octahedral::octahedral_unfold(encoded.to_array()))
            }
        }
    }
}

/// The f64 references of the WGSL functions.
pub mod reference {
    #[allow(unused_imports)]
    use glam::{BVec3, DVec2 as Vec2, DVec3 as Vec3, DVec4 as Vec4};
    type Float = f64;
    include!("functions/mod.rs");

    /// The textbook forms of the functions the WGSL takes from the codecs, in f64: what the
    /// codecs are measured against.
    mod codec_forms {
        include!("codec_references.rs");
    }
}

pub mod env_brdf_lut;
pub mod half_precision;

pub mod wgsl;

pub use wgsl::compose;
