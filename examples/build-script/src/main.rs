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

    /// The guide's quick start shows this crate's build script and includes: every line of
    /// its `rust,ignore` blocks is a line of `build.rs` or of this file, so the page cannot
    /// drift from the crate that CI runs.
    #[test]
    fn the_quick_start_quotes_this_crate() {
        let root = env!("CARGO_MANIFEST_DIR");
        let read = |path: &str| {
            std::fs::read_to_string(format!("{root}/{path}"))
                .unwrap_or_else(|error| panic!("{path}: {error}"))
        };
        let page = read("../../book/src/quick-start.md");
        let own = [read("build.rs"), read("src/main.rs")];
        let mut quoted = 0;
        let mut in_block = false;
        for line in page.lines() {
            if line.starts_with("```") {
                in_block = line == "```rust,ignore";
                continue;
            }
            if in_block && !line.trim().is_empty() {
                quoted += 1;
                assert!(
                    own.iter().any(|file| file.lines().any(|own| own == line)),
                    "the quick start's line\n{line}\nis not in examples/build-script"
                );
            }
        }
        assert!(quoted >= 8, "the quick start quotes {quoted} lines");
    }
}
