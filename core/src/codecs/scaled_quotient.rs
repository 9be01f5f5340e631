//! The rounding step the octahedral and RGBM codecs share: `floor(((2^bits - 1) numerator +
//! bias) / denominator)`, exactly, in 32-bit integers (bias `denominator / 2` rounds to
//! nearest, `denominator - 1` rounds up).

/// `floor(((2^bits - 1) numerator + bias) / denominator)`, exactly, for `numerator <=
/// denominator < 2^31` and `bias < denominator`.
///
/// The WGSL's algorithm (gbuffer-codegen's `wgsl::codecs::scaled_quotient`): `bits` steps of binary long division give `floor(2^bits
/// numerator / denominator)` and its remainder in 32-bit integers; taking `numerator` away and
/// adding `bias` moves the quotient by at most one either way.
#[inline(always)]
pub fn scaled_quotient(numerator: u32, denominator: u32, bias: u32, bits: u32) -> u32 {
    let whole = u32::from(numerator >= denominator);
    let mut quotient = whole;
    let mut remainder = numerator - whole * denominator;
    for _ in 0..bits {
        remainder <<= 1;
        let bit = u32::from(remainder >= denominator);
        quotient = (quotient << 1) | bit;
        remainder -= bit * denominator;
    }
    let up = u32::from(remainder + bias >= numerator + denominator);
    let down = u32::from(remainder + bias < numerator);
    quotient + up - down
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codecs::max_code;

    /// `floor(((2^bits - 1) numerator + bias) / denominator)` in 128-bit integers.
    fn scaled_quotient_reference(numerator: u32, denominator: u32, bias: u32, bits: u32) -> u32 {
        let product = u128::from(max_code(bits)) * u128::from(numerator) + u128::from(bias);
        (product / u128::from(denominator)) as u32
    }

    #[test]
    fn is_the_exact_floor() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::SmallRng::seed_from_u64(5);
        let largest = (1u32 << 31) - 1;
        let mut cases = vec![
            (0, 1, 0),
            (1, 1, 0),
            (largest, largest, largest - 1),
            (0, largest, largest / 2),
        ];
        for _ in 0..400_000 {
            // Denominators of every size, not only near 2^31.
            let denominator = rng.random_range(1..=largest) >> rng.random_range(0..31);
            let denominator = denominator.max(1);
            let numerator = rng.random_range(0..=denominator);
            let bias = rng.random_range(0..denominator);
            cases.push((numerator, denominator, bias));
        }
        for (numerator, denominator, bias) in cases {
            for bits in [1, 8, 12, 16] {
                assert_eq!(
                    scaled_quotient(numerator, denominator, bias, bits),
                    scaled_quotient_reference(numerator, denominator, bias, bits),
                    "{numerator} {denominator} {bias} {bits}"
                );
            }
        }
    }
}
