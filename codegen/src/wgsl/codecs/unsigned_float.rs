//! Unsigned small floats (`gbuffer_core::codecs::unsigned_float`), as the channels of
//! `r11f_g11f_b10f`. The exact encode rounds with [`small_float`](super::small_float)'s integer
//! algorithm. A code shifted up to ten mantissa bits is a half's bit pattern, so the decode is
//! `unpack2x16float`, exact. The fast form of `r11f_g11f_b10f` is the engines' idiom: halves
//! from `pack2x16float` with their low mantissa bits cut.

use gbuffer_core::codecs::unsigned_float::EXPONENT_BITS;

use super::{BitField, Functions};

/// The name of [`WGSL_ENCODE`]'s function for this format's `NAME`, for
/// [`Symbols::codec_helper`](gbuffer_core::Symbols::codec_helper).
pub const ENCODE_HELPER: &str = "to_unsigned_float";

/// The exact encode, per lane (`PREFIX_LANES_to_NAME`), around the rounding
/// `PREFIX_LANES_round_to_NAME` of [`small_float::helpers`](super::small_float::helpers). The
/// format's `NAME` is `unsigned_float`.
pub const WGSL_ENCODE: &str = "\
// The unsigned floats of r11f_g11f_b10f; negatives and NaN give 0 (as unsigned integers, both
// lie above the bits of infinity).
fn PREFIX_LANES_to_NAME(value: FLOATS) -> UINTS {
    let bits = bitcast<UINTS>(value);
    return PREFIX_LANES_round_to_NAME(bits) * UINTS(bits <= UINTS(0x7f800000u));
}

";

/// The fast encode of the `r11f_g11f_b10f` format (`ENCODE` is the function's name).
pub const WGSL_FAST_R11F_G11F_B10F: &str = "\
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

/// The decode of the `r11f_g11f_b10f` format: each code widened into a half.
pub const WGSL_DECODE_R11F_G11F_B10F: &str = "    let red_green = unpack2x16float(((word & 0x7ffu) << 4u) | ((word & 0x3ff800u) << 9u));\n    \
     return vec3<f32>(red_green, unpack2x16float((word >> 17u) & 0x7fe0u).x);\n";

/// An unsigned float bit field's WGSL: the exact rounding per lane; each code widened into a
/// half.
pub fn functions(field: &BitField) -> Functions {
    let lanes = field.lanes;
    let mantissa = field.each - EXPONENT_BITS;
    // The helpers' name says the widths, as fields of other widths have their own.
    let name = format!("e5m{mantissa}_float");
    let widen = 10 - mantissa;
    let decode = match lanes.0 {
        1 => format!("    return unpack2x16float(code << {widen}u).x;\n"),
        n => {
            let values: Vec<String> = "xyzw"[..n]
                .chars()
                .map(|lane| format!("unpack2x16float(codes.{lane} << {widen}u).x"))
                .collect();
            format!(
                "{}    return {}({});\n",
                field.split_codes(),
                lanes.of("f32"),
                values.join(", ")
            )
        }
    };
    Functions {
        encode: format!(
            "    let codes = {}(value);\n    return {};\n",
            field.helper(&format!("to_{name}")),
            field.joined("codes")
        ),
        decode,
        helpers: super::small_float::helpers(
            field.symbols,
            &name,
            WGSL_ENCODE,
            &vec![mantissa; lanes.0],
        ),
    }
}
