//! IEEE binary16 per component, 16 bits each: round to nearest even, denormals kept, sign
//! kept, saturating at +-65504 (never infinity); NaN gives 0. The decode is exact. The `rg16f`
//! format is built from it.
//!
//! The exact WGSL (gbuffer-codegen's `wgsl::codecs::half`) rounds with [`small_float`](super::small_float)'s integer algorithm, because
//! WGSL lets `pack2x16float` round either way; the fast form is `pack2x16float`, the
//! adapter's rounding (which may flush denormals and overflow to infinity). Both decode with
//! `unpack2x16float`, which widening makes exact, and which naga validates only with
//! `Capabilities::SHADER_FLOAT16_IN_FLOAT32`.

use super::small_float::{f32_from_small_float, small_float_from_magnitude};
use super::{Codec, F32_INFINITY_BITS};

/// f32 to the 16-bit code of an IEEE binary16, sign kept, saturating at +-65504. NaN gives 0.
#[inline]
pub fn half_from_f32(value: f32) -> u32 {
    let value_bits = value.to_bits();
    let magnitude = value_bits & 0x7fff_ffff;
    let code = ((value_bits >> 16) & 0x8000) | small_float_from_magnitude(magnitude, 10);
    // NaN, whatever its sign, gives 0.
    if magnitude > F32_INFINITY_BITS {
        0
    } else {
        code
    }
}

/// Decodes the 16-bit code of an IEEE binary16, exactly.
#[inline]
pub fn f32_from_half(code: u32) -> f32 {
    let magnitude = f32_from_small_float(code & 0x7fff, 10);
    f32::from_bits(magnitude.to_bits() | ((code & 0x8000) << 16))
}

/// The half codec: 16 bits a component.
pub const CODEC: Codec = Codec::floats(
    "half",
    (16, 16),
    (
        |value, _| half_from_f32(value),
        |code, _| f32_from_half(code),
    ),
)
.with_fast_form();

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codecs::assert_every_f32;

    /// On every f32: IEEE's rounding (the half crate's, which overflows to infinity where ours
    /// saturates at the largest finite value, and keeps NaN where ours stores 0).
    #[test]
    #[cfg_attr(
        debug_assertions,
        ignore = "exhaustive: run optimised, `cargo test --release -p gbuffer-core --lib every_f32`"
    )]
    fn rounds_every_f32_as_ieee_does() {
        let ieee = |value: f32, _| {
            let ieee = u32::from(::half::f16::from_f32(value).to_bits());
            if value.is_nan() {
                0
            } else if ieee & 0x7fff == 0x7c00 {
                (ieee & 0x8000) | 0x7bff
            } else {
                ieee
            }
        };
        assert_every_f32("half", &[16], |value, _| half_from_f32(value), ieee);
    }

    #[test]
    fn agrees_with_known_codes() {
        for (value, code) in [
            (0.0f32, 0x0000),
            (-0.0, 0x8000),
            (1.0, 0x3c00),
            (-2.0, 0xc000),
            (65504.0, 0x7bff),
            (65519.0, 0x7bff),
            (65520.0, 0x7bff), // rounds to 65536, saturates
            (1e9, 0x7bff),
            (f32::INFINITY, 0x7bff),
            (f32::NEG_INFINITY, 0xfbff),
            (f32::NAN, 0),
            (-f32::NAN, 0),
            (5.960_464_5e-8, 0x0001), // smallest denormal
            (2.980_232_2e-8, 0x0000), // exactly half of it: ties to even
            (2.980_233e-8, 0x0001),
            (6.097_555e-5, 0x03ff),   // largest denormal
            (6.103_515_6e-5, 0x0400), // smallest normal
        ] {
            assert_eq!(half_from_f32(value), code, "{value:e}");
        }
        for code in 0..0x10000 {
            let exponent = (code >> 10) & 31;
            if exponent == 31 {
                continue;
            }
            assert_eq!(half_from_f32(f32_from_half(code)), code, "code {code:#06x}");
        }
    }
}
