//! Unsigned normalized: a value in `[0, 1]` as the code `floor(0.5 + (2^n - 1) clamp(x, 0,
//! 1))` of `n` bits, decoded as `code / (2^n - 1)`. Exact: NaN and negatives give 0, values
//! from 1 up the largest code. 1 to 23 bits per component (past that an f32 has no more bits to
//! give). The formats `rgba8`, `rgb10_a2` and `rg16` are built from it.
//!
//! The exact encode rounds in f32 arithmetic and then checks its rounding exactly: the engines'
//! `u32(clamp(x) * max + 0.5)` is the code or one above it, whatever the adapter's rounding,
//! and one more product, exact by construction, tells which. The fast form is that first step
//! alone, one code from the exact one at most.

use super::wgsl::{BitField, Functions};
use super::{max_code, small_integer_from_f32, Codec, F32_INFINITY_BITS};

/// Unsigned normalized encode: `floor(0.5 + (2^bits - 1) * clamp(value, 0, 1))`, exact; NaN
/// gives 0. Valid for `bits` from 1 to 23.
///
/// The WGSL's algorithm ([`WGSL_ENCODE`]), step for step, with `x` the clamped value (NaN and
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

/// The name of [`WGSL_ENCODE`]'s function, for [`Lanes::helper`](super::wgsl::Lanes::helper).
pub const ENCODE_HELPER: &str = "to_unorm";

/// The exact encode, per lane (`PREFIX_LANES_to_unorm`).
pub const WGSL_ENCODE: &str = "\
// Unsigned normalized encode, per lane: floor(0.5 + max_code * clamp(value, 0, 1)), exact.
// NaN and negatives give 0 (as unsigned integers their bits lie above infinity's; saturate's
// NaN is the adapter's, so it is not trusted), values from 1.0 up max_code. The candidate,
// rounded in f32 as engines round, is the code or one above it whatever the adapter's rounding;
// it is one too high exactly when x * max_code + 0.5 < candidate, tested as x * two_to_bits -
// candidate + 0.5 < x, whose every step is exact (a power-of-two product, Sterbenz's lemma, a
// sum exact wherever it could equal x), so no rounding mode, fused multiply-add or reordering
// changes the answer (the proof: unorm_from_f32 in gbuffer-core). Float selects only: GLSL ES
// 3.00 has none on integer vectors. max_code = 2^bits - 1 and two_to_bits = 2^bits.
fn PREFIX_LANES_to_unorm(value: FLOATS, max_code: FLOATS, two_to_bits: FLOATS) -> UINTS {
    let x = select(FLOATS(0.0), saturate(value), bitcast<UINTS>(value) <= UINTS(0x7f800000u));
    let candidate = floor(x * max_code + FLOATS(0.5));
    let below = (x * two_to_bits - candidate) + FLOATS(0.5);
    return UINTS(candidate - select(FLOATS(0.0), FLOATS(1.0), below < x));
}

";

/// The fast encode of the `rgb10_a2` format (`ENCODE` is the function's name).
pub const WGSL_FAST_RGB10_A2: &str = "\
// Fast conversions: the codes are rounded in f32 arithmetic, one code from the exact ones at
// most (where the product lies within f32's rounding of a half-integer); the decode is exact.
fn ENCODE(c: vec4<f32>) -> u32 {
    let scale = vec4<f32>(1023.0, 1023.0, 1023.0, 3.0);
    let codes = vec4<u32>(clamp(c, vec4<f32>(0.0), vec4<f32>(1.0)) * scale + vec4<f32>(0.5));
    return codes.x | (codes.y << 10u) | (codes.z << 20u) | (codes.w << 30u);
}

";

/// The fast encode of the `rgba8` format for GLSL ES 3.00, which has no `packUnorm4x8`
/// (`ENCODE` is the function's name).
pub const WGSL_FAST_RGBA8_ARITHMETIC: &str = "\
// Fast conversions for GLSL ES 3.00, which has no packUnorm4x8: rounded in f32 arithmetic like
// the builtin (one code from the exact ones at most); the decode is the exact one.
fn ENCODE(c: vec4<f32>) -> u32 {
    let codes = vec4<u32>(clamp(c, vec4<f32>(0.0), vec4<f32>(1.0)) * 255.0 + vec4<f32>(0.5));
    let placed = codes << vec4<u32>(0u, 8u, 16u, 24u);
    return placed.x | placed.y | placed.z | placed.w;
}

";

/// The decode body of a unorm bit field: each code times the correctly rounded reciprocal of
/// its largest code (within 1 ulp of the exact quotient; the largest code decodes to 1.0).
pub fn wgsl_decode(field: &BitField) -> String {
    format!(
        "{}    return {}(codes) * {};\n",
        field.split_codes(),
        field.lanes.of("f32"),
        field.reciprocal(field.each)
    )
}

/// The unorm codec.
pub const CODEC: Codec =
    Codec::floats("unorm", (1, 23), (unorm_from_f32, f32_from_unorm), wgsl).with_fast_form();

/// A unorm bit field's WGSL: the exact encode (the engines' f32 rounding, checked), or that
/// rounding alone; the decode, each code times its largest code's reciprocal.
fn wgsl(field: &BitField) -> Functions {
    let (prefix, lanes, each) = (field.prefix, field.lanes, field.each);
    let max = max_code(each);
    let encode = if field.fast {
        format!(
            "    let codes = {}(clamp(value, {}, {}) * {} + {});\n    return {};\n",
            lanes.of("u32"),
            lanes.splat_f32(0.0),
            lanes.splat_f32(1.0),
            lanes.splat_f32(max as f32),
            lanes.splat_f32(0.5),
            field.joined("codes")
        )
    } else {
        format!(
            "    let codes = {}(value, {}, {});\n    return {};\n",
            lanes.helper(prefix, ENCODE_HELPER),
            lanes.splat_f32(max as f32),
            lanes.splat_f32((1u32 << each) as f32),
            field.joined("codes")
        )
    };
    let helpers = match field.fast {
        true => Vec::new(),
        false => vec![lanes.fill(WGSL_ENCODE, prefix)],
    };
    Functions {
        encode,
        decode: wgsl_decode(field),
        helpers,
    }
}

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
