//! Unsigned small floats: a 5-bit exponent (bias 15) over `n - 5` mantissa bits, no sign, as
//! the channels of `r11f_g11f_b10f` (6, 6 and 5 mantissa bits). Round to nearest even,
//! denormals kept, saturating at the largest finite value; negatives and NaN give 0. The decode
//! is exact. As a bit field, 6 to 15 bits per component (1 to 10 mantissa bits).
//!
//! The exact WGSL rounds with [`small_float`](super::small_float)'s integer algorithm. A code
//! shifted up to ten mantissa bits is a half's bit pattern, so the decode is
//! `unpack2x16float`, exact. The fast form of `r11f_g11f_b10f` is the engines' idiom: halves
//! from `pack2x16float` with their low mantissa bits cut.

use super::small_float::{f32_from_small_float, small_float_from_magnitude};
use super::wgsl::{BitField, Functions};
use super::{Codec, F32_INFINITY_BITS};

/// The exponent's width: the mantissa has the rest of a code's bits.
pub const EXPONENT_BITS: u32 = 5;

/// f32 to an unsigned small float of `mantissa_bits` (6 for r11f and g11f, 5 for b10f).
/// Negatives and NaN give 0 (as unsigned integers, both lie above infinity's bits).
#[inline(always)]
pub fn unsigned_float_from_f32(value: f32, mantissa_bits: u32) -> u32 {
    let value_bits = value.to_bits();
    let code = small_float_from_magnitude(value_bits, mantissa_bits);
    if value_bits > F32_INFINITY_BITS {
        0
    } else {
        code
    }
}

/// The name of [`WGSL_ENCODE`]'s function for this format's `NAME`, for
/// [`Lanes::helper`](super::wgsl::Lanes::helper).
pub const ENCODE_HELPER: &str = "to_unsigned_float";

/// The exact encode, per lane (`PREFIX_LANES_to_NAME`), around the rounding
/// `PREFIX_LANES_round_to_NAME` of [`small_float::wgsl_helpers`]. The format's `NAME` is
/// `unsigned_float`.
///
/// [`small_float::wgsl_helpers`]: super::small_float::wgsl_helpers
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

/// The unsigned small float codec: the mantissa has a code's bits past the exponent.
pub const CODEC: Codec = Codec::floats(
    "unsigned_float",
    (EXPONENT_BITS + 1, EXPONENT_BITS + 10),
    (
        |value, each| unsigned_float_from_f32(value, each - EXPONENT_BITS),
        |code, each| f32_from_small_float(code, each - EXPONENT_BITS),
    ),
    wgsl,
)
.with_binary16_builtins();

/// An unsigned float bit field's WGSL: the exact rounding per lane; each code widened into a
/// half.
fn wgsl(field: &BitField) -> Functions {
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
            "    let codes = {}_{}_to_{name}(value);\n    return {};\n",
            field.prefix,
            lanes.name(),
            field.joined("codes")
        ),
        decode,
        helpers: super::small_float::wgsl_helpers(
            field.prefix,
            &name,
            WGSL_ENCODE,
            &vec![mantissa; lanes.0],
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codecs::assert_every_f32;
    use crate::codecs::small_float::small_float_max_code;

    /// Small-float rounding written the branching way, bit by bit: the reference the
    /// branch-free algorithm is checked against on every f32.
    fn small_float_by_branches(magnitude_bits: u32, mantissa_bits: u32) -> u32 {
        if magnitude_bits > F32_INFINITY_BITS {
            return 0;
        }
        let exponent = magnitude_bits >> 23;
        let significand = (magnitude_bits & 0x7f_ffff) | 0x80_0000;
        // A normal result (2^-14 and up) drops 23 - mantissa_bits bits; a denormal one more,
        // and past 25 the value is under half the smallest denormal.
        let (exponent_part, extra) = if exponent >= 113 {
            ((exponent - 113) << mantissa_bits, 0)
        } else if exponent == 0 {
            return 0;
        } else {
            (0, 113 - exponent)
        };
        let shift = (23 - mantissa_bits + extra).min(25);
        let kept = significand >> shift;
        let remainder = significand & ((1 << shift) - 1);
        let halfway = 1 << (shift - 1);
        let round_up = remainder > halfway || (remainder == halfway && kept & 1 == 1);
        (exponent_part + kept + u32::from(round_up)).min(small_float_max_code(mantissa_bits))
    }

    #[test]
    #[cfg_attr(
        debug_assertions,
        ignore = "exhaustive: run optimised, `cargo test --release -p gbuffer-core --lib every_f32`"
    )]
    fn rounds_every_f32_as_the_branching_reference_does() {
        let reference = |value: f32, mantissa_bits| match value.is_sign_negative() {
            true => 0,
            false => small_float_by_branches(value.to_bits(), mantissa_bits),
        };
        assert_every_f32(
            "unsigned float",
            &[6, 5, 2],
            unsigned_float_from_f32,
            reference,
        );
    }

    /// The WGSL decodes by widening each code into a half (`unpack2x16float`): every code
    /// decodes to the mirror's value that way.
    #[test]
    fn codes_widened_into_halves_decode_as_the_mirror_does() {
        for mantissa_bits in 1..=10 {
            for code in 0..(32u32 << mantissa_bits) {
                let widened = code << (10 - mantissa_bits);
                let half = ::half::f16::from_bits(widened as u16).to_f32();
                let mirror = f32_from_small_float(code, mantissa_bits);
                assert!(
                    half.to_bits() == mirror.to_bits() || (half.is_nan() && mirror.is_nan()),
                    "code {code:#x} with {mantissa_bits} mantissa bits: {half:e}, mirror {mirror:e}"
                );
            }
        }
    }

    #[test]
    fn stores_negatives_as_zero_and_saturates() {
        assert_eq!(unsigned_float_from_f32(-1.0, 6), 0);
        assert_eq!(unsigned_float_from_f32(f32::INFINITY, 6), 0x7bf);
        assert_eq!(unsigned_float_from_f32(f32::INFINITY, 5), 0x3df);
        assert_eq!(f32_from_small_float(0x7bf, 6), 65024.0);
        assert_eq!(f32_from_small_float(0x3df, 5), 64512.0);
        assert_eq!(f32_from_small_float(0x7c0, 6), f32::INFINITY);
    }
}
