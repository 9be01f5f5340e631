//! The derive's expansion resolves every name absolutely: it compiles in a crate with
//! `#![no_implicit_prelude]` and beside user items named like the ones it uses.

#![no_implicit_prelude]
#![allow(dead_code, non_camel_case_types)]

mod layouts {
    use ::gbuffer::glam::{Vec3, Vec4};

    // Items named like what the expansion refers to; none of them may be picked up.
    pub struct Format;
    pub struct Layout;
    pub struct FieldType;
    pub struct ScalarKind;
    pub struct GBufferLayout;
    pub struct Option;
    pub struct Some;
    pub struct Result;
    pub struct String;
    pub struct Vec;
    pub struct u32;
    pub struct usize;
    pub struct str;
    pub struct channels;
    // The slices' loop's generic parameters' names.
    pub struct N;
    pub struct I;
    pub struct words;
    pub mod core {}
    pub mod std {}
    pub mod gbuffer {}
    pub mod glam {}
    pub mod packing {}

    #[derive(
        ::gbuffer::GBufferLayout,
        ::core::clone::Clone,
        ::core::marker::Copy,
        ::core::fmt::Debug,
        ::core::cmp::PartialEq,
    )]
    #[gbuffer(budget = 128)]
    pub struct Hygienic {
        #[pls(rgb10_a2)]
        pub light_accumulation: Vec3,
        #[pls(r32f)]
        pub depth: f32,
        #[pls(rgba8)]
        pub normals_roughness: Vec4,
        #[pls(rgba8ui)]
        pub material: ::gbuffer::glam::UVec4,
    }
}

#[test]
fn derive_compiles_and_works_without_the_prelude() {
    use ::gbuffer::GBufferLayout;
    let texel = layouts::Hygienic {
        light_accumulation: ::gbuffer::glam::Vec3::new(0.0, 0.5, 1.0),
        depth: 0.25,
        normals_roughness: ::gbuffer::glam::Vec4::ONE,
        material: ::gbuffer::glam::UVec4::new(1, 2, 3, 400),
    };
    let words = texel.pack();
    ::std::assert_eq!(words[3], 0xff03_0201);
    ::std::assert_eq!(layouts::Hygienic::unpack(&words).depth, 0.25);
    ::std::assert_eq!(<layouts::Hygienic as GBufferLayout>::USED_BITS, 126);
}

/// The crate as a user's engine re-exports it, under another name.
mod engine {
    pub use ::gbuffer as rendering;
}

mod renamed {
    use ::gbuffer::glam::Vec4;

    // No `gbuffer` at the crate root here would do: the derive must use the path it is given.
    #[derive(crate::engine::rendering::GBufferLayout)]
    #[gbuffer(budget = 64, crate = "crate::engine::rendering")]
    pub struct ThroughReexport {
        #[pls(rgba8)]
        pub albedo: Vec4,
        #[pls(r32f)]
        pub depth: f32,
    }
}

#[test]
fn derive_uses_the_crate_path_it_is_given() {
    use crate::engine::rendering::GBufferLayout;
    let texel = renamed::ThroughReexport {
        albedo: ::gbuffer::glam::Vec4::ONE,
        depth: 0.5,
    };
    ::std::assert_eq!(texel.pack(), [0xffff_ffff, 0x3f00_0000]);
    ::std::assert_eq!(renamed::ThroughReexport::layout().name, "ThroughReexport");
}
