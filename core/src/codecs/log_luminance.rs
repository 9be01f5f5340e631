//! Log luminance: a positive scalar per component as its piecewise-linear base-2 logarithm
//! over `[2^-16, 2^16)`, `n - 5` bits of each octave's fraction above 5 bits of octave: the
//! code of `x = (1 + f) 2^e` is `round((e + 16 + f) 2^(n - 5)) + 1`, halves up, and code 0
//! holds zero. Negatives, NaN and values under 2^-16 give 0; values from the top of the range
//! up the largest code. 6 to 24 bits per component; 10 bits hold a light value within 1.6%
//! (half of 1/32 of an octave, relative) over 32 octaves, as the luminance of LogLuv does.
//!
//! The logarithm is the float's own bits read as a fixed-point number (the exponent field is
//! the octave, the mantissa its linear fraction), so both ways are exact in integers: every
//! adapter stores the mirror's bits, and the decode is exact. This codec was added as the
//! codecs' module says a new one is: this file, one line in the list, and its WGSL's file in
//! the WGSL back end.

use super::{max_code, Codec, LightStorage, F32_INFINITY_BITS};

/// The bits of 2^-16, the bottom of the range (code 1).
const BOTTOM_BITS: u32 = 111 << 23;

/// The shift from a float's bits above those of 2^-16 (code 1) to a code of `bits` bits: 23
/// mantissa bits and 5 of octave above, `bits` kept.
#[inline(always)]
pub fn shift(bits: u32) -> u32 {
    28 - bits
}

/// Encodes a value in `bits` bits (6 to 24), exactly (see the module's doc).
#[inline(always)]
pub fn log_luminance_from_f32(value: f32, bits: u32) -> u32 {
    let value_bits = value.to_bits();
    // NaN and negatives lie above infinity's bits, zero and tiny values below 2^-16's.
    if !(BOTTOM_BITS..=F32_INFINITY_BITS).contains(&value_bits) {
        return 0;
    }
    let shift = shift(bits);
    let offset = value_bits - BOTTOM_BITS;
    (((offset + ((1 << shift) >> 1)) >> shift) + 1).min(max_code(bits))
}

/// Decodes a `bits`-bit code, exactly: code 0 is zero, code `c` the float whose bits are `(c -
/// 1)` octave fractions above 2^-16.
#[inline]
pub fn f32_from_log_luminance(code: u32, bits: u32) -> f32 {
    if code == 0 {
        return 0.0;
    }
    f32::from_bits(((code - 1) << shift(bits)) + BOTTOM_BITS)
}

/// The log luminance codec.
pub const CODEC: Codec = Codec::floats(
    "log_luminance",
    (6, 24),
    (log_luminance_from_f32, f32_from_log_luminance),
)
.with_light_storage(light_storage);

/// Three components of 6 to 10 bits (one word): rounding to the nearest of 2^(n - 5)
/// steps an octave is within 2^-(n - 4) of the value, relative; values under 2^-16 are
/// lost, within 2^-16 of the floor.
fn light_storage(floor: f64) -> Vec<LightStorage> {
    (6..=10)
        .map(|each| LightStorage {
            each,
            relative_error: 2f64.powi(4 - each as i32).max(2f64.powi(-16) / floor),
            largest: f64::from(f32_from_log_luminance(max_code(each), each)),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codecs::assert_every_f32;

    /// The octave and its fraction of a positive finite f64: `x = (1 + fraction) 2^octave`.
    fn octave_and_fraction(value: f64) -> (i32, f64) {
        let octave = value.log2().floor() as i32;
        // log2 may round across an octave's edge: step back onto it.
        let octave = match value / 2f64.powi(octave) {
            scaled if scaled >= 2.0 => octave + 1,
            scaled if scaled < 1.0 => octave - 1,
            _ => octave,
        };
        (octave, value / 2f64.powi(octave) - 1.0)
    }

    /// The contract in f64, the plain way: the piecewise-linear logarithm, scaled and rounded
    /// half up (exact: every f32 in range is a multiple of 2^-39 in log units).
    fn reference(value: f32, bits: u32) -> u32 {
        let value = f64::from(value);
        if value.is_nan() || value < 2f64.powi(-16) {
            return 0;
        }
        if value.is_infinite() {
            return max_code(bits);
        }
        let (octave, fraction) = octave_and_fraction(value);
        let logarithm = f64::from(octave + 16) + fraction;
        let code = (logarithm * 2f64.powi(bits as i32 - 5) + 0.5).floor() + 1.0;
        code.min(f64::from(max_code(bits))) as u32
    }

    #[test]
    #[cfg_attr(
        debug_assertions,
        ignore = "exhaustive: run optimised, `cargo test --release -p gbuffer-core --lib every_f32`"
    )]
    fn encodes_every_f32_as_the_contract_says() {
        assert_every_f32(
            "log luminance",
            &[6, 10, 16, 24],
            log_luminance_from_f32,
            reference,
        );
    }

    /// Every code decodes to its octave and fraction, and back to itself.
    #[test]
    fn decodes_every_code_exactly() {
        for bits in [6, 10, 12] {
            assert_eq!(f32_from_log_luminance(0, bits), 0.0);
            let per_octave = 2f64.powi(bits as i32 - 5);
            for code in 1..=max_code(bits) {
                let logarithm = f64::from(code - 1) / per_octave;
                let octave = logarithm.floor();
                let want = (1.0 + logarithm - octave) * 2f64.powi(octave as i32 - 16);
                let got = f32_from_log_luminance(code, bits);
                assert_eq!(f64::from(got), want, "code {code} of {bits} bits");
                assert_eq!(log_luminance_from_f32(got, bits), code);
            }
        }
    }

    /// The relative error of a round trip is within half a step of an octave's fraction.
    #[test]
    fn ten_bits_hold_light_within_a_sixty_fourth() {
        for index in 0..100_000 {
            let value = 2f32.powf(-15.9 + 31.8 * index as f32 / 100_000.0);
            let back = f32_from_log_luminance(log_luminance_from_f32(value, 10), 10);
            let relative = ((back - value) / value).abs();
            assert!(relative <= 1.0 / 64.0, "{value}: {back}");
        }
    }
}
