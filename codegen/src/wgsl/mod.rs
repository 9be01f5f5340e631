//! The WGSL emitter: a struct mirroring the layout, `pack_`/`unpack_`/`load_` functions, and
//! the helpers for a fragment shader that writes `Rgba32Uint` targets.
//!
//! Exact conversions (the default) give every conforming adapter the Rust mirror's bits. They
//! use only steps whose result no adapter may choose: integer and bit operations on the
//! float's bits, comparisons, `min`, `floor` of a value scaled by a power of two, float
//! arithmetic only where every order and rounding a GPU compiler may pick gives the same
//! answer (unorm's checked candidate, see `gbuffer_core::codecs::unorm`), and
//! `unpack2x16float` (binary16 to binary32 loses nothing). WGSL's `pack2x16float` rounds in an implementation-defined
//! way and `pack4x8unorm` lets the adapter pick either neighbour, so exact conversions do not
//! use them. The channels of a word are converted together, one vector instruction for all of
//! them; nothing branches on the data, and no `select` works on integer vectors (GLSL ES 3.00
//! cannot translate it). Their CPU twin is [`gbuffer_core::convert`]. Fast conversions
//! ([`Conversions::Fast`]) use the builtins and the engines' f32 idioms instead.
//!
//! The helpers, each codec's written by its file in [`codecs`], carry the layout's snake_case
//! name as a prefix (named through its `Symbols`), so the WGSL of several layouts can be
//! concatenated into one module.

mod bit_fields;
pub mod codecs;
mod targets;

pub use targets::lighting_targets;

use std::collections::BTreeSet;
use std::fmt::Write as _;

use gbuffer_core::Named;

use gbuffer_core::codecs::unsigned_float::EXPONENT_BITS;
use gbuffer_core::codecs::{max_code, Encoding};
use gbuffer_core::format::{Channel, Format};
use gbuffer_core::layout::{Field, Layout, Member, Storage};
use gbuffer_core::{Direction, ScalarKind, Symbols};

use gbuffer_core::Conversions;

use crate::LoweredLayout;
use codecs::{half, small_float, unorm, unsigned_float, Lanes};

/// The WGSL of a layout with exact conversions. The layout must have passed [`Layout::check`].
pub fn emit(layout: &Layout) -> String {
    emit_with(layout, Conversions::Exact)
}

/// The WGSL of a layout with the chosen conversions (lowered here: a caller that emits more
/// from the same layout lowers it once and calls [`emit_lowered`]).
pub fn emit_with(layout: &Layout, conversions: Conversions) -> String {
    emit_lowered(&LoweredLayout::new(layout), conversions)
}

/// The WGSL of a lowered layout with the chosen conversions.
pub fn emit_lowered(lowered: &LoweredLayout, conversions: Conversions) -> String {
    emit_for(lowered, conversions, Target::Wgsl)
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
pub(crate) fn emit_for(
    lowered: &LoweredLayout,
    conversions: Conversions,
    target: Target,
) -> String {
    let (layout, symbols) = (lowered.layout(), lowered.symbols());
    let name = symbols.texel();
    let words = lowered.words().len();
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
    let _ = writeln!(out, "const {}: u32 = {words}u;\n", symbols.words_constant());

    let guarantee = if fast_fields.is_empty() {
        "Exact conversions: the bits match the Rust mirror's on every adapter.".to_string()
    } else if !overridden {
        "Fast conversions: each channel within one code of the Rust mirror's on finite values within f16's range.".to_string()
    } else {
        format!("Exact conversions but for {}, whose channels are within one code of the Rust mirror's on finite values within f16's range.", fast_fields.join(", "))
    };
    let _ = writeln!(out, "// Packs a texel. {guarantee}");
    let _ = writeln!(out, "fn {}(v: {name}) -> {words_type} {{", symbols.pack());
    let _ = writeln!(out, "    return {words_type}(");
    for word in lowered.words() {
        let _ = writeln!(
            out,
            "        {}, // {}",
            encode_word(symbols, layout, &word.members, conversions),
            layout.field_names(word).join(", ")
        );
    }
    out.push_str("    );\n}\n\n");

    let locations = lowered.locations();
    let _ = writeln!(out, "// Unpacks a texel.");
    let _ = writeln!(out, "fn {}(w: {words_type}) -> {name} {{", symbols.unpack());
    let _ = writeln!(out, "    return {name}(");
    for (field, &(word, member)) in layout.fields.iter().zip(locations) {
        let _ = writeln!(
            out,
            "        {}, // {}",
            decode_expression(symbols, field, word, member, conversions),
            field.name
        );
    }
    out.push_str("    );\n}\n\n");

    for (field, &(word, member)) in layout.fields.iter().zip(locations) {
        let place = match field.storage {
            Storage::Word(_) => format!("word {word}"),
            Storage::Bits(_) => format!("bits {} of word {word}", member.bit_range()),
        };
        let _ = writeln!(out, "// Decodes `{}` alone, from {place}.", field.name);
        let _ = writeln!(
            out,
            "fn {}(w: {words_type}) -> {} {{",
            symbols.load_field(&field.name),
            field.ty.wgsl()
        );
        let _ = writeln!(
            out,
            "    return {};\n}}\n",
            decode_expression(symbols, field, word, member, conversions)
        );
    }

    write_targets(&mut out, lowered);
    write_format_helpers(&mut out, lowered, conversions, target);
    let bit_field_helpers = write_bit_field_functions(&mut out, lowered, conversions);
    write_conversion_helpers(&mut out, lowered, conversions, bit_field_helpers);
    // One trailing newline.
    while out.ends_with("\n\n") {
        out.pop();
    }
    // The header comes last, as it says what the code below it needs.
    let mut header = String::new();
    let half_floats = layout.fields.iter().any(|field| {
        field
            .encodings()
            .into_iter()
            .any(codecs::uses_binary16_builtins)
    });
    write_header(&mut header, lowered, fast.as_deref(), half_floats);
    header + &out
}

/// `fast` is None for exact conversions, or says which fields are fast (empty for all, or
/// " for a, b"); `half_floats` says whether the code uses `pack2x16float` or `unpack2x16float`
/// ([`codecs::uses_binary16_builtins`] of a field's encodings), which naga validates only with a
/// capability `Capabilities::default()` leaves out
/// (`gbuffer_translate::wgsl::GENERATED_CODE_CAPABILITIES`).
fn write_header(out: &mut String, lowered: &LoweredLayout, fast: Option<&str>, half_floats: bool) {
    let layout = lowered.layout();
    let _ = writeln!(
        out,
        "// G-buffer layout `{}`: {} words, {} bits ({} used) of a {}-bit budget.",
        layout.name,
        lowered.words().len(),
        lowered.bits(),
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
    for (index, word) in lowered.words().iter().enumerate() {
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
fn write_targets(out: &mut String, lowered: &LoweredLayout) {
    let symbols = lowered.symbols();
    let name = symbols.texel();
    let targets_struct = symbols.targets();
    let words = lowered.words().len();
    let targets = lowered.targets();
    let _ = writeln!(
        out,
        "// The G-buffer pass's fragment output: one colour target per four words (Rgba32Uint, the"
    );
    let _ = writeln!(
        out,
        "// last as narrow as its words; words 4t to 4t + 3 in target t, past the end zero)."
    );
    let _ = writeln!(out, "struct {targets_struct} {{");
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
        "fn {}(v: {name}) -> {targets_struct} {{\n    let w = {}(v);",
        symbols.pack_targets(),
        symbols.pack()
    );
    let vectors: Vec<String> = (0..targets)
        .map(|target| {
            let lanes: Vec<String> = (4 * target..4 * target + 4).map(word_or_zero).collect();
            format!("vec4<u32>({})", lanes.join(", "))
        })
        .collect();
    let _ = writeln!(
        out,
        "    return {targets_struct}({});\n}}\n",
        vectors.join(", ")
    );
    let _ = writeln!(out, "// Reassembles the words from the targets, e.g. `textureLoad` results of the lighting pass.");
    let _ = writeln!(
        out,
        "fn {}(t: {targets_struct}) -> array<u32, {words}> {{",
        symbols.words_from_targets()
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
        "fn {}(t: {targets_struct}) -> {name} {{\n    return {}({}(t));\n}}\n",
        symbols.unpack_targets(),
        symbols.unpack(),
        symbols.words_from_targets()
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
    symbols: &Symbols,
    layout: &Layout,
    members: &[Member],
    conversions: Conversions,
) -> String {
    let parts: Vec<String> = members
        .iter()
        .map(|member| {
            let field = &layout.fields[member.field];
            match field.storage {
                Storage::Word(format) => encode_call(symbols, field, format, conversions),
                Storage::Bits(_) => {
                    let call = format!(
                        "{}(v.{})",
                        symbols.bit_field(Direction::Encode, member.field),
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
fn encode_call(
    symbols: &Symbols,
    field: &Field,
    format: Format,
    conversions: Conversions,
) -> String {
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
    let function = symbols.format_word(Direction::Encode, format, mode_suffix(field, conversions));
    format!("{function}({widened})")
}

/// Decodes a field from word `word`: a whole word's channels narrowed to the field's
/// components, or a bit field's code taken out of its word.
fn decode_expression(
    symbols: &Symbols,
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
                symbols.bit_field(Direction::Decode, member.field)
            );
        }
    };
    let function = symbols.format_word(Direction::Decode, format, mode_suffix(field, conversions));
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
pub(crate) fn mode_suffix(field: &Field, conversions: Conversions) -> &'static str {
    match field.conversions {
        Some(own) if own != conversions => own.name_suffix(),
        _ => "",
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
    lowered: &LoweredLayout,
    conversions: Conversions,
    target: Target,
) {
    let (layout, symbols) = (lowered.layout(), lowered.symbols());
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
        let encode = symbols.format_word(Direction::Encode, format, suffix);
        let decode = symbols.format_word(Direction::Decode, format, suffix);
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
            (false, Format::Rgb10A2) => Some(unorm::WGSL_FAST_RGB10_A2),
            (false, Format::Rgba8) => Some(unorm::WGSL_FAST_RGBA8_ARITHMETIC),
            (false, Format::R11fG11fB10f) => Some(unsigned_float::WGSL_FAST_R11F_G11F_B10F),
            _ => None,
        };
        match template {
            Some(template) => out.push_str(&template.replace("ENCODE", &encode)),
            None => {
                let _ = writeln!(
                    out,
                    "fn {encode}(c: {vector}) -> u32 {{\n{}}}\n",
                    encode_body(symbols, format)
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
fn encode_body(symbols: &Symbols, format: Format) -> String {
    let channels = format.channels();
    let lanes = Lanes(channels.len());
    let first = channels[0];
    let codes = match first.encoding {
        Encoding::Float32 => "bitcast<u32>(c)".to_string(),
        Encoding::Uint if first.bits == 32 => "c".to_string(),
        Encoding::Uint => format!("min(c, {})", per_channel(format, |c| max_code(c.bits))),
        Encoding::Sint => {
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
        Encoding::Unorm => format!(
            "{}(c, {}, {})",
            symbols.codec_helper(lanes.0, unorm::ENCODE_HELPER),
            channel_literal(format, "f32", |c| format!("{:?}", max_code(c.bits) as f32)),
            channel_literal(format, "f32", |c| format!("{:?}", (1u32 << c.bits) as f32))
        ),
        Encoding::Half => format!("{}(c)", symbols.codec_helper(lanes.0, half::ENCODE_HELPER)),
        Encoding::UnsignedFloat => {
            let helper = symbols.codec_helper(lanes.0, unsigned_float::ENCODE_HELPER);
            format!("{helper}(c)")
        }
        other => unreachable!("a format's channels use per-component codecs, not {other}"),
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
        Encoding::Float32 => "bitcast<f32>(word)".to_string(),
        Encoding::Uint if channels.len() == 1 => "word".to_string(),
        Encoding::Uint => codes,
        // Move each channel's top bit to bit 31, then shift back arithmetically.
        Encoding::Sint => format!(
            "bitcast<{}>({}(word) << {}) >> {}",
            lanes.of("i32"),
            lanes.of("u32"),
            per_channel(format, |c| 32 - c.offset - c.bits),
            per_channel(format, |c| 32 - c.bits)
        ),
        // The reciprocal is correctly rounded; the product stays within 1 ulp of the exact
        // quotient and the largest code decodes to exactly 1.0.
        Encoding::Unorm => {
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
        Encoding::Half => "unpack2x16float(word)".to_string(),
        // The codes are halves without their sign and low mantissa bits: widened back into
        // halves, they decode exactly as rg16f does.
        Encoding::UnsignedFloat => return unsigned_float::WGSL_DECODE_R11F_G11F_B10F.to_string(),
        other => unreachable!("a format's channels use per-component codecs, not {other}"),
    };
    format!("    return {value};\n")
}

/// The mantissa bits of a small-float channel (half or unsigned float).
fn mantissa_bits(channel: &Channel) -> u32 {
    match channel.encoding {
        Encoding::UnsignedFloat => channel.bits - EXPONENT_BITS,
        _ => 10,
    }
}

/// The bit fields' encode and decode functions and the helpers they call, alone (no struct,
/// no pack or unpack): what a pixel local storage include adds beside its block.
#[cfg(feature = "tools")]
pub(crate) fn bit_field_functions(lowered: &LoweredLayout, conversions: Conversions) -> String {
    let mut out = String::new();
    let helpers = write_bit_field_functions(&mut out, lowered, conversions);
    write_each_once(&mut out, helpers);
    out
}

/// Each bit field's encode and decode functions; returns the helpers they call, for the caller
/// to write after the functions.
fn write_bit_field_functions(
    out: &mut String,
    lowered: &LoweredLayout,
    conversions: Conversions,
) -> Vec<String> {
    let mut helpers = Vec::new();
    for (index, field) in lowered.layout().fields.iter().enumerate() {
        if let Storage::Bits(bit_field) = field.storage {
            let (text, field_helpers) = bit_fields::functions(
                lowered.symbols(),
                index,
                field,
                bit_field,
                mode(field, conversions),
            );
            out.push_str(&text);
            helpers.extend(field_helpers);
        }
    }
    helpers
}

/// Each distinct text of `texts` once, in order.
fn write_each_once(out: &mut String, texts: Vec<String>) {
    let mut written = BTreeSet::new();
    for text in texts {
        if written.insert(text.clone()) {
            out.push_str(&text);
        }
    }
}

/// The conversion helpers of the layout's exact formats (unorm's per lane count, the small
/// floats' with their format's constants written out) and then its bit fields' (as
/// [`write_bit_field_functions`] returned them), each once.
fn write_conversion_helpers(
    out: &mut String,
    lowered: &LoweredLayout,
    conversions: Conversions,
    bit_field_helpers: Vec<String>,
) {
    let (layout, symbols) = (lowered.layout(), lowered.symbols());
    let exact: BTreeSet<Format> = layout
        .fields
        .iter()
        .filter(|field| is_exact(field, conversions))
        .filter_map(Field::format)
        .collect();
    let mut helpers: Vec<String> = exact
        .iter()
        .filter(|format| format.channels()[0].encoding == Encoding::Unorm)
        .map(|format| Lanes(format.channels().len()))
        .collect::<BTreeSet<Lanes>>()
        .into_iter()
        .map(|lanes| lanes.fill(unorm::WGSL_ENCODE, symbols))
        .collect();
    for format in exact {
        let (name, wrapper) = match format.channels()[0].encoding {
            Encoding::Half => ("unsigned_half", half::WGSL_ENCODE),
            Encoding::UnsignedFloat => ("unsigned_float", unsigned_float::WGSL_ENCODE),
            _ => continue,
        };
        let mantissas: Vec<u32> = format.channels().iter().map(mantissa_bits).collect();
        helpers.extend(small_float::helpers(symbols, name, wrapper, &mantissas));
    }
    helpers.extend(bit_field_helpers);
    write_each_once(out, helpers);
}

#[cfg(all(test, feature = "tools"))]
mod tests {
    use super::*;

    /// Listing 2.2 as its layout file gives it: two rgba8 fields, the third and fourth.
    fn mobile_metallic() -> Layout {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("layouts/mobile_metallic.toml");
        gbuffer_layout_file::read_layout_file(&path).unwrap().layout
    }

    #[test]
    fn a_layouts_fast_conversions_reach_the_wgsl() {
        let layout = mobile_metallic();
        assert!(!emit_with(&layout, Conversions::Exact).contains("pack4x8unorm(c)"));
        assert!(emit_with(&layout, Conversions::Fast).contains("pack4x8unorm(c)"));
    }

    #[test]
    fn a_fields_own_conversions_reach_the_wgsl() {
        let mut layout = mobile_metallic();
        layout.fields[2].conversions = Some(Conversions::Fast);
        assert!(emit_with(&layout, Conversions::Exact).contains(
            "_encode_rgba8_fast_word(c: vec4<f32>) -> u32 {\n    return pack4x8unorm(c);"
        ));
    }
}
