//! The printer against exact text, and its names against naga's GLSL writer's.

use super::*;
use crate::items::ItemKind;
use crate::{glsl_stage, wgsl};

fn printed(wgsl: &str, from_310: &[FromVersion310]) -> String {
    let (module, info) = wgsl::validate(wgsl, wgsl::GENERATED_CODE_CAPABILITIES)
        .unwrap_or_else(|error| panic!("{error}"));
    let choice = Choice {
        from_310,
        ..Choice::default()
    };
    print(&module, &info, &choice).unwrap().text
}

#[test]
fn declarations_say_highp_and_values_used_twice_are_held() {
    let wgsl = "
struct Texel { colour: vec3<f32>, flags: u32, }
const WORDS: u32 = 2u;
fn brighter(c: vec3<f32>) -> vec3<f32> {
    let doubled = c * 2.0;
    return select(c, doubled, c < vec3(0.5));
}
fn pack(t: Texel) -> array<u32, 2> {
    let c = brighter(t.colour);
    let bits = bitcast<vec3<u32>>(c);
    return array<u32, 2>(bits.x ^ bits.y, t.flags % WORDS);
}
";
    let expected = "\
struct Texel {
    highp vec3 colour;
    highp uint flags;
};
const highp uint WORDS = 2u;

highp vec3 brighter(highp vec3 c) {
    highp vec3 doubled = (c * 2.0);
    return mix(c, doubled, lessThan(c, vec3(0.5)));
}

highp uint[2] pack(Texel t) {
    highp vec3 _e2 = brighter(t.colour);
    highp uvec3 bits = floatBitsToUint(_e2);
    return uint[2]((bits.x ^ bits.y), (t.flags % WORDS));
}
";
    assert_eq!(printed(wgsl, &[]), expected);
}

#[test]
fn a_wrapped_function_calls_the_builtin_from_310_and_is_translated_before() {
    let wgsl = "
fn encode(c: vec4<f32>) -> u32 {
    let codes = vec4<u32>(round(clamp(c, vec4(0.0), vec4(1.0)) * 255.0));
    return codes.x | (codes.y << 8u) | (codes.z << 16u) | (codes.w << 24u);
}
";
    let wrap = FromVersion310 {
        function: "encode",
        builtin: "packUnorm4x8",
    };
    let expected = "\
#if __VERSION__ >= 310
highp uint encode(highp vec4 c) {
    return packUnorm4x8(c);
}
#else
highp uint encode(highp vec4 c) {
    highp uvec4 codes = uvec4(roundEven((clamp(c, vec4(0.0), vec4(1.0)) * 255.0)));
    return (((codes.x | (codes.y << 8u)) | (codes.z << 16u)) | (codes.w << 24u));
}
#endif
";
    assert_eq!(printed(wgsl, &[wrap]), expected);
}

#[test]
fn an_entry_point_gets_what_it_reaches_less_what_is_left_out() {
    let wgsl = "
struct Texel { colour: vec3<f32>, }
@group(0) @binding(1) var lut: texture_2d<f32>;
@group(0) @binding(2) var lut_sampler: sampler;
@group(0) @binding(3) var unused: texture_2d<f32>;
fn from_include(t: Texel) -> vec3<f32> { return t.colour; }
fn looked_up(x: f32) -> f32 { return textureSampleLevel(lut, lut_sampler, vec2(x, 0.5), 0.0).x; }
fn lit(t: Texel) -> vec3<f32> { return from_include(t) * looked_up(t.colour.x); }
fn unreached() -> vec4<f32> { return textureSampleLevel(unused, lut_sampler, vec2(0.0), 0.0); }
@fragment
fn entry() -> @location(0) vec4<f32> { return vec4(lit(Texel(vec3(1.0))), 1.0); }
";
    let (module, info) = wgsl::validate(wgsl, wgsl::GENERATED_CODE_CAPABILITIES).unwrap();
    let choice = Choice {
        entry_point: Some((naga::ShaderStage::Fragment, "entry")),
        leave_out: &["Texel", "from_include"],
        from_310: &[],
        binding_qualifiers: true,
    };
    let printed = print(&module, &info, &choice).unwrap();
    let expected = "\
layout(binding = 1) uniform highp sampler2D _group_0_binding_1_fs;

highp float looked_up(highp float x) {
    highp vec4 _e6 = textureLod(_group_0_binding_1_fs, vec2(vec2(x, 0.5)), 0.0);
    return _e6.x;
}

highp vec3 lit(Texel t_1) {
    highp vec3 _e1 = from_include(t_1);
    highp float _e4 = looked_up(t_1.colour.x);
    return (_e1 * _e4);
}
";
    assert_eq!(printed.text, expected);
    let texts: Vec<&str> = printed
        .items
        .iter()
        .map(|item| item.text.as_str())
        .collect();
    assert_eq!(texts.join("\n"), expected, "each item's text, in order");
    let kinds: Vec<(ItemKind, &str)> = printed
        .items
        .iter()
        .map(|item| (item.kind, item.wgsl.as_deref().unwrap_or_default()))
        .collect();
    assert_eq!(
        kinds,
        [
            (ItemKind::Texture, "lut"),
            (ItemKind::Function, "looked_up"),
            (ItemKind::Function, "lit")
        ]
    );
    let webgl = Choice {
        binding_qualifiers: false,
        ..choice
    };
    let printed = print(&module, &info, &webgl).unwrap();
    assert!(printed
        .text
        .starts_with("uniform highp sampler2D _group_0_binding_1_fs;\n"));
}

/// GLSL ES 3.20's built-in functions (section 8), which neither keyword list of the test
/// holds by construction, and names naga changes for other reasons.
#[rustfmt::skip]
const BUILTINS_AND_ODD_NAMES: [&str; 64] = [
    "radians", "degrees", "sin", "cos", "tan", "asin", "acos", "atan", "pow", "exp", "log", "exp2",
    "log2", "sqrt", "inversesqrt", "abs", "sign", "floor", "trunc", "round", "roundEven", "ceil",
    "fract", "mod", "modf", "min", "max", "clamp", "mix", "step", "smoothstep", "isnan", "isinf",
    "floatBitsToUint", "uintBitsToFloat", "fma", "frexp", "ldexp", "packUnorm4x8",
    "unpackHalf2x16", "length", "distance", "dot", "cross", "normalize", "reflect", "refract",
    "transpose", "inverse", "lessThan", "equal", "any", "not", "bitfieldExtract", "findMSB",
    "texture", "textureLod", "texelFetch", "dFdx", "barrier", "main", "gl_thing", "a__b",
    "target0",
];

/// naga's GLSL writer is the reference: the renderer's and the user's shaders, which it
/// translates, call the includes' items by the names it gives. For every word the list
/// reserves that WGSL allows as a name, a struct member so named is printed with the name
/// naga's writer gives it.
#[test]
fn names_are_the_ones_nagas_writer_gives() {
    let mut words: Vec<&str> = GLSL_RESERVED
        .iter()
        .copied()
        .chain(BUILTINS_AND_ODD_NAMES)
        .filter(|word| gbuffer_core::naming::check_identifier(word).is_ok())
        .collect();
    words.sort();
    words.dedup();
    let members: String = words
        .iter()
        .map(|word| format!("    {word}: f32,\n"))
        .collect();
    let wgsl = format!(
        "struct Probe {{\n{members}}}\n\
             @fragment\nfn probe_entry() -> @location(0) vec4<f32> {{\n    \
             var p: Probe;\n    return vec4<f32>(p.{});\n}}\n",
        words[0]
    );
    let (module, info) = wgsl::validate(&wgsl, wgsl::GENERATED_CODE_CAPABILITIES).unwrap();
    let (naga_text, _) = glsl_stage::write(
        (&module, &info),
        naga::ShaderStage::Fragment,
        "probe_entry",
        glsl_stage::Dialect::WebGl,
    )
    .unwrap();
    let ours = print(&module, &info, &Choice::default()).unwrap();
    let (_, names) = ours.struct_names(&module, "Probe").unwrap();
    // naga writes the struct first, a member a line: `    float name;`.
    let nagas: Vec<&str> = naga_text
        .lines()
        .skip_while(|line| !line.starts_with("struct Probe"))
        .skip(1)
        .take(words.len())
        .map(|line| {
            line.trim()
                .trim_start_matches("float ")
                .trim_end_matches(';')
        })
        .collect();
    assert!(words.len() > 300, "{} words", words.len());
    for ((word, ours), nagas) in words.iter().zip(&names).zip(&nagas) {
        assert_eq!(ours, nagas, "`{word}`");
    }
}

#[test]
fn what_it_cannot_print_is_named() {
    let wgsl = "fn f(x: u32) -> u32 { return countLeadingZeros(x); }";
    let (module, info) = wgsl::validate(wgsl, wgsl::GENERATED_CODE_CAPABILITIES).unwrap();
    let error = print(&module, &info, &Choice::default()).unwrap_err();
    assert!(
        error.contains("CountLeadingZeros") && error.contains("`f`"),
        "{error}"
    );
}
