//! Which of Bevy's shaders read its G-buffer texture, and whether each reads it through the
//! layout.
//!
//! The plugin replaces the functions that write and decode Bevy's G-buffer
//! (`deferred_gbuffer_from_pbr_input`, `pbr_input_from_deferred_gbuffer`), so a shader reads the
//! layout only where it hands the texel it loads to `pbr_input_from_deferred_gbuffer`. In Bevy
//! 0.20.1 two do: the deferred lighting pass and the screen-space reflections. A shader that
//! reads the words another way (as Bevy's own bits) would read the layout wrongly without a
//! word, so the plugin checks each shader Bevy loads ([`reading`]) and stops the app, naming the
//! module and the line, where one does.
//!
//! The check reads the text: each `let <name> = textureLoad(deferred_prepass_texture, ...)`
//! must reach `pbr_input_from_deferred_gbuffer`, and every other use of `<name>` is a raw read.
//! A raw read under `@if(WEBGL2)` is allowed on every other target: Bevy defines `WEBGL2` only
//! in a WebGL2 build (its deferred lighting reads its own depth bits there), and there the
//! plugin refuses it like any other.

use std::fmt;

/// The texture Bevy binds its G-buffer to in the view's bind group.
const TEXTURE: &str = "deferred_prepass_texture";

/// The function that decodes a G-buffer texel, the layout's once the plugin is in place.
const DECODE: &str = "pbr_input_from_deferred_gbuffer";

/// Whether this build is one where Bevy defines `WEBGL2` (a WebGL2 build: wasm32 without
/// WebGPU; the plugin has no `webgpu` feature to tell the two apart, so wasm32 counts).
const WEBGL2_BUILD: bool = cfg!(target_arch = "wasm32");

/// How a shader reads Bevy's G-buffer texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reading {
    /// It loads no texel of it (it may declare or import the binding).
    None,
    /// Every texel it loads goes to `pbr_input_from_deferred_gbuffer`: it reads the layout.
    Decodes,
}

/// A line of a shader that reads Bevy's G-buffer words other than through the layout.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RawRead {
    /// The shader's asset path.
    pub path: String,
    /// The line, from 1.
    pub line: usize,
    /// The line's text, trimmed.
    pub text: String,
}

impl fmt::Display for RawRead {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            out,
            "GBufferPlugin: {}, line {}, reads Bevy's G-buffer as Bevy's own bits (`{}`), not \
             through `{DECODE}`, so it would not read the layout",
            self.path, self.line, self.text
        )
    }
}

/// How the shader at `path`, whose text is `source`, reads Bevy's G-buffer texture, or the
/// first line that reads it other than through the layout.
pub fn reading(path: &str, source: &str) -> Result<Reading, RawRead> {
    let lines: Vec<&str> = source.lines().collect();
    let raw = |index: usize| RawRead {
        path: path.to_string(),
        line: index + 1,
        text: lines[index].trim().to_string(),
    };
    let load = format!("textureLoad({TEXTURE}");
    let mut reading = Reading::None;
    for (at, line) in lines.iter().enumerate() {
        if !line.contains(&load) {
            continue;
        }
        // `let <name> = textureLoad(deferred_prepass_texture, ...)`, nothing else.
        let name = line
            .trim()
            .strip_prefix("let ")
            .and_then(|rest| rest.split_once('='))
            .map(|(name, value)| (name.trim(), value.trim()))
            .filter(|(name, value)| is_identifier(name) && value.starts_with(&load))
            .map(|(name, _)| name)
            .ok_or_else(|| raw(at))?;
        let mut decoded = false;
        for (use_at, used) in lines.iter().enumerate() {
            if use_at == at || !mentions(used, name) {
                continue;
            }
            if decodes(used, name) {
                decoded = true;
            } else if WEBGL2_BUILD || !under_webgl2(&lines[..use_at]) {
                return Err(raw(use_at));
            }
        }
        if !decoded {
            return Err(raw(at));
        }
        reading = Reading::Decodes;
    }
    Ok(reading)
}

/// Whether `text` is a WGSL identifier.
fn is_identifier(text: &str) -> bool {
    text.chars()
        .next()
        .is_some_and(|first| first.is_alphabetic() || first == '_')
        && text.chars().all(|c| c.is_alphanumeric() || c == '_')
}

/// Whether `line` names the identifier `name` (not a longer one that contains it).
fn mentions(line: &str, name: &str) -> bool {
    line.match_indices(name).any(|(at, _)| {
        let before = line[..at].chars().next_back();
        let after = line[at + name.len()..].chars().next();
        ![before, after]
            .into_iter()
            .flatten()
            .any(|c| c.is_alphanumeric() || c == '_')
    })
}

/// Whether `line` hands `name`, whole, to the decode: `pbr_input_from_deferred_gbuffer(..., name)`.
fn decodes(line: &str, name: &str) -> bool {
    line.split_once(&format!("{DECODE}("))
        .and_then(|(_, arguments)| arguments.split_once(')'))
        .is_some_and(|(arguments, _)| arguments.split(',').any(|argument| argument.trim() == name))
}

/// Whether the statement after `before` is under `@if(WEBGL2)`: the last line before it that is
/// not blank is that attribute.
fn under_webgl2(before: &[&str]) -> bool {
    before
        .iter()
        .rev()
        .map(|line| line.trim())
        .find(|line| !line.is_empty())
        .is_some_and(|line| line == "@if(WEBGL2)")
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIGHTING: &str = "
fn fragment(in: FullscreenVertexOutput) -> @location(0) vec4<f32> {
    let deferred_data = textureLoad(deferred_prepass_texture, vec2<i32>(frag_coord.xy), 0);

    @if(WEBGL2)
    frag_coord.z = unpack_unorm3x4_plus_unorm_20_(deferred_data.b).w;
    var pbr_input = pbr_input_from_deferred_gbuffer(frag_coord, deferred_data);
}
";

    #[test]
    fn a_texel_handed_to_the_decode_reads_the_layout() {
        assert_eq!(reading("lighting.wesl", LIGHTING), Ok(Reading::Decodes));
        // Declaring or importing the binding reads nothing.
        let bindings = "@group(0) @binding(23) var deferred_prepass_texture: texture_2d<u32>;\n";
        assert_eq!(reading("bindings.wesl", bindings), Ok(Reading::None));
        let import =
            "import package::render::mesh_view_bindings::{deferred_prepass_texture, view};\n";
        assert_eq!(reading("ssr.wesl", import), Ok(Reading::None));
    }

    #[test]
    fn a_raw_read_is_named_with_its_module_and_line() {
        // Outside `@if(WEBGL2)`, the same read is Bevy's bits on every target.
        let raw = LIGHTING.replace("    @if(WEBGL2)\n", "");
        let error = reading("embedded://bevy_pbr/x.wesl", &raw).unwrap_err();
        assert_eq!(error.line, 5);
        assert_eq!(
            error.to_string(),
            "GBufferPlugin: embedded://bevy_pbr/x.wesl, line 5, reads Bevy's G-buffer as Bevy's \
             own bits (`frag_coord.z = unpack_unorm3x4_plus_unorm_20_(deferred_data.b).w;`), not \
             through `pbr_input_from_deferred_gbuffer`, so it would not read the layout"
        );
        // A texel never decoded, and a load that is not a plain `let`.
        let unread = "let words = textureLoad(deferred_prepass_texture, xy, 0);\nout = words.r;\n";
        assert_eq!(reading("a.wesl", unread).unwrap_err().line, 2);
        let undecoded = "let words = textureLoad(deferred_prepass_texture, xy, 0);\n";
        assert_eq!(reading("a.wesl", undecoded).unwrap_err().line, 1);
        let inline = "out = textureLoad(deferred_prepass_texture, xy, 0).r;\n";
        assert_eq!(reading("a.wesl", inline).unwrap_err().line, 1);
        // A longer name that contains the texel's is not a use of it.
        let longer = "let g = textureLoad(deferred_prepass_texture, xy, 0);\n\
                      let gx = 1;\nlet p = pbr_input_from_deferred_gbuffer(c, g);\n";
        assert_eq!(reading("a.wesl", longer), Ok(Reading::Decodes));
    }
}
