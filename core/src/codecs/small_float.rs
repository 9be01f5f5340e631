//! The rounding shared by the small floats: an f32 to a float with a 5-bit exponent (bias 15)
//! and a few mantissa bits, to nearest even, denormals kept, saturating at the largest finite
//! value (never infinity). [`half`](super::half) (10 mantissa bits and a sign) and
//! [`unsigned_float`](super::unsigned_float) (`r11f_g11f_b10f`'s 6 and 5 bits, no sign) are
//! built on it; the decode of both is exact.

use super::small_integer_from_f32;

/// The largest relative error of an unsigned float with `mantissa_bits` of mantissa above its
/// denormals: half an ulp, `2^-(mantissa_bits + 1)` (r11f: 2^-7, b10f: 2^-6, half: 2^-11).
/// The bound the solvers hold a light's precision to.
pub fn max_relative_error(mantissa_bits: u32) -> f64 {
    0.5f64.powi(mantissa_bits as i32 + 1)
}

/// The largest finite code of a float with a 5-bit exponent and `mantissa_bits` of mantissa.
#[inline]
pub fn small_float_max_code(mantissa_bits: u32) -> u32 {
    (30 << mantissa_bits) | ((1 << mantissa_bits) - 1)
}

/// Rounds a non-negative f32, given as its bits with the sign bit clear, to a float with a
/// 5-bit exponent (bias 15) and `mantissa_bits` of mantissa (1 to 10): round to nearest even,
/// denormals kept, saturating at the largest finite code. NaN gives 0.
///
/// The WGSL's algorithm (gbuffer-codegen's `wgsl::codecs::small_float`): normal results round the f32 bits in integer
/// arithmetic, rebiasing the exponent in the same add (a carry moves into the exponent, as it
/// should); denormal results scale the value by a power of two, exactly, and round it to
/// nearest even. Each path gives at least the code where the other applies (under 2^-14 the
/// rebias wraps around; from 2^-14 up the scaled value is at least the code), so the smaller is
/// the code. NaN scales to NaN, which converts to 0.
#[inline(always)]
pub fn small_float_from_magnitude(magnitude_bits: u32, mantissa_bits: u32) -> u32 {
    let shift = 23 - mantissa_bits;
    let odd = (magnitude_bits >> shift) & 1;
    let rounding_and_rebias = ((1u32 << (shift - 1)) - 1).wrapping_sub(113 << 23);
    let normal = (magnitude_bits
        .wrapping_add(rounding_and_rebias)
        .wrapping_add(odd)
        >> shift)
        + (1 << mantissa_bits);
    // value * 2^(14 + mantissa_bits), rounded to nearest even by adding and removing 2^23 (the
    // CPU rounds to nearest even, and a denormal result is under 2^10); larger values stay
    // large, and the conversion saturates.
    let scaled = f32::from_bits(magnitude_bits) * f32::from_bits((141 + mantissa_bits) << 23);
    // Rounded as above, exactly, in a conversion vector units have, after clamping in `max` and
    // `min` (no branch, so that the slices' loops vectorise): NaN and negative values (the
    // callers' negative inputs) give 0, and at 2^16 and above the value is past every code (the
    // minimum below takes `normal`).
    #[allow(clippy::manual_clamp)] // `clamp` keeps NaN, which must give 0 here.
    let denormal = small_integer_from_f32(scaled.max(0.0).min(65_536.0));
    normal
        .min(denormal)
        .min(small_float_max_code(mantissa_bits))
}

/// Decodes an unsigned small float code, exactly. Exponent 31 decodes to infinity or NaN as
/// the format defines (the encoders never produce it).
///
/// The code's exponent and mantissa are placed where an f32 has them (the five exponent bits
/// at the bottom of the f32's eight); then both readings, and a choice by masks (no branch, so
/// that the slices' loops vectorise). A normal code rebiases its exponent from 15 to 127 in one
/// add, exponent 31 to 255. A denormal one, `m * 2^-(14 + mantissa_bits)`, is `2^-14 (1 + m /
/// 2^mantissa_bits)` less `2^-14`: two normal f32s, and their difference exact (Sterbenz's
/// lemma) and normal or zero, so a caller's float unit that flushes denormals cannot change it.
#[inline]
pub fn f32_from_small_float(code: u32, mantissa_bits: u32) -> f32 {
    const TWO_TO_MINUS_14: u32 = 113 << 23;
    let placed = code << (23 - mantissa_bits);
    let is_special = u32::from(placed >= 31 << 23).wrapping_neg();
    let normal = placed + (112 << 23) + ((112 << 23) & is_special);
    let denormal = f32::from_bits(placed | TWO_TO_MINUS_14) - f32::from_bits(TWO_TO_MINUS_14);
    // All ones for a denormal, as a mask: an `if` here stays a branch in the loops.
    let is_denormal = u32::from(placed < 1 << 23).wrapping_neg();
    f32::from_bits((denormal.to_bits() & is_denormal) | (normal & !is_denormal))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Round to nearest even in f64 arithmetic, the textbook way, for comparison.
    fn small_float_reference(value: f32, mantissa_bits: u32) -> u32 {
        let max = f64::from(f32_from_small_float(
            small_float_max_code(mantissa_bits),
            mantissa_bits,
        ));
        let value = f64::from(value);
        if value.is_nan() || value <= 0.0 {
            return 0;
        }
        if value >= max {
            return small_float_max_code(mantissa_bits);
        }
        // Quantization step of the binade (or of the denormal range).
        let exponent = value.log2().floor().max(-14.0);
        let step = (exponent - f64::from(mantissa_bits)).exp2();
        let quotient = value / step;
        let mut rounded = quotient.round();
        if (quotient - quotient.floor() - 0.5).abs() == 0.0 && rounded % 2.0 != 0.0 {
            rounded -= 1.0;
        }
        // In the binade of 2^exponent the code is (exponent + 14) << mantissa_bits plus the
        // rounded quotient (which carries into the exponent when it reaches 2^(mantissa + 1)).
        let code = (((exponent + 14.0) as u32) << mantissa_bits) + rounded as u32;
        code.min(small_float_max_code(mantissa_bits))
    }

    /// Engines often run with x86's MXCSR set to read denormal inputs as zero (DAZ) and flush
    /// denormal results to zero (FTZ). The decode's denormals are differences of normal f32s,
    /// so with both set it still decodes every code as IEEE does (the half crate's widening).
    #[cfg(target_arch = "x86_64")]
    #[test]
    #[allow(deprecated)] // `_mm_getcsr` and `_mm_setcsr`, for want of a stable replacement.
    fn decodes_every_code_alike_with_denormals_flushed() {
        use std::arch::x86_64::{_mm_getcsr, _mm_setcsr};
        use std::hint::black_box;
        const DAZ_AND_FTZ: u32 = 0x0040 | 0x8000;
        for mantissa_bits in 1..=10 {
            let codes = 0..(32u32 << mantissa_bits);
            let ieee: Vec<f32> = codes
                .clone()
                .map(|code| ::half::f16::from_bits((code << (10 - mantissa_bits)) as u16).to_f32())
                .collect();
            // SAFETY: the flags change how this thread treats denormals, nothing else, and
            // are restored before anything else runs on it.
            let saved = unsafe { _mm_getcsr() };
            unsafe { _mm_setcsr(saved | DAZ_AND_FTZ) };
            // The smallest denormal, read as zero: the flags hold.
            let flushes = black_box(f32::from_bits(1)) * 2.0 == 0.0;
            let decoded: Vec<f32> = codes
                .map(|code| f32_from_small_float(black_box(code), mantissa_bits))
                .collect();
            unsafe { _mm_setcsr(saved) };
            assert!(flushes, "MXCSR's DAZ did not take");
            for (code, (ieee, decoded)) in ieee.iter().zip(&decoded).enumerate() {
                assert!(
                    ieee.to_bits() == decoded.to_bits() || (ieee.is_nan() && decoded.is_nan()),
                    "code {code:#x} of {mantissa_bits} mantissa bits: {decoded:e}, IEEE {ieee:e}"
                );
            }
        }
    }

    #[test]
    fn rounding_matches_a_textbook_one_on_every_boundary() {
        for mantissa_bits in [1, 2, 5, 6, 10] {
            let max = small_float_max_code(mantissa_bits);
            for code in 0..max {
                let low = f64::from(f32_from_small_float(code, mantissa_bits));
                let high = f64::from(f32_from_small_float(code + 1, mantissa_bits));
                let midpoint = ((low + high) / 2.0) as f32;
                for value in [
                    low as f32,
                    midpoint,
                    f32::from_bits(midpoint.to_bits() - 1),
                    f32::from_bits(midpoint.to_bits() + 1),
                ] {
                    assert_eq!(
                        small_float_from_magnitude(value.to_bits(), mantissa_bits),
                        small_float_reference(value, mantissa_bits),
                        "{value:e} with {mantissa_bits} mantissa bits"
                    );
                }
            }
        }
    }
}
