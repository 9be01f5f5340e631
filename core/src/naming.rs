//! Names: snake_case for generated functions, and the identifier rules every output language
//! (WGSL, GLSL ES, Rust) accepts.

/// `MobileMetallic` -> `mobile_metallic`, `HDRTarget` -> `hdr_target`, `Layout2D` -> `layout2_d`
/// is avoided: a digit run stays with the word before it (`Layout2D` -> `layout2d`).
pub fn snake_case(name: &str) -> String {
    let characters: Vec<char> = name.chars().collect();
    let mut snake = String::with_capacity(name.len() + 4);
    for (index, &character) in characters.iter().enumerate() {
        if character.is_ascii_uppercase() && index > 0 {
            let previous = characters[index - 1];
            let next_is_lower = characters
                .get(index + 1)
                .is_some_and(char::is_ascii_lowercase);
            let starts_word = previous.is_ascii_lowercase()
                || (previous.is_ascii_uppercase() && next_is_lower)
                || (previous.is_ascii_digit() && next_is_lower);
            if starts_word && !snake.ends_with('_') {
                snake.push('_');
            }
        }
        snake.push(character.to_ascii_lowercase());
    }
    snake
}

/// `parts` joined by `_` into one GLSL ES identifier: no part's own leading or trailing `_`
/// doubles one at a seam, since GLSL ES reserves every identifier containing `__` (and ANGLE
/// refuses them), and naga's names often end in `_` (`field_0_`).
pub fn glsl_identifier(parts: &[&str]) -> String {
    let parts: Vec<&str> = parts
        .iter()
        .map(|part| part.trim_matches('_'))
        .filter(|part| !part.is_empty())
        .collect();
    let mut joined = parts.join("_");
    while joined.contains("__") {
        joined = joined.replace("__", "_");
    }
    joined
}

/// The longest name a layout, field or scene may have, in characters. Generated names join a
/// layout's snake_case name, a field's and a suffix, and GLSL ES implementations need accept
/// identifiers of no more than 1024 characters (GLSL ES 3.20, section 3.7).
pub const MAX_IDENTIFIER_LENGTH: usize = 128;

/// Checks that `name` is an identifier every output accepts: ASCII letters, digits and
/// underscores, not starting with a digit or `__`, at most [`MAX_IDENTIFIER_LENGTH`]
/// characters, and none of WGSL's or Rust's keywords and reserved words ([`WGSL_RESERVED`],
/// [`RUST_RESERVED`]), which those emitters write as they are. GLSL's are accepted: every
/// GLSL output is naga's translation, and naga renames them (gbuffer-translate's printer, which
/// lists them, as naga does). The error completes the sentence "name `x` ...".
pub fn check_identifier(name: &str) -> Result<(), String> {
    let mut characters = name.chars();
    let Some(first) = characters.next() else {
        return Err("is empty".into());
    };
    if !(first.is_ascii_alphabetic() || first == '_')
        || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    {
        return Err(
            "must be an ASCII identifier (letters, digits, `_`; not starting with a digit)".into(),
        );
    }
    // ASCII: its length in bytes is its length in characters.
    if name.len() > MAX_IDENTIFIER_LENGTH {
        return Err(format!(
            "is {} characters long; names are limited to {MAX_IDENTIFIER_LENGTH}",
            name.len()
        ));
    }
    if name == "_" || name.starts_with("__") {
        return Err("is reserved in WGSL (`_` and names starting with `__`)".into());
    }
    for (language, reserved) in [("WGSL", WGSL_RESERVED), ("Rust", RUST_RESERVED)] {
        if reserved.binary_search(&name).is_ok() {
            return Err(format!(
                "is a {language} keyword or reserved word: rename it"
            ));
        }
    }
    Ok(())
}

/// Checks a layout's name: an identifier as [`check_identifier`] wants, which also names the
/// generated WGSL struct, so it must not shadow a WGSL predeclared type or builtin function
/// (the generated code calls them), and whose snake_case form prefixes GLSL globals, so it
/// must not start with `gl_`, which GLSL reserves. The error completes "name `x` ...".
pub fn check_layout_name(name: &str) -> Result<(), String> {
    check_identifier(name)?;
    if WGSL_PREDECLARED.binary_search(&name).is_ok() {
        return Err(format!(
            "is a WGSL predeclared type or builtin function (`{name}`), which the generated \
             struct would shadow: rename it"
        ));
    }
    let snake = snake_case(name);
    // The generated names join the snake name and a suffix with `_`: `__` inside it, or a
    // trailing `_`, puts `__` in every one, which GLSL reserves (naga's GLSL writer renames
    // such identifiers, and the includes' functions would not be found).
    if snake.contains("__") || snake.ends_with('_') {
        return Err(format!(
            "gives GLSL names containing `__` (`{snake}_target0`), which GLSL reserves: \
             rename it without a doubled or trailing `_`"
        ));
    }
    if snake == "gl" || snake.starts_with("gl_") {
        return Err(format!(
            "gives GLSL names starting with `gl_` (`{snake}_target0`), which GLSL reserves: \
             rename it"
        ));
    }
    Ok(())
}

/// WGSL's predeclared types, type generators and builtin functions (WGSL spec, sections 6 and
/// 17), sorted.
pub const WGSL_PREDECLARED: &[&str] = &[
    "abs",
    "acos",
    "acosh",
    "all",
    "any",
    "array",
    "arrayLength",
    "asin",
    "asinh",
    "atan",
    "atan2",
    "atanh",
    "atomic",
    "atomicAdd",
    "atomicAnd",
    "atomicCompareExchangeWeak",
    "atomicExchange",
    "atomicLoad",
    "atomicMax",
    "atomicMin",
    "atomicOr",
    "atomicStore",
    "atomicSub",
    "atomicXor",
    "bitcast",
    "bool",
    "ceil",
    "clamp",
    "cos",
    "cosh",
    "countLeadingZeros",
    "countOneBits",
    "countTrailingZeros",
    "cross",
    "degrees",
    "determinant",
    "distance",
    "dot",
    "dot4I8Packed",
    "dot4U8Packed",
    "dpdx",
    "dpdxCoarse",
    "dpdxFine",
    "dpdy",
    "dpdyCoarse",
    "dpdyFine",
    "exp",
    "exp2",
    "extractBits",
    "f16",
    "f32",
    "faceForward",
    "firstLeadingBit",
    "firstTrailingBit",
    "floor",
    "fma",
    "fract",
    "frexp",
    "fwidth",
    "fwidthCoarse",
    "fwidthFine",
    "i32",
    "insertBits",
    "inverseSqrt",
    "ldexp",
    "length",
    "log",
    "log2",
    "mat2x2",
    "mat2x2f",
    "mat2x2h",
    "mat2x3",
    "mat2x3f",
    "mat2x3h",
    "mat2x4",
    "mat2x4f",
    "mat2x4h",
    "mat3x2",
    "mat3x2f",
    "mat3x2h",
    "mat3x3",
    "mat3x3f",
    "mat3x3h",
    "mat3x4",
    "mat3x4f",
    "mat3x4h",
    "mat4x2",
    "mat4x2f",
    "mat4x2h",
    "mat4x3",
    "mat4x3f",
    "mat4x3h",
    "mat4x4",
    "mat4x4f",
    "mat4x4h",
    "max",
    "min",
    "mix",
    "modf",
    "normalize",
    "pack2x16float",
    "pack2x16snorm",
    "pack2x16unorm",
    "pack4x8snorm",
    "pack4x8unorm",
    "pack4xI8",
    "pack4xI8Clamp",
    "pack4xU8",
    "pack4xU8Clamp",
    "pow",
    "ptr",
    "quantizeToF16",
    "radians",
    "reflect",
    "refract",
    "reverseBits",
    "round",
    "sampler",
    "sampler_comparison",
    "saturate",
    "select",
    "sign",
    "sin",
    "sinh",
    "smoothstep",
    "sqrt",
    "step",
    "storageBarrier",
    "tan",
    "tanh",
    "textureBarrier",
    "textureDimensions",
    "textureGather",
    "textureGatherCompare",
    "textureLoad",
    "textureNumLayers",
    "textureNumLevels",
    "textureNumSamples",
    "textureSample",
    "textureSampleBaseClampToEdge",
    "textureSampleBias",
    "textureSampleCompare",
    "textureSampleCompareLevel",
    "textureSampleGrad",
    "textureSampleLevel",
    "textureStore",
    "texture_1d",
    "texture_2d",
    "texture_2d_array",
    "texture_3d",
    "texture_cube",
    "texture_cube_array",
    "texture_depth_2d",
    "texture_depth_2d_array",
    "texture_depth_cube",
    "texture_depth_cube_array",
    "texture_depth_multisampled_2d",
    "texture_external",
    "texture_multisampled_2d",
    "texture_storage_1d",
    "texture_storage_2d",
    "texture_storage_2d_array",
    "texture_storage_3d",
    "transpose",
    "trunc",
    "u32",
    "unpack2x16float",
    "unpack2x16snorm",
    "unpack2x16unorm",
    "unpack4x8snorm",
    "unpack4x8unorm",
    "unpack4xI8",
    "unpack4xU8",
    "vec2",
    "vec2f",
    "vec2h",
    "vec2i",
    "vec2u",
    "vec3",
    "vec3f",
    "vec3h",
    "vec3i",
    "vec3u",
    "vec4",
    "vec4f",
    "vec4h",
    "vec4i",
    "vec4u",
    "workgroupBarrier",
    "workgroupUniformLoad",
];

/// WGSL's keywords and reserved words (WGSL spec, sections 15.1 and 15.2), sorted.
pub const WGSL_RESERVED: &[&str] = &[
    "NULL",
    "Self",
    "abstract",
    "active",
    "alias",
    "alignas",
    "alignof",
    "as",
    "asm",
    "asm_fragment",
    "async",
    "attribute",
    "auto",
    "await",
    "become",
    "break",
    "case",
    "cast",
    "catch",
    "class",
    "co_await",
    "co_return",
    "co_yield",
    "coherent",
    "column_major",
    "common",
    "compile",
    "compile_fragment",
    "concept",
    "const",
    "const_assert",
    "const_cast",
    "consteval",
    "constexpr",
    "constinit",
    "continue",
    "continuing",
    "crate",
    "debugger",
    "decltype",
    "default",
    "delete",
    "demote",
    "demote_to_helper",
    "diagnostic",
    "discard",
    "do",
    "dynamic_cast",
    "else",
    "enable",
    "enum",
    "explicit",
    "export",
    "extends",
    "extern",
    "external",
    "fallthrough",
    "false",
    "filter",
    "final",
    "finally",
    "fn",
    "for",
    "friend",
    "from",
    "fxgroup",
    "get",
    "goto",
    "groupshared",
    "highp",
    "if",
    "impl",
    "implements",
    "import",
    "inline",
    "instanceof",
    "interface",
    "layout",
    "let",
    "loop",
    "lowp",
    "macro",
    "macro_rules",
    "match",
    "mediump",
    "meta",
    "mod",
    "module",
    "move",
    "mut",
    "mutable",
    "namespace",
    "new",
    "nil",
    "noexcept",
    "noinline",
    "nointerpolation",
    "non_coherent",
    "noncoherent",
    "noperspective",
    "null",
    "nullptr",
    "of",
    "operator",
    "override",
    "package",
    "packoffset",
    "partition",
    "pass",
    "patch",
    "pixelfragment",
    "precise",
    "precision",
    "premerge",
    "priv",
    "protected",
    "pub",
    "public",
    "readonly",
    "ref",
    "regardless",
    "register",
    "reinterpret_cast",
    "require",
    "requires",
    "resource",
    "restrict",
    "return",
    "self",
    "set",
    "shared",
    "sizeof",
    "smooth",
    "snorm",
    "static",
    "static_assert",
    "static_cast",
    "std",
    "struct",
    "subroutine",
    "super",
    "switch",
    "target",
    "template",
    "this",
    "thread_local",
    "throw",
    "trait",
    "true",
    "try",
    "type",
    "typedef",
    "typeid",
    "typename",
    "typeof",
    "union",
    "unless",
    "unorm",
    "unsafe",
    "unsized",
    "use",
    "using",
    "var",
    "varying",
    "virtual",
    "volatile",
    "wgsl",
    "where",
    "while",
    "with",
    "writeonly",
    "yield",
];

/// Rust's strict and reserved keywords (the Rust Reference, "Keywords", edition 2024), sorted;
/// `crate`, `self`, `super` and `Self` cannot even be raw identifiers.
pub const RUST_RESERVED: &[&str] = &[
    "Self", "abstract", "as", "async", "await", "become", "box", "break", "const", "continue",
    "crate", "do", "dyn", "else", "enum", "extern", "false", "final", "fn", "for", "gen", "if",
    "impl", "in", "let", "loop", "macro", "match", "mod", "move", "mut", "override", "priv", "pub",
    "ref", "return", "self", "static", "struct", "super", "trait", "true", "try", "type", "typeof",
    "unsafe", "unsized", "use", "virtual", "where", "while", "yield",
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snake_case_splits_words() {
        for (camel, snake) in [
            ("MobileMetallic", "mobile_metallic"),
            ("HDRTarget", "hdr_target"),
            ("Layout2D", "layout2d"),
            ("GBuffer", "g_buffer"),
            ("already_snake", "already_snake"),
            ("Listing2_1", "listing2_1"),
        ] {
            assert_eq!(snake_case(camel), snake);
        }
    }

    #[test]
    fn reserved_lists_are_sorted_for_binary_search() {
        assert!(WGSL_RESERVED.windows(2).all(|pair| pair[0] < pair[1]));
        assert!(WGSL_PREDECLARED.windows(2).all(|pair| pair[0] < pair[1]));
        assert!(RUST_RESERVED.windows(2).all(|pair| pair[0] < pair[1]));
    }

    #[test]
    fn layout_names() {
        assert!(check_layout_name("MobileMetallic").is_ok());
        assert!(check_layout_name("main").is_ok(), "GLSL renames it");
        assert!(check_layout_name("vec4").unwrap_err().contains("`vec4`"));
        for doubled in ["Spe__xcularWorkflow", "SpecularWorkflow_"] {
            let error = check_layout_name(doubled).unwrap_err();
            assert!(error.contains("`__`"), "{doubled}: {error}");
        }
        // `mobile_metallic`: a `_` before a capital is not doubled.
        assert!(check_layout_name("Mobile_Metallic").is_ok());
        assert!(check_layout_name("clamp").unwrap_err().contains("`clamp`"));
        assert!(check_layout_name("GlState")
            .unwrap_err()
            .contains("`gl_state_target0`"));
        assert!(check_layout_name("Glow").is_ok());
    }

    #[test]
    fn identifiers() {
        assert!(check_identifier("normals_roughness").is_ok());
        assert!(check_identifier("override").is_err());
        assert!(check_identifier("__hidden").is_err());
        assert!(check_identifier("2d").is_err());
        assert!(check_identifier("größe").is_err());
        // Rust's own keywords are refused; GLSL's are renamed by naga, so accepted.
        for name in ["in", "dyn", "box", "gen"] {
            assert!(
                check_identifier(name).unwrap_err().contains("Rust"),
                "{name}"
            );
        }
        // GLSL's reserved words and built-ins (gbuffer-translate's printer lists them all, and
        // the random layouts of the test suite name fields after them) and `__` inside a name.
        for name in ["sampler2D", "uvec4", "texture", "mix", "main", "a__b"] {
            assert!(check_identifier(name).is_ok(), "{name}");
        }
        assert!(check_identifier(&"n".repeat(MAX_IDENTIFIER_LENGTH)).is_ok());
        assert!(check_identifier(&"n".repeat(MAX_IDENTIFIER_LENGTH + 1))
            .unwrap_err()
            .contains("limited to 128"));
    }
}
