//! The one way WGSL becomes GLSL here: naga parses and validates the WGSL with the capabilities
//! generated code needs, and its GLSL writer translates one entry point. The includes' emitter,
//! the validator's portability check and the renderer's on-tile backends all call it, so they
//! translate alike; and [`declarations`] picks out of naga's GLSL what a hand-written `main`
//! or an include keeps.

use std::collections::HashSet;

use naga::back::glsl;
use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};

/// The naga capabilities the generated WGSL needs beyond the defaults: the exact decode of
/// half-float words calls `unpack2x16float`, which naga gates behind
/// `SHADER_FLOAT16_IN_FLOAT32` (wgpu grants it on every adapter but Mesa's without
/// shader-f16).
pub const GENERATED_CODE_CAPABILITIES: Capabilities = Capabilities::SHADER_FLOAT16_IN_FLOAT32;

/// Why WGSL was refused: naga's parse error or its validation error, whole, for a caller that
/// reports them in its own form (the validator's diagnostics).
#[derive(Debug)]
pub enum WgslError {
    /// The WGSL front end's error.
    Parse(naga::front::wgsl::ParseError),
    /// The validator's error, with its spans, and the module it refused (for the names its
    /// handles stand for).
    Validate(Box<(naga::Module, naga::WithSpan<naga::valid::ValidationError>)>),
}

impl WgslError {
    /// naga's message with the source lines it points at.
    pub fn emit_to_string(&self, wgsl: &str) -> String {
        match self {
            WgslError::Parse(error) => error.emit_to_string(wgsl),
            WgslError::Validate(refused) => refused.1.emit_to_string(wgsl),
        }
    }
}

/// Parses and validates `wgsl` with every validation flag, the default capabilities and
/// `extra`: the one place WGSL is taken in.
pub fn parse_and_validate(
    wgsl: &str,
    extra: Capabilities,
) -> Result<(naga::Module, ModuleInfo), WgslError> {
    let module = naga::front::wgsl::parse_str(wgsl).map_err(WgslError::Parse)?;
    match Validator::new(ValidationFlags::all(), Capabilities::default() | extra).validate(&module)
    {
        Ok(info) => Ok((module, info)),
        Err(error) => Err(WgslError::Validate(Box::new((module, error)))),
    }
}

/// [`parse_and_validate`], the error as naga's message with the source.
pub fn validate(wgsl: &str, extra: Capabilities) -> Result<(naga::Module, ModuleInfo), String> {
    parse_and_validate(wgsl, extra).map_err(|error| error.emit_to_string(wgsl))
}

/// Options for naga's GLSL writer: `version`, clip space left as the WGSL writes it (no
/// coordinate adjustment), and every resource keeping its WGSL binding number (GLSL ES 3.10
/// and GLSL 450 declare bindings in the shader; a host binds by those numbers).
pub fn options_keeping_bindings(module: &naga::Module, version: glsl::Version) -> glsl::Options {
    let mut binding_map = glsl::BindingMap::default();
    for (_, global) in module.global_variables.iter() {
        if let Some(binding) = &global.binding {
            binding_map.insert(*binding, binding.binding as u8);
        }
    }
    glsl::Options {
        version,
        writer_flags: glsl::WriterFlags::empty(),
        binding_map,
        ..glsl::Options::default()
    }
}

/// naga's GLSL of entry point `entry` (of `stage`) of a validated module, and the reflection
/// that says which uniform samples which texture. `options` says the version, the writer's
/// flags (naga's default adjusts clip space to GL's) and the bindings.
pub fn write(
    (module, info): (&naga::Module, &ModuleInfo),
    stage: naga::ShaderStage,
    entry: &str,
    options: &glsl::Options,
) -> Result<(String, glsl::ReflectionInfo), String> {
    let pipeline = glsl::PipelineOptions {
        shader_stage: stage,
        entry_point: entry.to_string(),
        multiview: None,
    };
    let mut text = String::new();
    let reflection = glsl::Writer::new(
        &mut text,
        module,
        info,
        options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )
    .and_then(|mut writer| writer.write())
    .map_err(|error| format!("naga cannot translate `{entry}` to GLSL: {error}"))?;
    Ok((text, reflection))
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
