//! The renderer's WGSL translated by naga for the on-tile backends: whole vertex shaders, and
//! the declarations of a fragment stage (types, constants, textures, functions) that a
//! hand-written `main` wraps with what WGSL cannot say: framebuffer fetch on GLES, subpass
//! inputs on Vulkan.
//!
//! The G-buffer layout's own declarations come from its generated include, pasted verbatim; the
//! translation of the renderer's WGSL, which declares the layout too (its functions take the
//! texel struct), leaves those out by name, so each is declared once.

use std::collections::HashSet;

use gbuffer_codegen::emit::glsl::naga_glsl;
use naga::back::glsl;

/// Which GLSL a translation is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    /// GLSL ES 3.10 (the GLES backend runs on GLES 3.2; panfrost, whose compiler the cost model
    /// runs, offers 3.10 at most).
    Gles,
    /// GLSL 450 for Vulkan (compiled to SPIR-V by glslang).
    Vulkan,
}

/// A translated stage: the GLSL, and the sampler uniforms naga declared with the binding of
/// the texture each samples (GLES binds them to texture units by name).
#[derive(Clone, Debug)]
pub struct Translation {
    /// The GLSL.
    pub text: String,
    /// (uniform name, binding of its texture in group 0).
    pub samplers: Vec<(String, u32)>,
}

/// Parses and validates WGSL, naming the problem with the source when it does not.
pub fn module(wgsl: &str) -> Result<(naga::Module, naga::valid::ModuleInfo), String> {
    naga_glsl::validate(wgsl, naga_glsl::GENERATED_CODE_CAPABILITIES)
        .map_err(|error| format!("the renderer's WGSL: {error}"))
}

/// naga's GLSL of entry point `entry` (of `stage`) in `wgsl`. Clip space is left as the WGSL
/// writes it (no coordinate adjustment: the scene flips y itself, `CLIP_Y_SIGN`), and every
/// resource of group 0 keeps its binding number.
pub fn translate(
    wgsl: &str,
    stage: naga::ShaderStage,
    entry: &str,
    dialect: Dialect,
) -> Result<Translation, String> {
    let (module, info) = module(wgsl)?;
    let version = match dialect {
        Dialect::Gles => glsl::Version::new_gles(310),
        Dialect::Vulkan => glsl::Version::Desktop(450),
    };
    let options = naga_glsl::options_keeping_bindings(&module, version);
    let (mut text, reflection) = naga_glsl::write((&module, &info), stage, entry, &options)?;
    let mut samplers: Vec<(String, u32)> = reflection
        .texture_mapping
        .iter()
        .filter_map(|(name, mapping)| {
            let binding = module.global_variables[mapping.texture].binding.as_ref()?;
            Some((name.clone(), binding.binding))
        })
        .collect();
    samplers.sort();
    if dialect == Dialect::Vulkan {
        // naga writes GL's names; Vulkan GLSL renames the vertex and instance indices.
        text = text
            .replace("gl_VertexID", "gl_VertexIndex")
            .replace("gl_InstanceID", "gl_InstanceIndex");
    }
    Ok(Translation { text, samplers })
}

/// The declarations of a translated fragment stage for a hand-written `main`: no `#version`,
/// `#extension` or precision statement, no entry point or its inputs and outputs, and none of
/// the declarations `include` already makes (the G-buffer layout's, by name).
pub fn declarations(translation: &str, include: &str) -> String {
    let declared = declared_names(include);
    let lines: Vec<&str> = translation.lines().collect();
    let mut out = String::new();
    let mut index = 0;
    while index < lines.len() {
        let line = lines[index];
        // A top-level block runs to its closing line at column 0.
        let end = if line.ends_with('{') && !line.starts_with(' ') {
            index
                + lines[index..]
                    .iter()
                    .position(|line| *line == "}" || *line == "};")
                    .unwrap_or(lines.len() - index - 1)
        } else {
            index
        };
        let skip = line.starts_with('#')
            || line.starts_with("precision ")
            || line.starts_with("void main()")
            || is_entry_point_interface(line)
            || declared_name(line).is_some_and(|name| declared.contains(name));
        if !skip {
            for line in &lines[index..=end] {
                out.push_str(line);
                out.push('\n');
            }
        }
        index = end + 1;
    }
    out
}

/// The entry point's own inputs and outputs, which the hand-written `main` declares.
fn is_entry_point_interface(line: &str) -> bool {
    let line = line.trim_start_matches("layout(location = ");
    [
        "smooth in ",
        "flat in ",
        "in ",
        "out ",
        "smooth out ",
        "flat out ",
    ]
    .iter()
    .any(|prefix| {
        line.starts_with(prefix)
            || line
                .split_once(") ")
                .is_some_and(|(_, rest)| rest.starts_with(prefix))
    })
}

/// The names the top-level declarations of `glsl` make.
fn declared_names(glsl: &str) -> HashSet<&str> {
    glsl.lines()
        .filter(|line| !line.starts_with(' ') && !line.starts_with('}'))
        .filter_map(declared_name)
        .collect()
}

/// The name a top-level line declares: `struct Name {`, `const T NAME = ...;`, or a function
/// `T name(...) {` (precision qualifiers and array return types included).
fn declared_name(line: &str) -> Option<&str> {
    if line.starts_with(' ') || line.starts_with('#') || line.starts_with("//") {
        return None;
    }
    if let Some(rest) = line.strip_prefix("struct ") {
        return rest.split_whitespace().next();
    }
    if line.starts_with("const ") {
        let (left, _) = line.split_once(" = ")?;
        return left.split_whitespace().last();
    }
    if line.ends_with(") {") {
        let (head, _) = line.split_once('(')?;
        return head.split_whitespace().last();
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_names_of_declarations_are_read() {
        assert_eq!(
            declared_name("struct MobileMetallic {"),
            Some("MobileMetallic")
        );
        assert_eq!(
            declared_name("const highp uint MOBILE_METALLIC_WORDS = 4u;"),
            Some("MOBILE_METALLIC_WORDS")
        );
        assert_eq!(
            declared_name("highp uint[4] pack_mobile_metallic(MobileMetallic v) {"),
            Some("pack_mobile_metallic")
        );
        assert_eq!(declared_name("    return x;"), None);
    }

    #[test]
    fn declarations_leave_out_what_the_include_declares_and_the_entry_point() {
        let include =
            "struct Texel {\n    float a;\n};\nfloat decode(uint w) {\n    return 0.0;\n}\n";
        let translation = "#version 320 es\nprecision highp float;\nstruct Texel {\n    float a;\n};\nstruct Mine {\n    float b;\n};\nfloat decode(uint w) {\n    return 1.0;\n}\nfloat mine(Texel t) {\n    return t.a;\n}\nlayout(location = 0) out vec4 _fs2p_location0;\nvoid main() {\n    _fs2p_location0 = vec4(0.0);\n}\n";
        assert_eq!(
            declarations(translation, include),
            "struct Mine {\n    float b;\n};\nfloat mine(Texel t) {\n    return t.a;\n}\n"
        );
    }
}
