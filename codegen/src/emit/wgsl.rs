//! The WGSL emitter: a struct mirroring the layout, `pack_`/`unpack_`/`load_` functions, and
//! the helpers for a fragment shader that writes `Rgba32Uint` targets.
//!
//! Every conversion is done with integer operations on the float's bits. WGSL's
//! `pack2x16float` rounds in an implementation-defined way, a float multiply or fused
//! multiply-add moves values next to rounding midpoints, and builtins such as `pack4x8unorm`
//! and `extractBits` do not translate to every backend (GLSL ES 3.00 has neither), so the
//! generated code uses shifts, masks and comparisons only. Its CPU twin is [`crate::convert`].
//!
//! Helpers carry the layout's snake_case name as a prefix, so the WGSL of several layouts can
//! be concatenated into one module.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use crate::convert::max_code;
use crate::format::{Channel, ChannelEncoding, Format, ScalarKind};
use crate::layout::{Field, Layout};

/// How the WGSL converts values to and from channel codes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Conversions {
    /// Integer operations on the float's bits: the same words on every adapter as the Rust
    /// mirror, and portable to every backend.
    #[default]
    Exact,
    /// WGSL's builtins where a format has one (`pack4x8unorm` for rgba8, `pack2x16unorm` for
    /// rg16, `pack2x16float` for rg16f), f32 arithmetic for rgb10_a2, exact conversions
    /// elsewhere. Fewer instructions; the
    /// rounding (and for f16 the handling of values past 65504) is the adapter's, so a word
    /// can differ from the Rust mirror's by one code, and the builtins do not translate to
    /// GLSL ES 3.00 (WebGL2) everywhere. `tests/tests/gpu_packing.rs` measures the deviation.
    Fast,
}

impl Conversions {
    /// Whether a format's encode is the exact one under these conversions (fast conversions
    /// replace it for rgba8, rg16, rg16f and rgb10_a2).
    pub fn is_exact_for(self, format: Format) -> bool {
        self == Conversions::Exact
            || !(self.builtins(format).is_some() || format == Format::Rgb10A2)
    }

    /// The builtin pack and unpack functions for a format, under these conversions.
    pub fn builtins(self, format: Format) -> Option<(&'static str, &'static str)> {
        match (self, format) {
            (Conversions::Fast, Format::Rgba8) => Some(("pack4x8unorm", "unpack4x8unorm")),
            (Conversions::Fast, Format::Rg16) => Some(("pack2x16unorm", "unpack2x16unorm")),
            (Conversions::Fast, Format::Rg16f) => Some(("pack2x16float", "unpack2x16float")),
            _ => None,
        }
    }
}

/// The WGSL of a layout with exact conversions. The layout must have passed [`Layout::check`].
pub fn emit(layout: &Layout) -> String {
    emit_with(layout, Conversions::Exact)
}

/// The WGSL of a layout with the chosen conversions.
pub fn emit_with(layout: &Layout, conversions: Conversions) -> String {
    let prefix = layout.snake_name();
    let name = &layout.name;
    let words = layout.words();
    let words_type = format!("array<u32, {words}>");
    let mut out = String::new();

    write_header(&mut out, layout, conversions);

    let _ = writeln!(out, "struct {name} {{");
    for field in &layout.fields {
        let _ = writeln!(out, "    {}: {},", field.name, field.ty.wgsl());
    }
    out.push_str("}\n\n");

    let _ = writeln!(
        out,
        "// The number of 32-bit words in one texel of `{name}`."
    );
    let _ = writeln!(
        out,
        "const {}_WORDS: u32 = {words}u;\n",
        prefix.to_uppercase()
    );

    let guarantee = match conversions {
        Conversions::Exact => {
            "Exact conversions: the bits match the Rust mirror's on every adapter."
        }
        Conversions::Fast => {
            "Fast conversions: each channel within one code of the Rust mirror's on finite values."
        }
    };
    let _ = writeln!(out, "// Packs a texel. {guarantee}");
    let _ = writeln!(out, "fn pack_{prefix}(v: {name}) -> {words_type} {{");
    let _ = writeln!(out, "    return {words_type}(");
    for field in &layout.fields {
        let _ = writeln!(
            out,
            "        {}, // {}",
            encode_call(&prefix, field),
            field.name
        );
    }
    out.push_str("    );\n}\n\n");

    let _ = writeln!(out, "// Unpacks a texel.");
    let _ = writeln!(out, "fn unpack_{prefix}(w: {words_type}) -> {name} {{");
    let _ = writeln!(out, "    return {name}(");
    for (word, field) in layout.fields.iter().enumerate() {
        let _ = writeln!(
            out,
            "        {}, // {}",
            decode_expression(&prefix, field, word),
            field.name
        );
    }
    out.push_str("    );\n}\n\n");

    for (word, field) in layout.fields.iter().enumerate() {
        let _ = writeln!(out, "// Decodes `{}` alone, from word {word}.", field.name);
        let _ = writeln!(
            out,
            "fn load_{prefix}_{}(w: {words_type}) -> {} {{",
            field.name,
            field.ty.wgsl()
        );
        let _ = writeln!(
            out,
            "    return {};\n}}\n",
            decode_expression(&prefix, field, word)
        );
    }

    write_targets(&mut out, layout);
    write_format_helpers(&mut out, layout, conversions);
    write_conversion_helpers(&mut out, layout, conversions);
    // One trailing newline.
    while out.ends_with("\n\n") {
        out.pop();
    }
    out
}

fn write_header(out: &mut String, layout: &Layout, conversions: Conversions) {
    let _ = writeln!(
        out,
        "// G-buffer layout `{}`: {} words, {} bits ({} used) of a {}-bit budget.",
        layout.name,
        layout.words(),
        layout.bits(),
        layout.used_bits(),
        layout.budget
    );
    let _ = writeln!(
        out,
        "// Generated by gbuffer from the layout declaration: edit that, not this file."
    );
    let _ = writeln!(out, "// Word i holds field i; inside a word the channels sit from the least significant bit up.");
    if conversions == Conversions::Fast {
        let _ = writeln!(out, "// Fast conversions: rgba8, rg16 and rg16f use WGSL's pack builtins and rgb10_a2 f32 arithmetic,");
        let _ = writeln!(out, "// whose rounding is the adapter's (a word may differ from the Rust mirror's by one code); other formats are exact.");
    }
    let width = layout
        .fields
        .iter()
        .map(|field| field.name.len())
        .max()
        .unwrap_or(0);
    for (word, field) in layout.fields.iter().enumerate() {
        let channels = field.format.channels();
        let bit_map: Vec<String> = channels
            .iter()
            .enumerate()
            .map(|(index, channel)| {
                let range = format!(
                    "{} {}-{}",
                    channel.name,
                    channel.offset,
                    channel.offset + channel.bits - 1
                );
                if index < field.ty.components {
                    range
                } else {
                    format!("({range} padding)")
                }
            })
            .collect();
        let _ = writeln!(
            out,
            "//   word {word}: {:<width$}  {:<14} {}",
            field.name,
            field.format.name(),
            bit_map.join(", ")
        );
    }
    out.push('\n');
}

/// The member of `<Name>Targets` for target `target`: `first`, `second`, ... (names that
/// end in a digit are renamed by naga's GLSL and WGSL writers, which naga_oil refuses in a
/// composable module), and `target<t>_words` past the sixteenth.
pub fn target_member(target: usize) -> String {
    const ORDINALS: [&str; 16] = [
        "first",
        "second",
        "third",
        "fourth",
        "fifth",
        "sixth",
        "seventh",
        "eighth",
        "ninth",
        "tenth",
        "eleventh",
        "twelfth",
        "thirteenth",
        "fourteenth",
        "fifteenth",
        "sixteenth",
    ];
    ORDINALS
        .get(target)
        .map_or_else(|| format!("target{target}_words"), |name| name.to_string())
}

/// The fragment-output struct (one `vec4<u32>` per target of four words) and its converters.
fn write_targets(out: &mut String, layout: &Layout) {
    let prefix = layout.snake_name();
    let name = &layout.name;
    let words = layout.words();
    let targets = layout.targets();
    let _ = writeln!(
        out,
        "// The G-buffer pass's fragment output: one colour target per four words (Rgba32Uint, the"
    );
    let _ = writeln!(
        out,
        "// last as narrow as its words; words 4t to 4t + 3 in target t, past the end zero)."
    );
    let _ = writeln!(out, "struct {name}Targets {{");
    for target in 0..targets {
        let _ = writeln!(
            out,
            "    @location({target}) {}: vec4<u32>,",
            target_member(target)
        );
    }
    out.push_str("}\n\n");
    let word_or_zero = |index: usize| {
        if index < words {
            format!("w[{index}]")
        } else {
            "0u".to_string()
        }
    };
    let _ = writeln!(
        out,
        "fn pack_{prefix}_targets(v: {name}) -> {name}Targets {{"
    );
    let _ = writeln!(out, "    let w = pack_{prefix}(v);");
    let vectors: Vec<String> = (0..targets)
        .map(|target| {
            let lanes: Vec<String> = (4 * target..4 * target + 4).map(word_or_zero).collect();
            format!("vec4<u32>({})", lanes.join(", "))
        })
        .collect();
    let _ = writeln!(
        out,
        "    return {name}Targets({});\n}}\n",
        vectors.join(", ")
    );
    let _ = writeln!(out, "// Reassembles the words from the targets, e.g. `textureLoad` results of the lighting pass.");
    let _ = writeln!(
        out,
        "fn {prefix}_words_from_targets(t: {name}Targets) -> array<u32, {words}> {{"
    );
    let lanes: Vec<String> = (0..words)
        .map(|word| format!("t.{}[{}]", target_member(word / 4), word % 4))
        .collect();
    let _ = writeln!(
        out,
        "    return array<u32, {words}>({});\n}}\n",
        lanes.join(", ")
    );
    let _ = writeln!(
        out,
        "fn unpack_{prefix}_targets(t: {name}Targets) -> {name} {{"
    );
    let _ = writeln!(
        out,
        "    return unpack_{prefix}({prefix}_words_from_targets(t));\n}}\n"
    );
}

/// The WGSL vector (or scalar) type a format's helpers take: one component per channel.
fn format_vector_type(format: Format) -> String {
    let scalar = format.scalar_kind().wgsl();
    match format.channels().len() {
        1 => scalar.to_string(),
        n => format!("vec{n}<{scalar}>"),
    }
}

/// `prefix_encode_rgb10_a2_word(vec4<f32>(v.field, 0.0))`: the field widened with zeros to the
/// format's channel count, so padding channels encode as zero bits.
fn encode_call(prefix: &str, field: &Field) -> String {
    let channels = field.format.channels().len();
    let value = format!("v.{}", field.name);
    let widened = if field.ty.components == channels {
        value
    } else {
        let zero = match field.format.scalar_kind() {
            ScalarKind::Float => "0.0",
            ScalarKind::Uint => "0u",
            ScalarKind::Sint => "0",
        };
        let zeros = vec![zero; channels - field.ty.components].join(", ");
        format!("{}({value}, {zeros})", format_vector_type(field.format))
    };
    format!("{prefix}_encode_{}_word({widened})", field.format.name())
}

/// Decodes word `word` and narrows it to the field's components.
fn decode_expression(prefix: &str, field: &Field, word: usize) -> String {
    let call = format!("{prefix}_decode_{}_word(w[{word}])", field.format.name());
    if field.ty.components == field.format.channels().len() {
        call
    } else {
        format!("{call}.{}", &"xyzw"[..field.ty.components])
    }
}

fn component(format: Format, index: usize) -> String {
    if format.channels().len() == 1 {
        "c".to_string()
    } else {
        format!("c.{}", &"xyzw"[index..=index])
    }
}

/// One encode and one decode function per format the layout uses.
fn write_format_helpers(out: &mut String, layout: &Layout, conversions: Conversions) {
    let prefix = layout.snake_name();
    let formats: BTreeSet<Format> = layout.fields.iter().map(|field| field.format).collect();
    for format in formats {
        if let Some((pack, unpack)) = conversions.builtins(format) {
            let vector = format_vector_type(format);
            let name = format.name();
            let _ = writeln!(
                out,
                "// {name}: fast conversions, the adapter's `{pack}` and `{unpack}`."
            );
            let _ = writeln!(
                out,
                "fn {prefix}_encode_{name}_word(c: {vector}) -> u32 {{\n    return {pack}(c);\n}}\n"
            );
            let _ = writeln!(out, "fn {prefix}_decode_{name}_word(word: u32) -> {vector} {{\n    return {unpack}(word);\n}}\n");
            continue;
        }
        if format == Format::Rgb10A2 && !conversions.is_exact_for(format) {
            // No builtin packs it: f32 arithmetic rounds, the decode stays exact.
            out.push_str(&FAST_RGB10_A2.replace("PREFIX", &prefix));
            let _ = writeln!(
                out,
                "fn {prefix}_decode_rgb10_a2_word(word: u32) -> vec4<f32> {{\n    return vec4<f32>(\n        {},\n    );\n}}\n",
                format
                    .channels()
                    .iter()
                    .map(|channel| decode_channel(&prefix, *channel))
                    .collect::<Vec<_>>()
                    .join(",\n        ")
            );
            continue;
        }
        let vector = format_vector_type(format);
        let channels = format.channels();
        let layout_description: Vec<String> = channels
            .iter()
            .map(|channel| {
                format!(
                    "{} {}-{}",
                    channel.name,
                    channel.offset,
                    channel.offset + channel.bits - 1
                )
            })
            .collect();
        let _ = writeln!(
            out,
            "// {}: {}, {}.",
            format.name(),
            format.encoding_summary(),
            layout_description.join(", ")
        );
        let terms: Vec<String> = channels
            .iter()
            .enumerate()
            .map(|(index, channel)| {
                let code = encode_channel(&prefix, *channel, &component(format, index));
                if channel.offset == 0 {
                    code
                } else {
                    format!("({code} << {}u)", channel.offset)
                }
            })
            .collect();
        let _ = writeln!(
            out,
            "fn {prefix}_encode_{}_word(c: {vector}) -> u32 {{",
            format.name()
        );
        let _ = writeln!(out, "    return {};\n}}\n", terms.join("\n        | "));

        let decoded: Vec<String> = channels
            .iter()
            .map(|channel| decode_channel(&prefix, *channel))
            .collect();
        let _ = writeln!(
            out,
            "fn {prefix}_decode_{}_word(word: u32) -> {vector} {{",
            format.name()
        );
        if decoded.len() == 1 {
            let _ = writeln!(out, "    return {};\n}}\n", decoded[0]);
        } else {
            let _ = writeln!(
                out,
                "    return {vector}(\n        {},\n    );\n}}\n",
                decoded.join(",\n        ")
            );
        }
    }
}

/// The expression that encodes one channel value into its code (not yet shifted into place).
fn encode_channel(prefix: &str, channel: Channel, value: &str) -> String {
    let max = max_code(channel.bits);
    match channel.encoding {
        ChannelEncoding::Unorm => format!("{prefix}_f32_to_unorm({value}, {max}u)"),
        ChannelEncoding::Float32 => format!("bitcast<u32>({value})"),
        ChannelEncoding::Half => format!("{prefix}_f32_to_half({value})"),
        ChannelEncoding::UnsignedFloat { mantissa_bits } => {
            format!("{prefix}_f32_to_unsigned_float({value}, {mantissa_bits}u)")
        }
        ChannelEncoding::Uint if channel.bits == 32 => value.to_string(),
        ChannelEncoding::Uint => format!("min({value}, {max}u)"),
        ChannelEncoding::Sint => {
            let highest = max >> 1;
            format!(
                "(bitcast<u32>(clamp({value}, -{}, {highest})) & {max:#x}u)",
                highest + 1
            )
        }
    }
}

/// The expression that decodes one channel of `word`.
fn decode_channel(prefix: &str, channel: Channel) -> String {
    let code = match (channel.offset, channel.offset + channel.bits) {
        (0, 32) => "word".to_string(),
        (offset, 32) => format!("word >> {offset}u"),
        (0, _) => format!("word & {:#x}u", channel.mask()),
        (offset, _) => format!("(word >> {offset}u) & {:#x}u", channel.mask()),
    };
    match channel.encoding {
        // The reciprocal is correctly rounded; the product stays within 1 ulp of the exact
        // quotient and the largest code decodes to exactly 1.0.
        ChannelEncoding::Unorm => {
            format!("f32({code}) * {:?}", 1.0f32 / max_code(channel.bits) as f32)
        }
        ChannelEncoding::Float32 => format!("bitcast<f32>({code})"),
        ChannelEncoding::Half => format!("{prefix}_f32_from_half({code})"),
        ChannelEncoding::UnsignedFloat { mantissa_bits } => {
            format!("{prefix}_f32_from_small_float({code}, {mantissa_bits}u)")
        }
        ChannelEncoding::Uint => code,
        ChannelEncoding::Sint => {
            // Move the channel's top bit to bit 31, then shift back arithmetically.
            let up = 32 - channel.offset - channel.bits;
            let raised = if up == 0 {
                "word".to_string()
            } else {
                format!("word << {up}u")
            };
            format!("bitcast<i32>({raised}) >> {}u", 32 - channel.bits)
        }
    }
}

/// The scalar conversion helpers, each emitted only when a format of the layout needs it.
fn write_conversion_helpers(out: &mut String, layout: &Layout, conversions: Conversions) {
    let prefix = layout.snake_name();
    let encodings: Vec<ChannelEncoding> = layout
        .fields
        .iter()
        .filter(|field| conversions.is_exact_for(field.format))
        .flat_map(|field| {
            field
                .format
                .channels()
                .iter()
                .map(|channel| channel.encoding)
        })
        .collect();
    let uses = |wanted: fn(&ChannelEncoding) -> bool| encodings.iter().any(wanted);
    let uses_half = uses(|encoding| *encoding == ChannelEncoding::Half);
    let uses_unsigned_float =
        uses(|encoding| matches!(encoding, ChannelEncoding::UnsignedFloat { .. }));
    if uses(|encoding| *encoding == ChannelEncoding::Unorm) {
        out.push_str(&UNORM_FROM_F32.replace("PREFIX", &prefix));
    }
    if uses_half || uses_unsigned_float {
        out.push_str(&SMALL_FLOAT.replace("PREFIX", &prefix));
    }
    if uses_half {
        out.push_str(&HALF.replace("PREFIX", &prefix));
    }
    if uses_unsigned_float {
        out.push_str(&UNSIGNED_FLOAT.replace("PREFIX", &prefix));
    }
}

const FAST_RGB10_A2: &str = "\
// rgb10_a2: fast conversions. The codes are rounded in f32 arithmetic: one code from the exact
// ones at most, where the product lies within f32's rounding of a half-integer.
fn PREFIX_encode_rgb10_a2_word(c: vec4<f32>) -> u32 {
    let scale = vec4<f32>(1023.0, 1023.0, 1023.0, 3.0);
    let codes = vec4<u32>(clamp(c, vec4<f32>(0.0), vec4<f32>(1.0)) * scale + vec4<f32>(0.5));
    return codes.x | (codes.y << 10u) | (codes.z << 20u) | (codes.w << 30u);
}

";

const UNORM_FROM_F32: &str = "\
// Unsigned normalized encode: floor(0.5 + max_code * clamp(value, 0, 1)), exact. The value is
// significand * 2^-shift; the product with max_code (at most 16 bits) is formed in two 12-bit
// halves so every step fits a u32. NaN and negatives give 0; 1.0 and above give max_code.
// No branch: every case is computed and `select` keeps the one that applies, so the fragments
// of a tile never diverge on their data.
fn PREFIX_f32_to_unorm(value: f32, max_code: u32) -> u32 {
    let bits = bitcast<u32>(value);
    let exponent = bits >> 23u;
    let normal = exponent != 0u;
    let significand = (bits & 0x7fffffu) | select(0u, 0x800000u, normal);
    // Past a shift of 40 the product is under one half, as it is at 41: clamping keeps the
    // shift amounts below 32. Values of 1.0 and above wrap here; their result is not kept.
    let shift = min(select(149u, 150u - exponent, normal), 41u);
    let high = max_code * (significand >> 12u) + ((max_code * (significand & 0xfffu)) >> 12u);
    let rounded = (high + (1u << ((shift - 13u) & 31u))) >> ((shift - 12u) & 31u);
    // NaN, or the sign bit set, gives 0.
    return select(select(rounded, max_code, bits >= 0x3f800000u), 0u, bits > 0x7f800000u);
}

";

const SMALL_FLOAT: &str = "\
// Rounds a non-negative f32, given as its bits, to a float with a 5-bit exponent (bias 15) and
// mantissa_bits of mantissa: to nearest even, denormals kept, saturating at the largest finite
// code (never infinity). NaN gives 0. Integer operations and `select` only, so every adapter
// rounds alike and no fragment branches on its data.
fn PREFIX_small_float_from_magnitude(magnitude: u32, mantissa_bits: u32) -> u32 {
    let exponent = magnitude >> 23u;
    let normal_result = exponent >= 113u;
    let f32_denormal = exponent == 0u;
    let significand = select((magnitude & 0x7fffffu) | 0x800000u, magnitude, f32_denormal);
    // A denormal result drops 113 - exponent more bits; an f32 denormal 112 more.
    let extra = select(select(113u - exponent, 112u, f32_denormal), 0u, normal_result);
    // Past 24 the value is under half the smallest denormal, as it is at 25.
    let shift = min(23u - mantissa_bits + extra, 25u);
    let exponent_part = select(0u, (exponent - 113u) << mantissa_bits, normal_result);
    let kept = significand >> shift;
    let remainder = significand & ((1u << shift) - 1u);
    let halfway = 1u << (shift - 1u);
    // `&` and `|` rather than `&&` and `||`: both sides are evaluated, without a branch.
    let round_up = (remainder > halfway) | ((remainder == halfway) & ((kept & 1u) == 1u));
    let max_code = (30u << mantissa_bits) | ((1u << mantissa_bits) - 1u);
    let code = min(exponent_part + kept + u32(round_up), max_code);
    return select(code, 0u, magnitude > 0x7f800000u);
}

// Decodes an unsigned small float, exactly (a denormal is mantissa * 2^-(14 + mantissa_bits)).
fn PREFIX_f32_from_small_float(code: u32, mantissa_bits: u32) -> f32 {
    let exponent = code >> mantissa_bits;
    let mantissa = code & ((1u << mantissa_bits) - 1u);
    let denormal = f32(mantissa) * bitcast<f32>((113u - mantissa_bits) << 23u);
    let f32_exponent = select(exponent + 112u, 255u, exponent == 31u);
    let normal = bitcast<f32>((f32_exponent << 23u) | (mantissa << (23u - mantissa_bits)));
    return select(normal, denormal, exponent == 0u);
}

";

const HALF: &str = "\
// IEEE binary16 from f32, sign kept, saturating at +-65504; NaN gives 0.
fn PREFIX_f32_to_half(value: f32) -> u32 {
    let bits = bitcast<u32>(value);
    let magnitude = bits & 0x7fffffffu;
    let code = ((bits >> 16u) & 0x8000u) | PREFIX_small_float_from_magnitude(magnitude, 10u);
    return select(code, 0u, magnitude > 0x7f800000u);
}

fn PREFIX_f32_from_half(code: u32) -> f32 {
    let magnitude = PREFIX_f32_from_small_float(code & 0x7fffu, 10u);
    return bitcast<f32>(bitcast<u32>(magnitude) | ((code & 0x8000u) << 16u));
}

";

const UNSIGNED_FLOAT: &str = "\
// The unsigned floats of r11f_g11f_b10f (6 or 5 mantissa bits); negatives and NaN give 0.
fn PREFIX_f32_to_unsigned_float(value: f32, mantissa_bits: u32) -> u32 {
    let bits = bitcast<u32>(value);
    return select(PREFIX_small_float_from_magnitude(bits, mantissa_bits), 0u, bits >= 0x80000000u);
}

";
