//! The derive's expansion resolves every name absolutely: it compiles in a crate with
//! `#![no_implicit_prelude]` and beside user items named like the ones it uses.

#![no_implicit_prelude]
#![allow(dead_code, non_camel_case_types)]

mod layouts {
    use ::shaderlib::glam::{Vec3, Vec4};

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
    pub struct words;
    pub mod core {}
    pub mod std {}
    pub mod shaderlib {}
    pub mod glam {}
    pub mod packing {}

    #[derive(
        ::shaderlib::GBufferLayout,
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
        pub material: ::shaderlib::glam::UVec4,
    }
}

#[test]
fn derive_compiles_and_works_without_the_prelude() {
    use ::shaderlib::GBufferLayout;
    let texel = layouts::Hygienic {
        light_accumulation: ::shaderlib::glam::Vec3::new(0.0, 0.5, 1.0),
        depth: 0.25,
        normals_roughness: ::shaderlib::glam::Vec4::ONE,
        material: ::shaderlib::glam::UVec4::new(1, 2, 3, 400),
    };
    let words = texel.pack();
    ::std::assert_eq!(words[3], 0xff03_0201);
    ::std::assert_eq!(layouts::Hygienic::unpack(&words).depth, 0.25);
    ::std::assert_eq!(<layouts::Hygienic as GBufferLayout>::USED_BITS, 126);
}
