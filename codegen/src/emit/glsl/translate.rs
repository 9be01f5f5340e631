//! The layout's WGSL translated to GLSL ES by naga, made fit to paste into a user's shader.
//!
//! naga writes a whole shader: a `#version`, default precision statements and an entry point.
//! An include must carry none of them, so the translation keeps the declarations only, and
//! gives every declaration of a float or integer type an explicit `highp`: the include then
//! compiles under any default precision the user's preamble sets (or none), and never changes
//! those defaults. `highp` matters for the integers too: GLSL ES lets a fragment shader's
//! default `int` be `mediump`, as narrow as 16 bits, and the packing needs all 32.
//!
//! naga renames identifiers that GLSL reserves (`sampler` becomes `sampler_`, `main` becomes
//! `main_`, names ending in a digit get a `_`, `__` is collapsed). The names it chose are read
//! back from the translation ([`GlslNames`]), so the hand-written parts of an include (blocks,
//! attachments, accessors) use the same names as the translated struct.

use super::TranslationError;
use crate::emit::wgsl::{function_name, Target};
use gbuffer_core::format::Format;
use gbuffer_core::layout::Layout;
use gbuffer_core::Conversions;

/// The GLSL ES version the functions are translated for: the lowest a user can write, so the
/// text compiles under `#version 300 es`, `310 es` and `320 es` alike.
const TRANSLATION_VERSION: u16 = 300;

/// The name of the empty entry point that naga's GLSL backend needs to write a shader.
const ENTRY_POINT: &str = "gbuffer_translation_entry";

/// The layout's types and functions in GLSL ES, and the names naga gave the layout's struct
/// and fields.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Translation {
    /// Declarations only: no `#version`, `#extension` or precision statement.
    pub text: String,
    /// The names naga gave the layout's struct, fields and targets.
    pub names: GlslNames,
}

impl Translation {
    /// Checks that the translation defines function `name` as the WGSL named it (naga keeps
    /// a name that is no GLSL keyword and does not end in a digit, as the generated helpers'
    /// are): the includes call it by that name.
    pub fn check_defines(&self, name: &str) -> Result<(), TranslationError> {
        match self.text.contains(&format!(" {name}(")) {
            true => Ok(()),
            false => Err(TranslationError(format!(
                "naga's GLSL for `{}` has no function `{name}`",
                self.names.layout
            ))),
        }
    }
}

/// What the layout's identifiers are called in GLSL.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GlslNames {
    /// The texel struct (the layout's name, renamed if GLSL reserves it).
    pub layout: String,
    /// Its members, one per field, in field order.
    pub fields: Vec<String>,
    /// The `<Name>Targets` struct.
    pub targets: String,
    /// Its `vec4<u32>` members, one per `Rgba32Uint` target.
    pub target_members: Vec<String>,
}

/// Translates the layout's exact WGSL to GLSL ES declarations with explicit precision.
pub fn translate(layout: &Layout) -> Result<Translation, TranslationError> {
    translate_with(layout, Conversions::Exact)
}

/// Translates the layout's WGSL with the chosen conversions. GLSL ES 3.00 has no
/// `packUnorm4x8`: under fast conversions rgba8 is translated from f32 arithmetic, and the
/// builtins take over from GLSL ES 3.10 up (`#if __VERSION__ >= 310`).
pub fn translate_with(
    layout: &Layout,
    conversions: Conversions,
) -> Result<Translation, TranslationError> {
    let glsl = naga_glsl(layout, conversions)?;
    let body = declarations(&glsl);
    let names = read_names(&body, layout)?;
    let mut text = with_explicit_precision(&body);
    // rgba8's fast functions: the layout's own where its conversions are fast, and those of
    // fields that choose fast conversions against exact ones.
    let prefix = layout.snake_name();
    let fast_suffixes: &[&str] = match conversions {
        Conversions::Fast => &[""],
        Conversions::Exact => &["_fast"],
    };
    for suffix in fast_suffixes {
        for (verb, builtin) in [("encode", "packUnorm4x8"), ("decode", "unpackUnorm4x8")] {
            let name = function_name(&prefix, verb, Format::Rgba8, suffix);
            text = with_builtin_from_310(&text, &format!(" {name}("), builtin);
        }
    }
    let translation = Translation { text, names };
    check_bit_field_functions(&translation, layout)?;
    Ok(translation)
}

/// Wraps the function whose signature contains `signature` (if the text has it) in
/// `#if __VERSION__ >= 310`, with a body that calls `builtin` on its one parameter first and
/// the translated one after `#else`.
fn with_builtin_from_310(glsl: &str, signature: &str, builtin: &str) -> String {
    let lines: Vec<&str> = glsl.lines().collect();
    let definition = |line: &&str| line.contains(signature) && line.ends_with(") {");
    let Some(start) = lines.iter().position(definition) else {
        return glsl.to_string();
    };
    let Some(length) = lines[start..].iter().position(|line| *line == "}") else {
        return glsl.to_string();
    };
    let header = lines[start];
    // `highp uint name(highp vec4 c_1) {`: the parameter is the last word in the parentheses.
    let parameter = header
        .split_once('(')
        .and_then(|(_, rest)| rest.split_once(')'))
        .and_then(|(parameters, _)| parameters.split_whitespace().last())
        .unwrap_or_default();
    let mut out: Vec<String> = lines[..start].iter().map(|line| line.to_string()).collect();
    out.push("#if __VERSION__ >= 310".into());
    out.push(header.to_string());
    out.push(format!("    return {builtin}({parameter});"));
    out.push("}".into());
    out.push("#else".into());
    out.extend(
        lines[start..=start + length]
            .iter()
            .map(|line| line.to_string()),
    );
    out.push("#endif".into());
    out.extend(
        lines[start + length + 1..]
            .iter()
            .map(|line| line.to_string()),
    );
    out.join("\n") + "\n"
}

/// The bit fields' functions and their helpers alone, translated to GLSL ES declarations
/// with explicit precision (for pixel local storage includes, whose block members share the
/// global namespace with whatever the include declares).
pub fn translate_bit_field_functions(
    layout: &Layout,
    conversions: Conversions,
) -> Result<String, TranslationError> {
    let wgsl = crate::emit::wgsl::bit_field_functions(layout, conversions);
    let glsl = naga_glsl_of(wgsl)?;
    Ok(with_explicit_precision(&declarations(&glsl)))
}

/// naga's whole GLSL ES shader for the layout's WGSL plus an empty fragment entry point.
fn naga_glsl(layout: &Layout, conversions: Conversions) -> Result<String, TranslationError> {
    naga_glsl_of(crate::emit::wgsl::emit_for(
        layout,
        conversions,
        Target::GlslEs300,
    ))
}

/// naga's whole GLSL ES shader for `wgsl` plus an empty fragment entry point.
fn naga_glsl_of(mut wgsl: String) -> Result<String, TranslationError> {
    use super::naga_glsl::GENERATED_CODE_CAPABILITIES;
    use naga::back::glsl;

    wgsl.push_str(&format!(
        "\n@fragment\nfn {ENTRY_POINT}() -> @location(0) vec4<f32> {{\n    return vec4<f32>(0.0);\n}}\n"
    ));
    let (module, info) =
        super::naga_glsl::validate(&wgsl, GENERATED_CODE_CAPABILITIES).map_err(TranslationError)?;
    let options = glsl::Options {
        version: glsl::Version::new_gles(TRANSLATION_VERSION),
        ..glsl::Options::default()
    };
    let (text, _) = super::naga_glsl::write(
        (&module, &info),
        naga::ShaderStage::Fragment,
        ENTRY_POINT,
        &options,
    )
    .map_err(TranslationError)?;
    Ok(text)
}

/// Checks that naga kept the bit fields' functions' WGSL names, which name no field and hold
/// no `__` (the includes call them by those names).
fn check_bit_field_functions(
    translation: &Translation,
    layout: &Layout,
) -> Result<(), TranslationError> {
    let prefix = layout.snake_name();
    for (index, _) in layout
        .fields
        .iter()
        .enumerate()
        .filter(|(_, field)| field.bit_field().is_some())
    {
        for verb in ["encode", "decode"] {
            let name = crate::emit::wgsl::bit_field_function_name(&prefix, verb, index);
            translation.check_defines(&name)?;
        }
    }
    Ok(())
}

/// The layout's declarations in naga's GLSL ([`super::naga_glsl::declarations`]: no header,
/// entry point or its output), with runs of blank lines folded into one.
fn declarations(glsl: &str) -> String {
    let mut body = String::new();
    for line in super::naga_glsl::declarations(glsl, "").trim().lines() {
        if !(line.is_empty() && body.ends_with("\n\n")) {
            body.push_str(line);
            body.push('\n');
        }
    }
    body
}

/// Reads the names of the first two structs and their members, which the WGSL emitter
/// declares first: the texel struct and the targets struct.
fn read_names(glsl: &str, layout: &Layout) -> Result<GlslNames, TranslationError> {
    let mut structs = Vec::new();
    let mut lines = glsl.lines();
    while let Some(line) = lines.next() {
        let Some(name) = line
            .strip_prefix("struct ")
            .and_then(|rest| rest.strip_suffix(" {"))
        else {
            continue;
        };
        let members: Vec<String> = lines
            .by_ref()
            .take_while(|line| !line.starts_with("};"))
            .filter_map(|member| {
                let declaration = member.trim().strip_suffix(';')?;
                let name = declaration.rsplit(' ').next()?;
                // Array members are written `type name[N]`.
                Some(name.split('[').next().unwrap_or(name).to_string())
            })
            .collect();
        structs.push((name.to_string(), members));
        if structs.len() == 2 {
            break;
        }
    }
    match <[_; 2]>::try_from(structs) {
        Ok([(layout_name, fields), (targets, target_members)])
            if fields.len() == layout.fields.len() && target_members.len() == layout.targets() =>
        {
            Ok(GlslNames {
                layout: layout_name,
                fields,
                targets,
                target_members,
            })
        }
        _ => Err(TranslationError(format!(
            "naga's GLSL for `{}` does not start with the texel and targets structs",
            layout.name
        ))),
    }
}

/// GLSL's float and integer types: the ones a precision qualifier applies to.
const PRECISION_TYPES: &[&str] = &[
    "float", "vec2", "vec3", "vec4", "int", "ivec2", "ivec3", "ivec4", "uint", "uvec2", "uvec3",
    "uvec4", "mat2", "mat3", "mat4",
];

const PRECISION_QUALIFIERS: &[&str] = &["highp", "mediump", "lowp"];

/// Prefixes `highp` to every type that starts a declaration (a type followed by a name, or by
/// `[N]` and a name): struct members, constants, parameters, return types and locals. A type
/// followed by `(` is a constructor or conversion and stays as it is.
pub fn with_explicit_precision(glsl: &str) -> String {
    let bytes = glsl.as_bytes();
    let mut out = String::with_capacity(glsl.len() + glsl.len() / 4);
    let mut previous_word = "";
    let mut index = 0;
    while index < bytes.len() {
        if !is_identifier_start(bytes[index]) {
            out.push(bytes[index] as char);
            index += 1;
            continue;
        }
        let start = index;
        while index < bytes.len() && is_identifier_part(bytes[index]) {
            index += 1;
        }
        let word = &glsl[start..index];
        if PRECISION_TYPES.contains(&word)
            && !PRECISION_QUALIFIERS.contains(&previous_word)
            && starts_declaration(&bytes[index..])
        {
            out.push_str("highp ");
        }
        out.push_str(word);
        previous_word = word;
    }
    out
}

/// Whether the text after a type names a declaration: optional `[digits]`, spaces, then an
/// identifier.
fn starts_declaration(rest: &[u8]) -> bool {
    let mut index = 0;
    if rest.first() == Some(&b'[') {
        while index < rest.len() && rest[index] != b']' {
            index += 1;
        }
        index += 1;
    }
    let spaces = rest[index.min(rest.len())..]
        .iter()
        .take_while(|byte| **byte == b' ')
        .count();
    spaces > 0
        && rest
            .get(index + spaces)
            .is_some_and(|byte| is_identifier_start(*byte))
}

fn is_identifier_start(byte: u8) -> bool {
    byte.is_ascii_alphabetic() || byte == b'_'
}

fn is_identifier_part(byte: u8) -> bool {
    byte.is_ascii_alphanumeric() || byte == b'_'
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn declarations_get_highp_and_constructors_do_not() {
        let glsl = "struct S {\n    vec3 a;\n    uint b[4];\n};\nconst uint N = 4u;\n\
                    uint[4] f(vec4 c, uint w[4]) {\n    uint x = uint(c.x);\n    return uint[4](x, 0u, 0u, 0u);\n}\n";
        assert_eq!(
            with_explicit_precision(glsl),
            "struct S {\n    highp vec3 a;\n    highp uint b[4];\n};\nconst highp uint N = 4u;\n\
             highp uint[4] f(highp vec4 c, highp uint w[4]) {\n    highp uint x = uint(c.x);\n    return uint[4](x, 0u, 0u, 0u);\n}\n"
        );
    }

    #[test]
    fn qualified_types_are_left_alone() {
        let glsl = "highp vec4 a; mediump float b;";
        assert_eq!(with_explicit_precision(glsl), glsl);
    }
}
