//! Signed normalized: a value in `[-1, 1]` as GL's `round(clamp(x, -1, 1) (2^(n-1) - 1))`,
//! halves away from zero, exact, in an `n`-bit two's complement; decoded as `max(code /
//! (2^(n-1) - 1), -1)`, so the most negative code reads -1 as the next one does. NaN gives 0.
//! 2 to 24 bits per component.
//!
//! The magnitude is [`unorm`](super::unorm)'s code of `|x|` at `n - 1` bits (the same
//! formula) and the sign is applied to the code, so the encoding is symmetric about zero.

use super::integer::i32_from_sint;
use super::unorm::unorm_from_f32;
use super::{max_code, Codec};

/// Signed normalized encode, GL's formula `round(clamp(value, -1, 1) * (2^(bits - 1) - 1))`
/// with halves rounded away from zero, exact; the code is the `bits`-bit two's complement. NaN
/// gives 0. Valid for `bits` from 2 to 24.
#[inline(always)]
pub fn snorm_from_f32(value: f32, bits: u32) -> u32 {
    // NaN's magnitude encodes as 0, whatever its sign.
    let magnitude = unorm_from_f32(f32::from_bits(value.to_bits() & 0x7fff_ffff), bits - 1);
    if value.to_bits() >> 31 == 1 {
        magnitude.wrapping_neg() & max_code(bits)
    } else {
        magnitude
    }
}

/// Signed normalized decode, GL's formula `max(code / (2^(bits - 1) - 1), -1)`.
#[inline]
pub fn f32_from_snorm(code: u32, bits: u32) -> f32 {
    (i32_from_sint(code, bits) as f32 / (max_code(bits) >> 1) as f32).max(-1.0)
}

/// The snorm codec.
pub const CODEC: Codec = Codec::floats("snorm", (2, 24), (snorm_from_f32, f32_from_snorm));

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codecs::assert_every_f32;

    /// Snorm evaluated plainly, in f64 (exact: the product has at most 48 significant bits),
    /// halves rounded away from zero.
    fn snorm_reference(value: f32, bits: u32) -> u32 {
        if value.is_nan() {
            return 0;
        }
        let scaled = f64::from(value).clamp(-1.0, 1.0) * f64::from(max_code(bits) >> 1);
        let rounded = (scaled.abs() + 0.5).floor().copysign(scaled) as i32;
        (rounded as u32) & max_code(bits)
    }

    #[test]
    #[cfg_attr(
        debug_assertions,
        ignore = "exhaustive: run optimised, `cargo test --release -p gbuffer-core --lib every_f32`"
    )]
    fn the_algorithm_is_exact_for_every_f32() {
        assert_every_f32("snorm", &[8, 16, 24], snorm_from_f32, snorm_reference);
    }

    #[test]
    fn is_symmetric_and_decodes_the_most_negative_code_to_minus_one() {
        for bits in [2, 4, 8, 12, 16, 24] {
            let highest = max_code(bits) >> 1;
            for (value, expected) in [
                (1.0f32, highest),
                (-1.0, highest.wrapping_neg() & max_code(bits)),
                (-0.0, 0),
                (f32::NAN, 0),
                (-f32::NAN, 0),
                (f32::NEG_INFINITY, highest.wrapping_neg() & max_code(bits)),
            ] {
                assert_eq!(
                    snorm_from_f32(value, bits),
                    expected,
                    "{value} at {bits} bits"
                );
            }
            assert_eq!(f32_from_snorm(highest + 1, bits), -1.0);
            assert_eq!(f32_from_snorm(highest, bits), 1.0);
            for code in [0, 1, highest / 2, highest] {
                let negative = code.wrapping_neg() & max_code(bits);
                assert_eq!(f32_from_snorm(negative, bits), -f32_from_snorm(code, bits));
                assert_eq!(snorm_from_f32(f32_from_snorm(code, bits), bits), code);
            }
        }
    }
}
