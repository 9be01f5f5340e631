//! Unsigned normalized: a value in `[0, 1]` as the code `floor(0.5 + (2^n - 1) clamp(x, 0,
//! 1))` of `n` bits, decoded as `code / (2^n - 1)`. Exact: NaN and negatives give 0, values
//! from 1 up the largest code. 1 to 23 bits per component (past that an f32 has no more bits to
//! give). The formats `rgba8`, `rgb10_a2` and `rg16` are built from it.
//!
//! The exact encode rounds in f32 arithmetic and then checks its rounding exactly: the engines'
//! `u32(clamp(x) * max + 0.5)` is the code or one above it, whatever the adapter's rounding,
//! and one more product, exact by construction, tells which. The fast form is that first step
//! alone, one code from the exact one at most.

use super::{max_code, small_integer_from_f32, Codec, F32_INFINITY_BITS};

/// Unsigned normalized encode: `floor(0.5 + (2^bits - 1) * clamp(value, 0, 1))`, exact; NaN
/// gives 0. Valid for `bits` from 1 to 23.
///
/// The WGSL's algorithm (gbuffer-codegen's `wgsl::codecs::unorm`), step for step, with `x` the clamped value (NaN and
/// negatives, as unsigned integers above infinity's bits, give 0) and `max_code = 2^bits - 1`:
/// - the candidate `floor(x * max_code + 0.5)` is the code or the code plus one however its
///   roundings go, fused or not: a rounding never crosses an integer the exact value lies
///   beyond, and the exact sum is below the code plus one;
/// - it is one too high exactly when `x * max_code + 0.5 < candidate`, that is when `x *
///   2^bits - candidate + 0.5 < x`, and each step of that is exact: `x * 2^bits` (a power of
///   two), its difference with the candidate (the two lie within a factor of two, Sterbenz's
///   lemma), and the half added (the sum is exact wherever it could equal `x`: from `x =
///   2^-(bits + 1)` up; below, the candidate is 0 and the sum at least 0.5), in any order an
///   optimiser picks (freedreno folds the half into the candidate first, also exact).
#[inline(always)]
pub fn unorm_from_f32(value: f32, bits: u32) -> u32 {
    let x = if value.to_bits() > F32_INFINITY_BITS {
        0.0
    } else {
        value.min(1.0)
    };
    let candidate = (x * max_code(bits) as f32 + 0.5).floor();
    let below = (x * (1u32 << bits) as f32 - candidate) + 0.5;
    let correction = if below < x { 1.0 } else { 0.0 };
    // The code is an integer from 0 to 2^23 - 1.
    small_integer_from_f32(candidate - correction)
}

/// Unsigned normalized decode: the exact quotient `code / (2^bits - 1)`, correctly rounded.
///
/// Computed as `code` times the reciprocal in f64, rounded once to f32: a vector multiply
/// costs a fraction of a vector divide. It is the correctly rounded quotient for every code:
/// the f64 product is within 2^-52 (relative) of `code / max_code`, and a quotient of an odd
/// divisor is never an f32 rounding midpoint and lies at least 2^-25 / max_code, 2^-48 at 23
/// bits, from the nearest (a midpoint is a dyadic rational; the difference's numerator is a
/// nonzero integer), so both round to the same f32. Tested against f32 division, every code
/// of every width.
#[inline]
pub fn f32_from_unorm(code: u32, bits: u32) -> f32 {
    (f64::from(code) * (1.0 / f64::from(max_code(bits)))) as f32
}

/// The largest error of a `bits`-bit unorm over [0, 1]: half a step, `0.5 / (2^bits - 1)`.
/// The bound the solvers (`gbuffer-solver`, the Bevy plugin's) hold a precision to.
pub fn max_error(bits: u32) -> f64 {
    0.5 * (1.0 / f64::from(max_code(bits)))
}

/// The unorm codec.
pub const CODEC: Codec =
    Codec::floats("unorm", (1, 23), (unorm_from_f32, f32_from_unorm)).with_fast_form();

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codecs::assert_every_f32;

    /// The unorm formula evaluated plainly, in f64: exact for every f32 (the product has at
    /// most 40 significant bits, and adding one half cannot round up to the next integer: a
    /// product within 2^-41 of a half-integer would need bits the value does not have).
    fn unorm_reference(value: f32, bits: u32) -> u32 {
        (f64::from(value).clamp(0.0, 1.0) * f64::from(max_code(bits)) + 0.5) as u32
    }

    #[test]
    #[cfg_attr(
        debug_assertions,
        ignore = "exhaustive: run optimised, `cargo test --release -p gbuffer-core --lib every_f32`"
    )]
    fn the_algorithm_is_exact_for_every_f32() {
        assert_every_f32(
            "unorm",
            &[2, 8, 10, 16, 20, 23],
            unorm_from_f32,
            unorm_reference,
        );
    }

    /// f32 division is correctly rounded (IEEE 754), the reference the f64 product must match.
    #[test]
    fn the_decode_is_the_correctly_rounded_quotient_for_every_code() {
        for bits in 1..=23 {
            let max = max_code(bits);
            for code in 0..=max {
                let quotient = code as f32 / max as f32;
                assert_eq!(
                    f32_from_unorm(code, bits).to_bits(),
                    quotient.to_bits(),
                    "code {code} of {bits} bits"
                );
            }
        }
    }

    #[test]
    fn edges() {
        for bits in [2, 8, 10, 16] {
            let max = max_code(bits);
            for (value, expected) in [
                (0.0, 0),
                (-0.0, 0),
                (-1.0, 0),
                (f32::NAN, 0),
                (-f32::NAN, 0),
                (f32::NEG_INFINITY, 0),
                (f32::INFINITY, max),
                (1.0, max),
                (2.5, max),
                (f32::from_bits(1), 0),
                (0.5 / max as f32 * 0.999, 0),
            ] {
                assert_eq!(
                    unorm_from_f32(value, bits),
                    expected,
                    "{value:e} at {bits} bits"
                );
            }
            for code in 0..=max {
                assert_eq!(unorm_from_f32(f32_from_unorm(code, bits), bits), code);
            }
        }
    }
}
