//! Unsigned small floats: a 5-bit exponent (bias 15) over `n - 5` mantissa bits, no sign, as
//! the channels of `r11f_g11f_b10f` (6, 6 and 5 mantissa bits). Round to nearest even,
//! denormals kept, saturating at the largest finite value; negatives and NaN give 0. The decode
//! is exact. As a bit field, 6 to 15 bits per component (1 to 10 mantissa bits).
//!
//! The exact WGSL (gbuffer-codegen's `wgsl::codecs::unsigned_float`) rounds with [`small_float`](super::small_float)'s integer algorithm. A code
//! shifted up to ten mantissa bits is a half's bit pattern, so the decode is
//! `unpack2x16float`, exact. The fast form of `r11f_g11f_b10f` is the engines' idiom: halves
//! from `pack2x16float` with their low mantissa bits cut.

use super::small_float::{f32_from_small_float, small_float_from_magnitude};
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

/// The unsigned small float codec: the mantissa has a code's bits past the exponent.
pub const CODEC: Codec = Codec::floats(
    "unsigned_float",
    (EXPONENT_BITS + 1, EXPONENT_BITS + 10),
    (
        |value, each| unsigned_float_from_f32(value, each - EXPONENT_BITS),
        |code, each| f32_from_small_float(code, each - EXPONENT_BITS),
    ),
);

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
