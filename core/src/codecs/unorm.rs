//! Unsigned normalized: a value in `[0, 1]` as the code `floor(0.5 + (2^n - 1) clamp(x, 0,
//! 1))` of `n` bits, decoded as `code / (2^n - 1)`. Exact: NaN and negatives give 0, values
//! from 1 up the largest code. 1 to 23 bits per component (past that an f32 has no more bits to
//! give). The formats `rgba8`, `rgb10_a2` and `rg16` are built from it.
//!
//! The exact WGSL works on the float's bits, as the mirror does, because a GPU compiler may
//! reassociate float arithmetic; the fast form is the engines' `u32(clamp(x) * max + 0.5)`, one
//! code from the exact one at most.

use super::wgsl::{BitField, Functions};
use super::{max_code, Codec, F32_INFINITY_BITS};

/// The bits of 1.0 as f32.
const F32_ONE_BITS: u32 = 0x3f80_0000;

/// Unsigned normalized encode: `floor(0.5 + (2^bits - 1) * clamp(value, 0, 1))`, exact; NaN
/// gives 0. Valid for `bits` from 1 to 23.
///
/// The WGSL's algorithm ([`WGSL_ENCODE`]): with `value = significand * 2^-(shift + bits)` and
/// `2^bits - 1 = max_code`, the code is `(significand - significand / 2^bits + 2^(shift -
/// 1)) >> shift`, where rounding `significand / 2^bits` up changes no result. NaN and negatives
/// (as unsigned integers above infinity's bits) clamp to 0, values from 1.0 up to 1.0; past a
/// shift of 26 every code is 0, as it is at 26.
#[inline(always)]
pub fn unorm_from_f32(value: f32, bits: u32) -> u32 {
    let value_bits = value.to_bits();
    let clamped = if value_bits > F32_INFINITY_BITS {
        0
    } else {
        value_bits.min(F32_ONE_BITS)
    };
    let significand = (clamped & 0x7f_ffff) | 0x80_0000;
    let shift = (150 - bits - (clamped >> 23)).min(26);
    let scaled = significand - ((significand + max_code(bits)) >> bits);
    (scaled + ((1 << shift) >> 1)) >> shift
}

/// Unsigned normalized decode: the exact quotient `code / (2^bits - 1)`, correctly rounded.
#[inline]
pub fn f32_from_unorm(code: u32, bits: u32) -> f32 {
    code as f32 / max_code(bits) as f32
}

/// The exact encode, per lane (`PREFIX_LANES_to_unorm`).
pub const WGSL_ENCODE: &str = "\
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

/// A unorm bit field's WGSL: the exact encode on the float's bits, or the engines' f32
/// rounding; the decode, each code times its largest code's reciprocal.
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
            "    let codes = {prefix}_{}_to_unorm(value, {}, {}, {});\n    return {};\n",
            lanes.name(),
            lanes.splat(each),
            lanes.splat(max),
            lanes.splat(150 - each),
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
    fn the_algorithm_is_exact_for_every_f32() {
        assert_every_f32(
            "unorm",
            &[2, 8, 10, 16, 20, 23],
            unorm_from_f32,
            unorm_reference,
        );
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
