//! The WGSL of bit fields: per field an encode function that returns its code in the low
//! bits and a decode function that takes it back, their bodies and helpers written by the
//! field's codec's file ([`codecs`](super::codecs)). The pack function shifts each code into
//! place and combines a word's codes with `|`.
//!
//! Exact conversions keep the codecs' contracts bit for bit with integer operations only (the
//! decodes of unorm, snorm, octahedral and RGBM are f32 arithmetic, within a few ulp of the
//! mirror); fast conversions use f32 arithmetic and builtins where the codec has a fast form
//! (unorm, half, octahedral, RGBM), one code from the exact ones at most (for octahedral and
//! RGBM, which name some values by two codes, two steps of the decoded value).

use gbuffer_core::bit_field::BitField;
use gbuffer_core::layout::{Conversions, Field};
use gbuffer_core::{Direction, Symbols};

use super::codecs::{self, Lanes};

/// The encode and decode functions of a bit field, under `conversions`, and the conversion
/// helpers they call, each a complete WGSL text (the caller writes each distinct text once):
/// the codec's WGSL written once for both.
pub(super) fn functions(
    symbols: &Symbols,
    index: usize,
    field: &Field,
    bit_field: BitField,
    conversions: Conversions,
) -> (String, Vec<String>) {
    let components = field.ty.components;
    let codec_field = codecs::BitField {
        symbols,
        lanes: Lanes(components),
        each: bit_field.component_bits(components),
        fast: !conversions.is_exact_for_encoding(bit_field.encoding),
        range: bit_field.encoding.range(),
    };
    let codecs::Functions {
        encode,
        decode,
        helpers,
    } = codecs::functions(bit_field.encoding, &codec_field);
    let ty = field.ty.wgsl();
    let encode_name = symbols.bit_field(Direction::Encode, index);
    let decode_name = symbols.bit_field(Direction::Decode, index);
    let mode = if codec_field.fast {
        ", fast conversions"
    } else {
        ""
    };
    let text = format!(
        "// `{}`: {bit_field}{mode}; the code in the low {} bits.\n\
         fn {encode_name}(value: {ty}) -> u32 {{\n{encode}}}\n\n\
         fn {decode_name}(code: u32) -> {ty} {{\n{decode}}}\n\n",
        field.name, bit_field.bits
    );
    (text, helpers)
}
