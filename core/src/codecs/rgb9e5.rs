//! Shared-exponent rgb9e5 (EXT_texture_shared_exponent): a `vec3` in 32 bits, three 9-bit
//! mantissas (red in bits 0-8, green 9-17, blue 18-26) over one 5-bit exponent (27-31, bias
//! 15). Each channel is clamped to `[0, 65408]` (NaN to 0); the shared exponent is
//! `max(-16, floor(log2(largest))) + 16`, one more where the largest channel's mantissa rounds
//! up to 512; each mantissa is `floor(channel / 2^(exponent - 24) + 0.5)`. The extension's
//! algorithm evaluated exactly, on the floats' bits: `floor(log2)` is the exponent field, and
//! rounding a value scaled by a power of two is a shift of its significand with half its last
//! place added. The decode, `mantissa 2^(exponent - 24)`, is exact.
//!
//! The shading library's `rgb9e5_encode` and `rgb9e5_decode` (module `hdr`) are this codec's
//! WGSL (gbuffer-codegen's `wgsl::codecs::rgb9e5`).

use super::{Codec, Shape, F32_INFINITY_BITS};

/// The largest relative error of the brightest channel of rgb9e5 above the denormals: half a
/// step of its 9-bit mantissa (at least 256 of 512), 2^-9.
pub const MAX_RELATIVE_ERROR: f64 = 1.0 / 512.0;

/// The largest value rgb9e5 holds, as f32 bits: (511 / 512) 2^16 = 65408.
const MAX_BITS: u32 = 0x477f_8000;

/// Encodes a colour, exactly (see the module's doc).
#[inline(always)]
pub fn rgb9e5_from_f32(rgb: [f32; 3]) -> u32 {
    // Non-negative floats order like their bits; NaN and negatives lie above infinity's.
    let clamped = rgb.map(|value| {
        let bits = value.to_bits();
        if bits > F32_INFINITY_BITS {
            0
        } else {
            bits.min(MAX_BITS)
        }
    });
    let largest = clamped[0].max(clamped[1]).max(clamped[2]);
    // Biased exponent 111 is 2^-16: the smallest the shared exponent represents.
    let exponent = (largest >> 23).max(111) - 111;
    let exponent = exponent + u32::from(mantissa_at(largest, exponent) == 512);
    let [red, green, blue] = clamped.map(|bits| mantissa_at(bits, exponent));
    red | (green << 9) | (blue << 18) | (exponent << 27)
}

/// `floor(value * 2^(24 - exponent) + 0.5)` for a non-negative f32 given as bits: its
/// significand shifted right by `150 - e - (24 - exponent)` with rounding; past a shift of 25
/// the result is 0, as it is at 25 (an f32 denormal shifts by at least that much).
#[inline(always)]
fn mantissa_at(bits: u32, exponent: u32) -> u32 {
    let significand = (bits & 0x7f_ffff) | 0x80_0000;
    let shift = (126 + exponent).saturating_sub(bits >> 23).min(25);
    (significand + ((1 << shift) >> 1)) >> shift
}

/// Decodes rgb9e5, exactly: each mantissa times 2^(exponent - 24).
#[inline]
pub fn f32_from_rgb9e5(word: u32) -> [f32; 3] {
    let scale = f32::from_bits(((word >> 27) + 103) << 23);
    [0, 9, 18].map(|offset| ((word >> offset) & 0x1ff) as f32 * scale)
}

/// The rgb9e5 codec.
pub const CODEC: Codec = Codec::vector(
    "rgb9e5",
    Shape::Fixed(32, 3, "a `Vec3`"),
    (
        |rgb, _, _| rgb9e5_from_f32(rgb),
        |word, _, _| f32_from_rgb9e5(word),
    ),
);

#[cfg(test)]
mod tests {
    use super::*;

    /// EXT_texture_shared_exponent's rgb9e5 algorithm as its text writes it, in f64 (every
    /// step exact for f32 inputs; `floor(log2)` read from the f64's exponent field).
    fn rgb9e5_reference(rgb: [f32; 3]) -> u32 {
        let clamped = rgb.map(|value| {
            let value = f64::from(value);
            if value.is_nan() {
                0.0
            } else {
                value.clamp(0.0, 65408.0)
            }
        });
        let largest = clamped[0].max(clamped[1]).max(clamped[2]);
        let floor_log2 = if largest > 0.0 {
            ((largest.to_bits() >> 52) & 0x7ff) as i32 - 1023
        } else {
            i32::MIN
        };
        let exponent_p = floor_log2.max(-16) + 16;
        let mantissa =
            |value: f64, exponent: i32| (value / 2f64.powi(exponent - 24) + 0.5).floor() as u32;
        let exponent = if mantissa(largest, exponent_p) == 512 {
            exponent_p + 1
        } else {
            exponent_p
        };
        let [red, green, blue] = clamped.map(|value| mantissa(value, exponent));
        red | (green << 9) | (blue << 18) | ((exponent as u32) << 27)
    }

    /// Against the extension's algorithm: edge cases, the exponent carry beside every power of
    /// two, the largest value, and a million random triples.
    #[test]
    fn is_the_extensions_algorithm_evaluated_exactly() {
        let mut cases: Vec<[f32; 3]> = vec![
            [0.0, 0.0, 0.0],
            [-0.0, -1.0, f32::NAN],
            [65408.0, 65408.0, 65408.0],
            [65409.0, 1e9, f32::INFINITY],
            [f32::NEG_INFINITY, f32::MIN_POSITIVE, f32::from_bits(1)],
            [1.0, 0.5, 0.25],
        ];
        for exponent in -20..17 {
            let power = 2f32.powi(exponent);
            for largest in [
                power,
                power * (1.0 - 2f32.powi(-10)),
                f32::from_bits((power * (1.0 - 2f32.powi(-10))).to_bits() - 1),
                power * (1.0 - 2f32.powi(-11)),
                f32::from_bits(power.to_bits() - 1),
            ] {
                cases.push([largest, largest / 3.0, largest / 700.0]);
                cases.push([
                    largest / 512.0,
                    largest,
                    f32::from_bits(largest.to_bits() + 1),
                ]);
            }
        }
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut random = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let bits = (state >> 32) as u32;
            // Mostly magnitudes rgb9e5 holds, some of anything.
            if state & 3 == 0 {
                f32::from_bits(bits)
            } else {
                f32::from_bits(0x3000_0000 + bits % 0x1800_0000)
            }
        };
        cases.extend((0..1_000_000).map(|_| [random(), random(), random()]));
        for rgb in cases {
            assert_eq!(
                rgb9e5_from_f32(rgb),
                rgb9e5_reference(rgb),
                "{rgb:?}: {:#010x}, reference {:#010x}",
                rgb9e5_from_f32(rgb),
                rgb9e5_reference(rgb)
            );
        }
        // Decoding is exact: the mantissa times 2^(exponent - 24).
        for exponent in 0..32u32 {
            for mantissa in [0u32, 1, 255, 256, 511] {
                let word = mantissa | (mantissa << 9) | (mantissa << 18) | (exponent << 27);
                let expected = (f64::from(mantissa) * 2f64.powi(exponent as i32 - 24)) as f32;
                assert_eq!(f32_from_rgb9e5(word), [expected; 3]);
                if mantissa >= 256 {
                    assert_eq!(
                        rgb9e5_from_f32([expected; 3]),
                        word,
                        "canonical words round-trip"
                    );
                }
            }
        }
    }
}
