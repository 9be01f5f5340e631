//! The fused frame in a browser: WebGL 2 with pixel local storage (ANGLE's, which Chromium
//! offers behind `--enable-webgl-draft-extensions`) draws the frame of [`crate::on_tile`] with
//! the G-buffer in planes that are cleared on tile and never stored; only the output is.
//!
//! The page (`web/fused.mjs`, plain JavaScript) holds the host's calls; this module makes what
//! it loads, as files: the five programs in GLSL ES 3.00 (the renderer's WGSL translated by naga,
//! the layout's WebGL include as generated, the stages' `main`s without `discard`, which pixel
//! local storage forbids: the GLES paths' programs in WebGL's dialect), the texture unit of
//! each sampler uniform (GLSL ES 3.00 has no binding qualifiers, and the units are the
//! bindings the WGSL gives the inputs), the mesh and the baked inputs (`scene.mjs`), and the layout's host
//! module (`layout.webgl_pls.js`).

use std::fmt::Write as _;

use gbuffer_core::Named;
use gbuffer_files::json::string as json_string;

use crate::fused_programs::{fused_programs, FusedDialect};
use crate::inputs::{Inputs, Texels};
use crate::mesh::Mesh;
use crate::options::Options;
use crate::scene::{DECALS, POINT_LIGHT_COUNT};
use crate::shaders::{ENVIRONMENT_BINDING, LIGHT_MAP_BINDING, LUT_BINDING};

/// The files the page loads for `options`: `scene.mjs` (the programs, the mesh, the inputs and
/// the frame's size and draws) and `layout.webgl_pls.js` (the layout's host module).
pub fn export(options: &Options, inputs: &Inputs) -> Result<Vec<(String, Vec<u8>)>, String> {
    let fused = fused_programs(options, FusedDialect::WebGlPixelLocalStorage)?;
    let host = fused
        .webgl_host
        .clone()
        .ok_or("the WebGL programs have no host module")?;
    let mesh = Mesh::scene();
    let mut scene = String::from(
        "// The fused frame's scene for web/fused.mjs, exported by gbuffer-render (render/src/webgl.rs):\n\
         // edit the renderer, not this file.\n\n",
    );
    let _ = writeln!(
        scene,
        "export const WIDTH = {};\nexport const HEIGHT = {};",
        options.width, options.height
    );
    let _ = writeln!(
        scene,
        "export const POINT_LIGHT_COUNT = {POINT_LIGHT_COUNT};\nexport const DECAL_COUNT = {};",
        DECALS.len()
    );
    scene
        .push_str("\n/** One program per stage, in drawing order. */\nexport const PROGRAMS = [\n");
    for program in &fused.programs {
        let samplers: Vec<String> = program
            .samplers
            .iter()
            .map(|(name, unit)| format!("[{}, {unit}]", json_string(name)))
            .collect();
        let _ = writeln!(
            scene,
            "  {{ stage: {}, vertex: {}, fragment: {}, samplers: [{}] }},",
            json_string(program.stage.name()),
            json_string(program.glsl_vertex()?),
            json_string(&program.fragment),
            samplers.join(", ")
        );
    }
    scene.push_str("];\n\n");
    let vertices: &[u8] = bytemuck::cast_slice(&mesh.vertices);
    let indices: &[u8] = bytemuck::cast_slice(&mesh.indices);
    let _ = writeln!(
        scene,
        "/** The mesh: per vertex its position and normal (f32 x 3 each) and object (u32), 28 bytes; u32 indices. */\n\
         export const MESH = {{ vertices: \"{}\", indices: \"{}\", indexCount: {} }};\n",
        base64(vertices),
        base64(indices),
        mesh.indices.len()
    );
    scene.push_str(
        "/** The inputs: texture unit, format, wrapping in s, and the mips, largest first (bytes in base64). */\n\
         export const TEXTURES = [\n",
    );
    for (unit, format, repeat, mips) in [
        (
            ENVIRONMENT_BINDING,
            "RGBA8",
            true,
            inputs.environment.as_slice(),
        ),
        (
            LUT_BINDING,
            "RGBA16F",
            false,
            std::slice::from_ref(&inputs.lut),
        ),
        (
            LIGHT_MAP_BINDING,
            "RGBA8",
            false,
            std::slice::from_ref(&inputs.light_map),
        ),
    ] {
        let levels: Vec<String> = mips.iter().map(level).collect();
        let _ = writeln!(
            scene,
            "  {{ unit: {unit}, internalFormat: \"{format}\", repeat: {repeat}, mips: [{}] }},",
            levels.join(", ")
        );
    }
    scene.push_str("];\n");
    Ok(vec![
        ("scene.mjs".into(), scene.into_bytes()),
        ("layout.webgl_pls.js".into(), host.into_bytes()),
    ])
}

/// A mip level as the page reads it.
fn level(texels: &Texels) -> String {
    format!(
        "{{ width: {}, height: {}, bytes: \"{}\" }}",
        texels.width,
        texels.height,
        base64(&texels.bytes)
    )
}

/// Standard base64 (RFC 4648), with padding.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let value = (u32::from(chunk[0]) << 16)
            | (u32::from(*chunk.get(1).unwrap_or(&0)) << 8)
            | u32::from(*chunk.get(2).unwrap_or(&0));
        for index in 0..4 {
            if index <= chunk.len() {
                out.push(ALPHABET[(value >> (18 - 6 * index) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// RFC 4648's test vectors.
    #[test]
    fn base64_is_rfc_4648s() {
        for (input, output) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(input.as_bytes()), output);
        }
    }
}
