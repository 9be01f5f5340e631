//! RGBM (Karis 2009): a colour in `[0, range]` in 32 bits laid out as rgba8, the colour over a
//! shared multiplier: `colour = rgb m range`. The multiplier `m = ceil(255 max(r, g, b) /
//! range) / 255` (at least 1/255) sits in bits 24-31, each channel `round(255 c / (m range))`
//! in bits 0-7, 8-15 and 16-23. The decode is f32 arithmetic.
//!
//! The exact encode works in integers: channels are clamped to `[0, range]` (NaN to 0) and
//! taken in multiples of `range 2^-22` (rounded down), and [`scaled_quotient`] rounds the
//! ratios; `range` has at most 16 significant bits ([`RgbmRange`]) so that its fixed point is
//! exact. The fast encode is Karis's f32 arithmetic.
//!
//! The shading library's `rgbm_encode` and `rgbm_decode` (module `hdr`, for rgba8 render
//! targets and textures) are this codec's WGSL (gbuffer-codegen's `wgsl::codecs::rgbm`): the exact encode's codes over 255, and the decode of
//! four unorm values, which a filtered texture sample also is.

use super::scaled_quotient::scaled_quotient;
use super::unorm::f32_from_unorm;
use super::{significand_and_exponent, Codec, Shape, F32_INFINITY_BITS};

/// The largest value an RGBM field stores: a positive float with at most 16 significant bits
/// (6, 8, 16, 51.5, ...), so that the exact encoding holds it without rounding.
#[derive(Clone, Copy, Debug)]
pub struct RgbmRange(f32);

impl RgbmRange {
    /// The range, if it is one an RGBM field can hold; otherwise why not.
    pub fn new(range: f32) -> Result<RgbmRange, String> {
        if !(range.is_finite() && range >= f32::MIN_POSITIVE) {
            return Err(format!(
                "an RGBM range must be a positive finite number, not {range}"
            ));
        }
        if range.to_bits() & 0xff != 0 {
            return Err(format!(
                "RGBM range {range} has more than 16 significant bits; the exact encoding needs \
                 it within 16 (6, 8, 16 or 51.5 are fine)"
            ));
        }
        Ok(RgbmRange(range))
    }

    /// The range written after `rgbm`, which it needs.
    pub fn from_range(range: Option<f32>) -> Result<RgbmRange, String> {
        let range = range.ok_or(
            "`rgbm` needs the largest value it stores: `rgbm(8)` in the derive, `range = 8.0` \
             in a layout file",
        )?;
        RgbmRange::new(range)
    }

    /// A range the derive has checked with [`RgbmRange::new`] (derived code builds its bit
    /// fields in constant expressions).
    #[doc(hidden)]
    pub const fn from_checked(range: f32) -> RgbmRange {
        RgbmRange(range)
    }

    /// The range as a float.
    pub fn get(self) -> f32 {
        self.0
    }
}

impl PartialEq for RgbmRange {
    fn eq(&self, other: &Self) -> bool {
        self.0.to_bits() == other.0.to_bits()
    }
}

impl Eq for RgbmRange {}

impl std::hash::Hash for RgbmRange {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.0.to_bits().hash(state);
    }
}

impl PartialOrd for RgbmRange {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for RgbmRange {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.to_bits().cmp(&other.0.to_bits())
    }
}

/// The exact encode of a colour in `[0, range]` (see the module's doc).
#[inline(always)]
pub fn rgbm_from_f32(rgb: [f32; 3], range: f32) -> u32 {
    let range_bits = range.to_bits();
    let (range_significand, range_exponent) = significand_and_exponent(range_bits);
    // range 2^(22 - floor(log2 range)): 2^22 and up, exact as the low significand bit is 0.
    let range_fixed = range_significand >> 1;
    let fixed = rgb.map(|value| {
        let bits = value.to_bits();
        let clamped = bits.min(range_bits) * u32::from(bits <= F32_INFINITY_BITS);
        let (significand, exponent) = significand_and_exponent(clamped);
        significand >> (range_exponent + 1 - exponent).min(31)
    });
    let largest = fixed[0].max(fixed[1]).max(fixed[2]);
    let multiplier = scaled_quotient(largest, range_fixed, range_fixed - 1, 8).max(1);
    let denominator = multiplier * range_fixed;
    let [red, green, blue] =
        fixed.map(|channel| scaled_quotient(255 * channel, denominator, denominator >> 1, 8));
    red | (green << 8) | (blue << 16) | (multiplier << 24)
}

/// The four unorm values of a word, as an rgba8 target or texture holds them.
#[inline]
pub fn unit_from_word(word: u32) -> [f32; 4] {
    [0, 8, 16, 24].map(|offset| f32_from_unorm((word >> offset) & 0xff, 8))
}

/// The decode of four unorm values: `rgb * (m * range)` (f32 arithmetic; an adapter's product
/// may differ from this in the last place).
#[inline]
pub fn rgbm_decode(unit: [f32; 4], range: f32) -> [f32; 3] {
    let scale = unit[3] * range;
    [unit[0] * scale, unit[1] * scale, unit[2] * scale]
}

/// The decode of a word: [`rgbm_decode`] of its codes over 255.
#[inline]
pub fn f32_from_rgbm(word: u32, range: f32) -> [f32; 3] {
    rgbm_decode(unit_from_word(word), range)
}

/// The RGBM codec. Its range is the encoding's parameter ([`RgbmRange`], always there).
pub const CODEC: Codec = Codec::vector(
    "rgbm",
    Shape::Fixed(32, 3, "a `Vec3`"),
    (
        |rgb, _, range| rgbm_from_f32(rgb, range.unwrap_or(1.0)),
        |word, _, range| f32_from_rgbm(word, range.unwrap_or(1.0)),
    ),
)
.with_fast_form();

#[cfg(test)]
mod tests {
    use super::*;

    /// The contract written another way: fixed point by scaling in f64 (exact) and flooring,
    /// the multiplier and channels rounded in 128-bit integers.
    fn rgbm_reference(rgb: [f32; 3], range: f32) -> u32 {
        let scale = 2f64.powi(22 - f64::from(range).log2().floor() as i32);
        let range_fixed = (f64::from(range) * scale) as u128;
        let fixed = rgb.map(|value| {
            let value = if value.is_nan() {
                0.0
            } else {
                f64::from(value).clamp(0.0, f64::from(range))
            };
            (value * scale).floor() as u128
        });
        let largest = fixed[0].max(fixed[1]).max(fixed[2]);
        let multiplier = (255 * largest).div_ceil(range_fixed).max(1);
        let denominator = multiplier * range_fixed;
        let [red, green, blue] =
            fixed.map(|channel| ((255 * 255 * channel + denominator / 2) / denominator) as u32);
        red | (green << 8) | (blue << 16) | ((multiplier as u32) << 24)
    }

    #[test]
    fn follows_its_contract_within_its_bound() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::SmallRng::seed_from_u64(13);
        for range in [1.0f32, 6.0, 8.0, 51.5, 65535.0] {
            let mut values: Vec<f32> = vec![
                0.0,
                -0.0,
                range,
                range * 2.0,
                -1.0,
                f32::NAN,
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::MAX,
                1e-30,
                1e-45,
            ];
            // Each multiplier step k range / 255 and its neighbours.
            for k in 0..=255u32 {
                let step = (f64::from(k) * f64::from(range) / 255.0) as f32;
                values.extend([
                    step,
                    f32::from_bits(step.to_bits().saturating_sub(1)),
                    f32::from_bits(step.to_bits() + 1),
                ]);
            }
            let mut cases: Vec<[f32; 3]> = values.iter().map(|&v| [v, v * 0.5, v * 0.25]).collect();
            for _ in 0..100_000 {
                cases.push([0; 3].map(|_| rng.random_range(0.0..range)));
                cases.push([0; 3].map(|_| values[rng.random_range(0..values.len())]));
            }
            for rgb in cases {
                let word = rgbm_from_f32(rgb, range);
                assert_eq!(word, rgbm_reference(rgb, range), "{rgb:?} in range {range}");
                let decoded = f32_from_rgbm(word, range);
                let multiplier = f64::from(word >> 24) / 255.0;
                // Half a code of the channel's step, and the fixed point's 2^-22 range.
                let bound =
                    0.5 / 255.0 * multiplier * f64::from(range) + f64::from(range) * 2f64.powi(-21);
                for (value, decoded) in rgb.iter().zip(decoded) {
                    if value.is_finite() && (0.0..=range).contains(value) {
                        let error = (f64::from(*value) - f64::from(decoded)).abs();
                        assert!(
                            error <= bound * (1.0 + 1e-6),
                            "{rgb:?} -> {decoded} in range {range}: {error} > {bound}"
                        );
                    }
                }
            }
        }
    }
}
