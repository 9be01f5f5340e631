//! A G-buffer declared in a layout file rather than with the derive: the build script writes
//! `mobile_metallic.rs` (the struct and its `GBufferLayout` impl) and the shader includes.
//! Run with `cargo run -p build-script-example`.

use gbuffer::glam::{Vec3, Vec4};
use gbuffer::GBufferLayout;

include!(concat!(env!("OUT_DIR"), "/mobile_metallic.rs"));

/// The GLSL ES framebuffer-fetch include, for the engine's OpenGL ES path.
const FRAMEBUFFER_FETCH_GLSL: &str =
    include_str!(concat!(env!("OUT_DIR"), "/mobile_metallic.fetch.glsl"));

fn main() {
    let texel = MobileMetallic {
        light_accumulation: Vec3::new(0.25, 0.5, 1.0),
        depth: 0.75,
        normals_roughness: Vec4::new(0.5, 0.5, 1.0, 0.3),
        albedo_metallic: Vec4::new(1.0, 0.8, 0.2, 1.0),
    };
    let words = texel.pack();
    println!("{}", MobileMetallic::report());
    println!("packed: {words:08x?}");
    println!("unpacked: {:?}", MobileMetallic::unpack(&words));
    println!(
        "WGSL: {} lines; GLSL framebuffer fetch: {} lines",
        MobileMetallic::WGSL.lines().count(),
        FRAMEBUFFER_FETCH_GLSL.lines().count()
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_layout_file_mirror_packs_as_the_derived_layout_does() {
        let texel = MobileMetallic {
            light_accumulation: Vec3::new(0.1, 0.7, 3.0),
            depth: 0.123,
            normals_roughness: Vec4::new(0.2, 0.4, 0.6, 0.8),
            albedo_metallic: Vec4::new(0.9, 0.1, 0.5, 1.0),
        };
        let derived = gbuffer::seed_layouts::MobileMetallic {
            light_accumulation: texel.light_accumulation,
            depth: texel.depth,
            normals_roughness: texel.normals_roughness,
            albedo_metallic: texel.albedo_metallic,
        };
        assert_eq!(texel.pack(), derived.pack());
        assert_eq!(
            MobileMetallic::WGSL,
            gbuffer::seed_layouts::MobileMetallic::WGSL.to_string() + "\n"
        );
    }
}
