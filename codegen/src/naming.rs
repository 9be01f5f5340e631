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

/// Checks that `name` is an identifier every output accepts: ASCII letters, digits and
/// underscores, not starting with a digit or `__`, and not a WGSL keyword or reserved word.
/// The error completes the sentence "name `x` ...".
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
    if name == "_" || name.starts_with("__") {
        return Err("is reserved in WGSL (`_` and names starting with `__`)".into());
    }
    if WGSL_RESERVED.binary_search(&name).is_ok() {
        return Err("is a WGSL keyword or reserved word: rename it".into());
    }
    Ok(())
}

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
    fn reserved_list_is_sorted_for_binary_search() {
        assert!(WGSL_RESERVED.windows(2).all(|pair| pair[0] < pair[1]));
    }

    #[test]
    fn identifiers() {
        assert!(check_identifier("normals_roughness").is_ok());
        assert!(check_identifier("override").is_err());
        assert!(check_identifier("__hidden").is_err());
        assert!(check_identifier("2d").is_err());
        assert!(check_identifier("größe").is_err());
    }
}
