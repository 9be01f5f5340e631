//! The fused frame in a browser: WebGL 2 with pixel local storage (ANGLE's, which Chromium
//! offers behind `--enable-webgl-draft-extensions`) draws the frame of [`crate::on_tile`] with
//! the G-buffer in planes that are cleared on tile and never stored; only the output is.
//!
//! The page (`web/fused.mjs`, plain JavaScript) holds the host's calls; this module makes what
//! it loads, as files: the six programs in GLSL ES 3.00 (the renderer's WGSL translated by naga,
//! the layout's WebGL include as generated, the stages' `main`s without `discard`, which pixel
//! local storage forbids), the texture unit of each sampler uniform (GLSL ES 3.00 has no
//! binding qualifiers), the mesh and the baked inputs (`scene.mjs`), and the layout's host
//! module (`layout.webgl_pls.js`).

use std::fmt::Write as _;

use gbuffer_codegen::emit::glsl::{self as includes, Include};
use gbuffer_codegen::emit::json::string as json_string;

use crate::glsl::{self, Dialect};
use crate::inputs::{Inputs, Texels};
use crate::mesh::Mesh;
use crate::on_tile::{fused_wgsl, texel_struct_name, tile_layout, Stage};
use crate::options::Options;
use crate::scene::{DECALS, POINT_LIGHT_COUNT};

/// Texture units of the inputs: the bindings the WGSL gives them, as the GLES backend binds them.
const ENVIRONMENT_UNIT: u32 = 1;
const LUT_UNIT: u32 = 2;
const LIGHT_MAP_UNIT: u32 = 5;

/// One program of the fused frame.
#[derive(Clone, Debug)]
pub struct WebGlProgram {
    /// The stage it draws.
    pub stage: Stage,
    /// Its vertex shader.
    pub vertex: String,
    /// Its fragment shader.
    pub fragment: String,
    /// Each sampler uniform and the texture unit it samples.
    pub samplers: Vec<(String, u32)>,
}

/// The fused frame's programs for `options`, one per [`Stage`], in drawing order.
pub fn programs(options: &Options) -> Result<Vec<WebGlProgram>, String> {
    let layout = tile_layout(options)?;
    let model = layout.layout();
    let (include, _) = includes::include(&model, Include::WebGlPixelLocalStorage, 0)
        .map_err(|error| error.to_string())?;
    let wgsl = fused_wgsl(options, layout, -1.0);
    let snake = model.snake_name();
    let texel = texel_struct_name(&model)?;
    let stages = glsl::translate(
        &wgsl,
        naga::ShaderStage::Fragment,
        "translation_entry",
        Dialect::WebGl,
    )?;
    let declarations = glsl::declarations(&stages.text, &include);
    Stage::ALL
        .into_iter()
        .map(|stage| {
            let vertex = glsl::translate(
                &wgsl,
                naga::ShaderStage::Vertex,
                stage.vertex_entry(),
                Dialect::WebGl,
            )?;
            let main = stage.pixel_local_storage_main(
                &texel,
                &snake,
                &format!("    store_{snake}(texel);\n"),
            );
            let fragment = format!(
                "#version 300 es\n#extension GL_ANGLE_shader_pixel_local_storage : require\n\
                 precision highp float;\nprecision highp int;\n\n{include}\n{declarations}\n\
                 layout(location = 0) out highp vec4 frame_colour;\nuniform highp uint volume_index;\n{main}"
            );
            let mut samplers = stages.samplers.clone();
            samplers.extend(vertex.samplers);
            samplers.sort();
            samplers.dedup();
            Ok(WebGlProgram {
                stage,
                vertex: vertex.text,
                fragment,
                samplers,
            })
        })
        .collect()
}

/// The files the page loads for `options`: `scene.mjs` (the programs, the mesh, the inputs and
/// the frame's size and draws) and `layout.webgl_pls.js` (the layout's host module).
pub fn export(options: &Options, inputs: &Inputs) -> Result<Vec<(String, Vec<u8>)>, String> {
    let layout = tile_layout(options)?.layout();
    let (_, interface) = includes::include(&layout, Include::WebGlPixelLocalStorage, 0)
        .map_err(|error| error.to_string())?;
    let host = includes::webgl::host_module(&layout, &interface);
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
    for program in programs(options)? {
        let samplers: Vec<String> = program
            .samplers
            .iter()
            .map(|(name, unit)| format!("[{}, {unit}]", json_string(name)))
            .collect();
        let _ = writeln!(
            scene,
            "  {{ stage: {}, vertex: {}, fragment: {}, samplers: [{}] }},",
            json_string(program.stage.name()),
            json_string(&program.vertex),
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
            ENVIRONMENT_UNIT,
            "RGBA8",
            true,
            inputs.environment.as_slice(),
        ),
        (
            LUT_UNIT,
            "RGBA16F",
            false,
            std::slice::from_ref(&inputs.lut),
        ),
        (
            LIGHT_MAP_UNIT,
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
