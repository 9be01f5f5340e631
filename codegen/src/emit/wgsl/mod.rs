//! The WGSL emitter: a struct mirroring the layout, `pack_`/`unpack_`/`load_` functions, and
//! the helpers for a fragment shader that writes `Rgba32Uint` targets.
//!
//! Exact conversions (the default) give every conforming adapter the Rust mirror's bits. They
//! use only steps whose result no adapter may choose: integer and bit operations on the
//! float's bits, comparisons, `min`, `round` of a value scaled by a power of two, and
//! `unpack2x16float` (binary16 to binary32 loses nothing). Float arithmetic is avoided: a GPU
//! compiler may reassociate it. WGSL's `pack2x16float` rounds in an implementation-defined
//! way and `pack4x8unorm` lets the adapter pick either neighbour, so exact conversions do not
//! use them. The channels of a word are converted together, one vector instruction for all of
//! them; nothing branches on the data, and no `select` works on integer vectors (GLSL ES 3.00
//! cannot translate it). Their CPU twin is [`crate::convert`]. Fast conversions
//! ([`Conversions::Fast`]) use the builtins and the engines' f32 idioms instead.
//!
//! Helpers carry the layout's snake_case name as a prefix, so the WGSL of several layouts can
//! be concatenated into one module.

mod bit_fields;

use std::collections::BTreeSet;
use std::fmt::Write as _;

use crate::convert::max_code;
use crate::format::{Channel, ChannelEncoding, Format, ScalarKind};
use crate::layout::{Field, Layout, Member, Storage};

pub use crate::layout::Conversions;

/// The WGSL of a layout with exact conversions. The layout must have passed [`Layout::check`].
pub fn emit(layout: &Layout) -> String {
    emit_with(layout, Conversions::Exact)
}

/// The WGSL of a layout with the chosen conversions.
pub fn emit_with(layout: &Layout, conversions: Conversions) -> String {
    emit_for(layout, conversions, Target::Wgsl)
}

/// Who reads the emitted WGSL.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Target {
    /// WGSL's users.
    Wgsl,
    /// naga's GLSL ES 3.00 writer, which has no `packUnorm4x8`: fast rgba8 is written in f32
    /// arithmetic, and the GLSL include puts the builtins back from GLSL ES 3.10 up.
    GlslEs300,
}

/// The WGSL of a layout with the chosen conversions, for `target`.
pub(crate) fn emit_for(layout: &Layout, conversions: Conversions, target: Target) -> String {
    let prefix = layout.snake_name();
    let name = &layout.name;
    let words = layout.words();
    let words_type = format!("array<u32, {words}>");
    let mut out = String::new();

    let fast_fields = fast_field_names(layout, conversions);
    let overridden = layout
        .fields
        .iter()
        .any(|field| !mode_suffix(field, conversions).is_empty());
    let fast = match (fast_fields.is_empty(), overridden) {
        (true, _) => None,
        (false, false) => Some(String::new()),
        (false, true) => Some(format!(" for {}", fast_fields.join(", "))),
    };

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

    let guarantee = if fast_fields.is_empty() {
        "Exact conversions: the bits match the Rust mirror's on every adapter.".to_string()
    } else if !overridden {
        "Fast conversions: each channel within one code of the Rust mirror's on finite values within f16's range.".to_string()
    } else {
        format!("Exact conversions but for {}, whose channels are within one code of the Rust mirror's on finite values within f16's range.", fast_fields.join(", "))
    };
    let _ = writeln!(out, "// Packs a texel. {guarantee}");
    let _ = writeln!(out, "fn pack_{prefix}(v: {name}) -> {words_type} {{");
    let _ = writeln!(out, "    return {words_type}(");
    for word in layout.word_contents() {
        let _ = writeln!(
            out,
            "        {}, // {}",
            encode_word(&prefix, layout, &word.members, conversions),
            layout.field_names(&word).join(", ")
        );
    }
    out.push_str("    );\n}\n\n");

    let locations = layout.field_locations();
    let _ = writeln!(out, "// Unpacks a texel.");
    let _ = writeln!(out, "fn unpack_{prefix}(w: {words_type}) -> {name} {{");
    let _ = writeln!(out, "    return {name}(");
    for (field, &(word, member)) in layout.fields.iter().zip(&locations) {
        let _ = writeln!(
            out,
            "        {}, // {}",
            decode_expression(&prefix, field, word, member, conversions),
            field.name
        );
    }
    out.push_str("    );\n}\n\n");

    for (field, &(word, member)) in layout.fields.iter().zip(&locations) {
        let place = match field.storage {
            Storage::Word(_) => format!("word {word}"),
            Storage::Bits(_) => format!("bits {} of word {word}", member.bit_range()),
        };
        let _ = writeln!(out, "// Decodes `{}` alone, from {place}.", field.name);
        let _ = writeln!(
            out,
            "fn load_{prefix}_{}(w: {words_type}) -> {} {{",
            field.name,
            field.ty.wgsl()
        );
        let _ = writeln!(
            out,
            "    return {};\n}}\n",
            decode_expression(&prefix, field, word, member, conversions)
        );
    }

    write_targets(&mut out, layout);
    write_format_helpers(&mut out, layout, conversions, target);
    write_bit_field_functions(&mut out, layout, conversions);
    write_conversion_helpers(&mut out, layout, conversions);
    // One trailing newline.
    while out.ends_with("\n\n") {
        out.pop();
    }
    // The header comes last, as it says what the code below it needs.
    let mut header = String::new();
    let half_floats = out.contains("pack2x16float(");
    write_header(&mut header, layout, fast.as_deref(), half_floats);
    header + &out
}

/// `fast` is None for exact conversions, or says which fields are fast (empty for all, or
/// " for a, b"); `half_floats` says whether the code uses `pack2x16float` or `unpack2x16float`,
/// which naga validates only with a capability `Capabilities::default()` leaves out
/// (`gbuffer_codegen::emit::glsl::naga_glsl::GENERATED_CODE_CAPABILITIES`).
fn write_header(out: &mut String, layout: &Layout, fast: Option<&str>, half_floats: bool) {
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
    if half_floats {
        let _ = writeln!(
            out,
            "// Its half floats use (un)pack2x16float: validating it with naga needs"
        );
        let _ = writeln!(out, "// Capabilities::SHADER_FLOAT16_IN_FLOAT32 (in wgpu, the SHADER_F16_IN_F32 downlevel flag).");
    }
    let _ = writeln!(out, "// Whole-word fields take a word each; bit fields share r32ui words from the least significant");
    let _ = writeln!(
        out,
        "// bit up; inside a word a format's channels sit from the least significant bit up."
    );
    if let Some(which) = fast {
        let _ = writeln!(out, "// Fast conversions{which}: rgba8, rg16 and rg16f use WGSL's pack builtins, rgb10_a2 f32");
        let _ = writeln!(out, "// arithmetic, r11f_g11f_b10f cut halves and unorm, half, octahedral and rgbm bit fields f32");
        let _ = writeln!(out, "// arithmetic, whose rounding is the adapter's (a code may differ from the Rust mirror's by one);");
        let _ = writeln!(out, "// the rest is exact.");
    }
    let width = layout
        .fields
        .iter()
        .map(|field| field.name.len())
        .max()
        .unwrap_or(0);
    for (index, word) in layout.word_contents().iter().enumerate() {
        if word.is_bit_fields {
            let _ = writeln!(out, "//   word {index}: r32ui bit fields");
            for member in &word.members {
                let field = &layout.fields[member.field];
                let _ = writeln!(
                    out,
                    "//     {:<width$}  bits {}, {}",
                    field.name,
                    member.bit_range(),
                    field.storage_name()
                );
            }
            continue;
        }
        let field = &layout.fields[word.members[0].field];
        let bit_map: Vec<String> = word
            .format
            .channels()
            .iter()
            .enumerate()
            .map(|(index, channel)| {
                let range = channel.bit_range();
                if index < field.ty.components {
                    range
                } else {
                    format!("({range} padding)")
                }
            })
            .collect();
        let _ = writeln!(
            out,
            "//   word {index}: {:<width$}  {:<14} {}",
            field.name,
            word.format.name(),
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

/// The expression of one packed word: a whole-word field's encode call, or its bit fields'
/// codes shifted into place and combined.
fn encode_word(
    prefix: &str,
    layout: &Layout,
    members: &[Member],
    conversions: Conversions,
) -> String {
    let parts: Vec<String> = members
        .iter()
        .map(|member| {
            let field = &layout.fields[member.field];
            match field.storage {
                Storage::Word(format) => encode_call(prefix, field, format, conversions),
                Storage::Bits(_) => {
                    let call = format!(
                        "{}(v.{})",
                        bit_fields::function_name(prefix, "encode", member.field),
                        field.name
                    );
                    match member.offset {
                        0 => call,
                        offset => format!("({call} << {offset}u)"),
                    }
                }
            }
        })
        .collect();
    parts.join(" | ")
}

/// `prefix_encode_rgb10_a2_word(vec4<f32>(v.field, 0.0))`: the field widened with zeros to the
/// format's channel count, so padding channels encode as zero bits.
fn encode_call(prefix: &str, field: &Field, format: Format, conversions: Conversions) -> String {
    let channels = format.channels().len();
    let value = format!("v.{}", field.name);
    let widened = if field.ty.components == channels {
        value
    } else {
        let zero = match format.scalar_kind() {
            ScalarKind::Float => "0.0",
            ScalarKind::Uint | ScalarKind::Bool => "0u",
            ScalarKind::Sint => "0",
        };
        let zeros = vec![zero; channels - field.ty.components].join(", ");
        format!("{}({value}, {zeros})", format_vector_type(format))
    };
    let function = function_name(prefix, "encode", format, mode_suffix(field, conversions));
    format!("{function}({widened})")
}

/// Decodes a field from word `word`: a whole word's channels narrowed to the field's
/// components, or a bit field's code taken out of its word.
fn decode_expression(
    prefix: &str,
    field: &Field,
    word: usize,
    member: Member,
    conversions: Conversions,
) -> String {
    let format = match field.storage {
        Storage::Word(format) => format,
        Storage::Bits(_) => {
            let shifted = match member.offset {
                0 => format!("w[{word}]"),
                offset => format!("(w[{word}] >> {offset}u)"),
            };
            let code = match member.bits {
                32 => shifted,
                bits => format!("{shifted} & {:#x}u", max_code(bits)),
            };
            return format!(
                "{}({code})",
                bit_fields::function_name(prefix, "decode", member.field)
            );
        }
    };
    let function = function_name(prefix, "decode", format, mode_suffix(field, conversions));
    let call = format!("{function}(w[{word}])");
    if field.ty.components == format.channels().len() {
        call
    } else {
        format!("{call}.{}", &"xyzw"[..field.ty.components])
    }
}

/// A field's conversions: its own, or the layout's.
fn mode(field: &Field, conversions: Conversions) -> Conversions {
    field.conversions.unwrap_or(conversions)
}

/// Whether a field's encode under these conversions is the exact one.
fn is_exact(field: &Field, conversions: Conversions) -> bool {
    let mode = mode(field, conversions);
    match field.storage {
        Storage::Word(format) => mode.is_exact_for(format),
        Storage::Bits(bit_field) => mode.is_exact_for_encoding(bit_field.encoding),
    }
}

/// The names of the fields whose encode is not the exact one.
fn fast_field_names(layout: &Layout, conversions: Conversions) -> Vec<&str> {
    layout
        .fields
        .iter()
        .filter(|field| !is_exact(field, conversions))
        .map(|field| field.name.as_str())
        .collect()
}

/// What a format's functions add to their names for a field whose conversions differ from
/// the layout's: `_fast` or `_exact` (nothing otherwise).
fn mode_suffix(field: &Field, conversions: Conversions) -> &'static str {
    match field.conversions {
        Some(own) if own != conversions => own.name_suffix(),
        _ => "",
    }
}

/// `<prefix>_<verb>_field_<index>_bits`, e.g. `bevy_like_decode_field_6_bits`: the encode
/// (value to code) or decode (code to value) of bit field `index`.
pub fn bit_field_function_name(prefix: &str, verb: &str, index: usize) -> String {
    bit_fields::function_name(prefix, verb, index)
}

/// `<prefix>_<verb>_<format><suffix>_word`, e.g. `mobile_metallic_encode_rgba8_word`.
pub(crate) fn function_name(prefix: &str, verb: &str, format: Format, suffix: &str) -> String {
    format!("{prefix}_{verb}_{}{suffix}_word", format.name())
}

/// The lanes a format's helpers work on: a scalar for one channel, a vector for several, so
/// that one instruction converts every channel of a word.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Lanes(usize);

impl Lanes {
    /// The lane count's name in helper names: `f32`, `f32x2`, `f32x3`, `f32x4` (no helper name
    /// may end in a digit, which naga_oil refuses).
    fn name(self) -> String {
        match self.0 {
            1 => "f32".to_string(),
            n => format!("f32x{n}"),
        }
    }

    /// The WGSL type with `scalar` in every lane.
    fn of(self, scalar: &str) -> String {
        match self.0 {
            1 => scalar.to_string(),
            n => format!("vec{n}<{scalar}>"),
        }
    }

    /// A literal with one value per lane, e.g. `vec4<u32>(0u, 8u, 16u, 24u)`; a splat when the
    /// values agree.
    fn literal(self, scalar: &str, values: &[String]) -> String {
        if self.0 == 1 {
            values[0].clone()
        } else if values.iter().all(|value| *value == values[0]) {
            format!("{}({})", self.of(scalar), values[0])
        } else {
            format!("{}({})", self.of(scalar), values.join(", "))
        }
    }

    /// `template` with its placeholders filled for these lanes.
    fn fill(self, template: &str, prefix: &str) -> String {
        template
            .replace("PREFIX", prefix)
            .replace("LANES", &self.name())
            .replace("SINTS", &self.of("i32"))
            .replace("FLOATS", &self.of("f32"))
            .replace("UINTS", &self.of("u32"))
    }
}

/// A literal with one `u32` per channel of `format`.
fn per_channel(format: Format, value: impl Fn(&Channel) -> u32) -> String {
    channel_literal(format, "u32", |channel| format!("{}u", value(channel)))
}

/// A literal of `scalar`s, one per channel of `format`, each written by `write`.
fn channel_literal(format: Format, scalar: &str, write: impl Fn(&Channel) -> String) -> String {
    let values: Vec<String> = format.channels().iter().map(write).collect();
    Lanes(values.len()).literal(scalar, &values)
}

/// One encode and one decode function per format the layout uses.
fn write_format_helpers(
    out: &mut String,
    layout: &Layout,
    conversions: Conversions,
    target: Target,
) {
    let prefix = layout.snake_name();
    // Each format once per name suffix, with the conversions the suffix stands for.
    let functions: BTreeSet<(Format, &str, Conversions)> = layout
        .fields
        .iter()
        .filter_map(|field| {
            Some((
                field.format()?,
                mode_suffix(field, conversions),
                mode(field, conversions),
            ))
        })
        .collect();
    for (format, suffix, conversions) in functions {
        let name = format.name();
        let vector = format_vector_type(format);
        let encode = function_name(&prefix, "encode", format, suffix);
        let decode = function_name(&prefix, "decode", format, suffix);
        let builtins = conversions
            .builtins(format)
            .filter(|_| !(target == Target::GlslEs300 && format == Format::Rgba8));
        if let Some((pack, unpack)) = builtins {
            let _ = writeln!(
                out,
                "// {name}: fast conversions, the adapter's `{pack}` and `{unpack}`."
            );
            let _ = writeln!(
                out,
                "fn {encode}(c: {vector}) -> u32 {{\n    return {pack}(c);\n}}\n"
            );
            let _ = writeln!(
                out,
                "fn {decode}(word: u32) -> {vector} {{\n    return {unpack}(word);\n}}\n"
            );
            continue;
        }
        let channels = format.channels();
        let layout_description: Vec<String> =
            channels.iter().map(|channel| channel.bit_range()).collect();
        let _ = writeln!(
            out,
            "// {name}: {}, {}.",
            format.encoding_summary(),
            layout_description.join(", ")
        );
        let template = match (conversions.is_exact_for(format), format) {
            (false, Format::Rgb10A2) => Some(FAST_RGB10_A2),
            (false, Format::Rgba8) => Some(FAST_RGBA8_ARITHMETIC),
            (false, Format::R11fG11fB10f) => Some(FAST_R11F_G11F_B10F),
            _ => None,
        };
        match template {
            Some(template) => out.push_str(&template.replace("ENCODE", &encode)),
            None => {
                let _ = writeln!(
                    out,
                    "fn {encode}(c: {vector}) -> u32 {{\n{}}}\n",
                    encode_body(&prefix, format)
                );
            }
        }
        let _ = writeln!(
            out,
            "fn {decode}(word: u32) -> {vector} {{\n{}}}\n",
            decode_body(format)
        );
    }
}

/// The exact encode of a word: every channel's code at once, then the codes shifted into
/// place and combined.
fn encode_body(prefix: &str, format: Format) -> String {
    let channels = format.channels();
    let lanes = Lanes(channels.len());
    let first = channels[0];
    let codes = match first.encoding {
        ChannelEncoding::Float32 => "bitcast<u32>(c)".to_string(),
        ChannelEncoding::Uint if first.bits == 32 => "c".to_string(),
        ChannelEncoding::Uint => format!("min(c, {})", per_channel(format, |c| max_code(c.bits))),
        ChannelEncoding::Sint => {
            let bound = |value: i64| {
                Lanes(channels.len()).literal("i32", &vec![value.to_string(); channels.len()])
            };
            let highest = i64::from(max_code(first.bits) >> 1);
            format!(
                "({}(clamp(c, {}, {})) & {})",
                if channels.len() == 1 {
                    "bitcast<u32>".to_string()
                } else {
                    format!("bitcast<{}>", lanes.of("u32"))
                },
                bound(-highest - 1),
                bound(highest),
                per_channel(format, |c| c.mask())
            )
        }
        ChannelEncoding::Unorm => format!(
            "{prefix}_{}_to_unorm(c, {}, {}, {})",
            lanes.name(),
            per_channel(format, |c| c.bits),
            per_channel(format, |c| max_code(c.bits)),
            per_channel(format, |c| 150 - c.bits)
        ),
        ChannelEncoding::Half => format!("{prefix}_{}_to_half(c)", lanes.name()),
        ChannelEncoding::UnsignedFloat { .. } => {
            format!("{prefix}_{}_to_unsigned_float(c)", lanes.name())
        }
    };
    if channels.len() == 1 {
        return format!("    return {codes};\n");
    }
    let combined: Vec<String> = "xyzw"[..channels.len()]
        .chars()
        .map(|lane| format!("placed.{lane}"))
        .collect();
    format!(
        "    let placed = {codes} << {};\n    return {};\n",
        per_channel(format, |c| c.offset),
        combined.join(" | ")
    )
}

/// The exact decode of a word: every channel's code moved to its own lane, then converted.
fn decode_body(format: Format) -> String {
    let channels = format.channels();
    let lanes = Lanes(channels.len());
    let codes = format!(
        "({}(word) >> {}) & {}",
        lanes.of("u32"),
        per_channel(format, |c| c.offset),
        per_channel(format, |c| c.mask())
    );
    let value = match channels[0].encoding {
        ChannelEncoding::Float32 => "bitcast<f32>(word)".to_string(),
        ChannelEncoding::Uint if channels.len() == 1 => "word".to_string(),
        ChannelEncoding::Uint => codes,
        // Move each channel's top bit to bit 31, then shift back arithmetically.
        ChannelEncoding::Sint => format!(
            "bitcast<{}>({}(word) << {}) >> {}",
            lanes.of("i32"),
            lanes.of("u32"),
            per_channel(format, |c| 32 - c.offset - c.bits),
            per_channel(format, |c| 32 - c.bits)
        ),
        // The reciprocal is correctly rounded; the product stays within 1 ulp of the exact
        // quotient and the largest code decodes to exactly 1.0.
        ChannelEncoding::Unorm => {
            let reciprocals: Vec<String> = channels
                .iter()
                .map(|c| format!("{:?}", 1.0f32 / max_code(c.bits) as f32))
                .collect();
            return format!(
                "    let codes = {codes};\n    return {}(codes) * {};\n",
                lanes.of("f32"),
                lanes.literal("f32", &reciprocals)
            );
        }
        // Every binary16 value is a binary32 value, and `unpack2x16float` is defined as that
        // conversion: exact, on an adapter that keeps half denormals as WGSL asks.
        ChannelEncoding::Half => "unpack2x16float(word)".to_string(),
        // The codes are halves without their sign and low mantissa bits: widened back into
        // halves, they decode exactly as rg16f does.
        ChannelEncoding::UnsignedFloat { .. } => {
            return "    let red_green = unpack2x16float(((word & 0x7ffu) << 4u) | ((word & 0x3ff800u) << 9u));\n    \
                    return vec3<f32>(red_green, unpack2x16float((word >> 17u) & 0x7fe0u).x);\n"
                .to_string()
        }
    };
    format!("    return {value};\n")
}

/// The mantissa bits of a small-float channel (half or unsigned float).
fn mantissa_bits(channel: &Channel) -> u32 {
    match channel.encoding {
        ChannelEncoding::UnsignedFloat { mantissa_bits } => mantissa_bits,
        _ => 10,
    }
}

/// The bit fields' encode and decode functions and the helpers they call, alone (no struct,
/// no pack or unpack): what a pixel local storage include adds beside its block.
#[cfg(feature = "tools")]
pub(crate) fn bit_field_functions(layout: &Layout, conversions: Conversions) -> String {
    let prefix = layout.snake_name();
    let mut out = String::new();
    write_bit_field_functions(&mut out, layout, conversions);
    let mut written = BTreeSet::new();
    for field in &layout.fields {
        if let Storage::Bits(bit_field) = field.storage {
            for helper in bit_fields::helpers(&prefix, field, bit_field, mode(field, conversions)) {
                if written.insert(helper.clone()) {
                    out.push_str(&helper);
                }
            }
        }
    }
    out
}

/// Each bit field's encode and decode functions.
fn write_bit_field_functions(out: &mut String, layout: &Layout, conversions: Conversions) {
    let prefix = layout.snake_name();
    for (index, field) in layout.fields.iter().enumerate() {
        if let Storage::Bits(bit_field) = field.storage {
            out.push_str(&bit_fields::functions(
                &prefix,
                index,
                field,
                bit_field,
                mode(field, conversions),
            ));
        }
    }
}

/// The conversion helpers of the layout's exact formats (unorm's per lane count, the small
/// floats' with their format's constants written out) and of its bit fields, each once.
fn write_conversion_helpers(out: &mut String, layout: &Layout, conversions: Conversions) {
    let prefix = layout.snake_name();
    let exact: BTreeSet<Format> = layout
        .fields
        .iter()
        .filter(|field| is_exact(field, conversions))
        .filter_map(Field::format)
        .collect();
    let mut helpers: Vec<String> = exact
        .iter()
        .filter(|format| format.channels()[0].encoding == ChannelEncoding::Unorm)
        .map(|format| Lanes(format.channels().len()))
        .collect::<BTreeSet<Lanes>>()
        .into_iter()
        .map(|lanes| lanes.fill(UNORM_FROM_F32, &prefix))
        .collect();
    for format in exact {
        let (name, wrapper) = match format.channels()[0].encoding {
            ChannelEncoding::Half => ("unsigned_half", HALF),
            ChannelEncoding::UnsignedFloat { .. } => ("unsigned_float", UNSIGNED_FLOAT),
            _ => continue,
        };
        let mantissas: Vec<u32> = format.channels().iter().map(mantissa_bits).collect();
        helpers.extend(small_float_helpers(&prefix, name, wrapper, &mantissas));
    }
    for field in &layout.fields {
        if let Storage::Bits(bit_field) = field.storage {
            helpers.extend(bit_fields::helpers(
                &prefix,
                field,
                bit_field,
                mode(field, conversions),
            ));
        }
    }
    let mut written = BTreeSet::new();
    for helper in helpers {
        if written.insert(helper.clone()) {
            out.push_str(&helper);
        }
    }
}

/// The helpers that round f32s to small floats of the given mantissa widths (one lane each)
/// and `wrapper`, which calls them, with their constants written out.
fn small_float_helpers(prefix: &str, name: &str, wrapper: &str, mantissas: &[u32]) -> Vec<String> {
    let lanes = Lanes(mantissas.len());
    let literal = |scalar: &str, write: &dyn Fn(u32) -> String| {
        let values: Vec<String> = mantissas.iter().map(|&bits| write(bits)).collect();
        lanes.literal(scalar, &values)
    };
    let distinct: BTreeSet<u32> = mantissas.iter().copied().collect();
    let distinct: Vec<String> = distinct.iter().map(u32::to_string).collect();
    let constants = [
        ("MANTISSA_BITS", distinct.join(" or ")),
        (
            "ROUNDING_AND_REBIAS",
            literal("u32", &|bits| {
                let shift = 23 - bits;
                format!(
                    "{:#x}u",
                    ((1u32 << (shift - 1)) - 1).wrapping_sub(113 << 23)
                )
            }),
        ),
        ("SHIFT", literal("u32", &|bits| format!("{}u", 23 - bits))),
        (
            "DENORMAL_SCALE",
            literal("f32", &|bits| format!("{:?}", ((14 + bits) as f32).exp2())),
        ),
        (
            "MAX_CODE",
            literal("u32", &|bits| format!("{}u", (31 << bits) - 1)),
        ),
        (
            "SMALLEST_NORMAL",
            literal("u32", &|bits| format!("{}u", 1 << bits)),
        ),
        ("NAME", name.to_string()),
    ];
    [SMALL_FLOAT_FROM_MAGNITUDE, wrapper]
        .iter()
        .map(|template| {
            let mut helper = lanes.fill(template, prefix);
            for (placeholder, value) in &constants {
                helper = helper.replace(placeholder, value);
            }
            helper
        })
        .collect()
}

const FAST_RGB10_A2: &str = "\
// Fast conversions: the codes are rounded in f32 arithmetic, one code from the exact ones at
// most (where the product lies within f32's rounding of a half-integer); the decode is exact.
fn ENCODE(c: vec4<f32>) -> u32 {
    let scale = vec4<f32>(1023.0, 1023.0, 1023.0, 3.0);
    let codes = vec4<u32>(clamp(c, vec4<f32>(0.0), vec4<f32>(1.0)) * scale + vec4<f32>(0.5));
    return codes.x | (codes.y << 10u) | (codes.z << 20u) | (codes.w << 30u);
}

";

const FAST_RGBA8_ARITHMETIC: &str = "\
// Fast conversions for GLSL ES 3.00, which has no packUnorm4x8: rounded in f32 arithmetic like
// the builtin (one code from the exact ones at most); the decode is the exact one.
fn ENCODE(c: vec4<f32>) -> u32 {
    let codes = vec4<u32>(clamp(c, vec4<f32>(0.0), vec4<f32>(1.0)) * 255.0 + vec4<f32>(0.5));
    let placed = codes << vec4<u32>(0u, 8u, 16u, 24u);
    return placed.x | placed.y | placed.z | placed.w;
}

";

const FAST_R11F_G11F_B10F: &str = "\
// Fast conversions, the engines' idiom: the adapter converts to half floats with
// `pack2x16float`, whose mantissas are cut to 6 and 5 bits (one code under the exact rounding
// at most; the adapter may flush values under 2^-14 to zero and turn values past 65504 into
// infinity). The decode is the exact one.
fn ENCODE(c: vec3<f32>) -> u32 {
    let positive = max(c, vec3<f32>(0.0));
    let red_green = pack2x16float(positive.xy);
    let blue = pack2x16float(vec2<f32>(positive.z, 0.0));
    return ((red_green >> 4u) & 0x7ffu) | ((red_green >> 9u) & 0x3ff800u) | ((blue & 0x7fe0u) << 17u);
}

";

const UNORM_FROM_F32: &str = "\
// Unsigned normalized encode, per lane: floor(0.5 + max_code * clamp(value, 0, 1)), exact, in
// integer arithmetic on the float's bits (a GPU compiler may reassociate float arithmetic, so
// exactness cannot rest on it). With value = significand * 2^-(shift + bits) and max_code =
// 2^bits - 1, the code is (significand - significand / 2^bits + 2^(shift - 1)) >> shift, and
// rounding significand / 2^bits up changes no result. NaN and negatives give 0 (as unsigned
// integers their bits lie above infinity's), values from 1.0 up give max_code; past a shift of
// 26 every code is 0, as it is at 26. No branch, so the fragments of a tile never diverge, and
// no `select` on integer vectors, which GLSL ES 3.00 cannot express (a multiply by 0 or 1).
// shift_bias is 150 - bits (passed in: an optimiser does not fold vector constants).
fn PREFIX_LANES_to_unorm(value: FLOATS, bits: UINTS, max_code: UINTS, shift_bias: UINTS) -> UINTS {
    let value_bits = bitcast<UINTS>(value);
    let clamped = min(value_bits, UINTS(0x3f800000u)) * UINTS(value_bits <= UINTS(0x7f800000u));
    let significand = (clamped & UINTS(0x7fffffu)) | UINTS(0x800000u);
    let shift = min(shift_bias - (clamped >> UINTS(23u)), UINTS(26u));
    let scaled = significand - ((significand + max_code) >> bits);
    return (scaled + ((UINTS(1u) << shift) >> UINTS(1u))) >> shift;
}

";

const SNORM_FROM_F32: &str = "\
// Signed normalized encode, per lane: GL's round(clamp(value, -1, 1) * (2^(bits - 1) - 1)),
// halves away from zero, exact: the magnitude's unorm code at bits - 1 bits (NaN's is 0),
// negated in the bits-bit two's complement for a set sign bit (a multiply-free negation, as
// GLSL ES 3.00 has no `select` on integer vectors). magnitude_* are to_unorm's parameters
// at bits - 1 bits; mask is 2^bits - 1.
fn PREFIX_LANES_to_snorm(value: FLOATS, magnitude_bits: UINTS, magnitude_max: UINTS, shift_bias: UINTS, mask: UINTS) -> UINTS {
    let value_bits = bitcast<UINTS>(value);
    let magnitude = bitcast<FLOATS>(value_bits & UINTS(0x7fffffffu));
    let code = PREFIX_LANES_to_unorm(magnitude, magnitude_bits, magnitude_max, shift_bias);
    let negative = value_bits >> UINTS(31u);
    return ((code ^ (UINTS(0u) - negative)) + negative) & mask;
}

// Signed normalized decode: max(code / (2^(bits - 1) - 1), -1), the code sign-extended by
// moving its top bit to bit 31 and shifting back arithmetically (up is 32 - bits).
fn PREFIX_LANES_from_snorm(code: UINTS, up: UINTS, reciprocal: FLOATS) -> FLOATS {
    let signed = bitcast<SINTS>(code << up) >> up;
    return max(FLOATS(signed) * reciprocal, FLOATS(-1.0));
}

";

const RGB9E5_MANTISSA: &str = "\
// floor(value * 2^(24 - exponent) + 0.5) for non-negative f32 bits; past a shift of 25 the
// result is 0, as it is at 25 (the shift is never negative: no channel exceeds the largest).
fn PREFIX_LANES_rgb9e5_mantissa(bits: UINTS, exponent: UINTS) -> UINTS {
    let significand = (bits & UINTS(0x7fffffu)) | UINTS(0x800000u);
    let shift = min(UINTS(126u) + exponent - (bits >> UINTS(23u)), UINTS(25u));
    return (significand + ((UINTS(1u) << shift) >> UINTS(1u))) >> shift;
}

";

const RGB9E5: &str = "\
// Shared-exponent rgb9e5 (EXT_texture_shared_exponent), its algorithm evaluated exactly: the
// channels clamped to [0, 65408] (NaN to 0; as unsigned integers, NaN and negatives lie above
// infinity's bits), the exponent max(-16, floor(log2(largest))) + 16 read from the exponent
// field, one more where the largest channel's mantissa rounds up to 512, and each mantissa
// floor(channel / 2^(exponent - 24) + 0.5) by shifting the significand with half its last
// place added. Red in bits 0-8, green 9-17, blue 18-26, the exponent 27-31.
fn PREFIX_f32x3_to_rgb9e5(value: vec3<f32>) -> u32 {
    let bits = bitcast<vec3<u32>>(value);
    let clamped = min(bits, vec3<u32>(0x477f8000u)) * vec3<u32>(bits <= vec3<u32>(0x7f800000u));
    let largest = max(clamped.x, max(clamped.y, clamped.z));
    let rough_exponent = max(largest >> 23u, 111u) - 111u;
    let exponent = rough_exponent + u32(PREFIX_f32_rgb9e5_mantissa(largest, rough_exponent) == 512u);
    let mantissas = PREFIX_f32x3_rgb9e5_mantissa(clamped, vec3<u32>(exponent)) << vec3<u32>(0u, 9u, 18u);
    return mantissas.x | mantissas.y | mantissas.z | (exponent << 27u);
}

// Decodes rgb9e5, exactly: each mantissa times 2^(exponent - 24).
fn PREFIX_f32x3_from_rgb9e5(word: u32) -> vec3<f32> {
    let scale = bitcast<f32>(((word >> 27u) + 103u) << 23u);
    return vec3<f32>((vec3<u32>(word) >> vec3<u32>(0u, 9u, 18u)) & vec3<u32>(0x1ffu)) * scale;
}

";

/// Rounds non-negative f32s (bits) to small floats; the placeholders are per-lane literals.
const SMALL_FLOAT_FROM_MAGNITUDE: &str = "\
// Rounds non-negative f32s, given as bits, to floats with a 5-bit exponent (bias 15) and
// MANTISSA_BITS bits of mantissa: to nearest even, denormals kept, saturating at the largest finite
// code (never infinity); the caller maps NaN. Normal results round the f32 bits in integer
// arithmetic, rebiasing the exponent in the same add (a carry moves into the exponent, as it
// should). Denormal results scale the value by a power of two, exactly, and `round` it (to
// nearest even). No step depends on how the adapter rounds. Each path gives at least the code
// where the other applies (under 2^-14 the rebias wraps around; from 2^-14 up the scaled value
// is at least the code, saturating in the conversion), so `min` picks the right one.
fn PREFIX_LANES_round_to_NAME(magnitude: UINTS) -> UINTS {
    let odd = (magnitude >> SHIFT) & UINTS(1u);
    let normal = ((magnitude + ROUNDING_AND_REBIAS + odd) >> SHIFT) + SMALLEST_NORMAL;
    let denormal = UINTS(round(bitcast<FLOATS>(magnitude) * DENORMAL_SCALE));
    return min(min(normal, denormal), MAX_CODE);
}

";

const HALF: &str = "\
// IEEE binary16 from f32, sign kept, saturating at +-65504; NaN gives 0.
fn PREFIX_LANES_to_half(value: FLOATS) -> UINTS {
    let bits = bitcast<UINTS>(value);
    let magnitude = bits & UINTS(0x7fffffffu);
    let signed = PREFIX_LANES_round_to_unsigned_half(magnitude) | ((bits >> UINTS(16u)) & UINTS(0x8000u));
    return signed * UINTS(magnitude <= UINTS(0x7f800000u));
}

";

const UNSIGNED_FLOAT: &str = "\
// The unsigned floats of r11f_g11f_b10f; negatives and NaN give 0 (as unsigned integers, both
// lie above the bits of infinity).
fn PREFIX_LANES_to_unsigned_float(value: FLOATS) -> UINTS {
    let bits = bitcast<UINTS>(value);
    return PREFIX_LANES_round_to_unsigned_float(bits) * UINTS(bits <= UINTS(0x7f800000u));
}

";
