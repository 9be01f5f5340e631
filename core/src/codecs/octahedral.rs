//! Octahedral normals (Cigolle et al. 2014, "A Survey of Efficient Representations for
//! Independent Unit Vectors"): a unit `vec3` as two coordinates of `n / 2` bits, x in the low
//! half. The map: `p = n.xy / (|x| + |y| + |z|)`, folded for `z < 0` to `(1 - |p.yx|)
//! sign_not_zero(p)`, each coordinate mapped to `[0, 1]` and rounded to unorm (half up). The
//! decode unfolds the lower hemisphere (Stubbe's branch-free form) and normalizes. 2 to 32 bits,
//! even.
//!
//! The exact encode works in integers: the magnitudes are aligned to the largest one's
//! exponent with 28 bits below its leading one (smaller components lose the bits under that,
//! and a component 2^31 times smaller than the largest counts as 0), every coordinate is a
//! ratio of their integer sums, and [`scaled_quotient`] rounds it. NaN components count as 0
//! and so does the zero vector, which encodes as +z; `-0.0` is not negative. The fast encode is
//! the map in f32 arithmetic ([`octahedral_fold`]), the adapter's division and rounding.
//!
//! The shading library's `octahedral_encode` and `octahedral_decode` (module `normals`) are
//! this map's two halves, as the WGSL back end writes them (gbuffer-codegen's
//! `wgsl::codecs::octahedral::map_functions`).

use super::scaled_quotient::scaled_quotient;
use super::unorm::f32_from_unorm;
use super::{max_code, significand_and_exponent, Codec, Shape, F32_INFINITY_BITS};

/// The largest angle, in degrees, between a unit normal and its `bits`-per-coordinate
/// octahedral round trip: `sqrt(18)` half-steps of a coordinate (proven in
/// `integration-tests/tests/shading_physics.rs` and `convert`'s tests). The bound the solvers
/// hold a normal's precision to.
pub fn max_error_degrees(bits: u32) -> f64 {
    (18f64.sqrt() * (1.0 / f64::from(max_code(bits)))).to_degrees()
}

/// The exact encode at `bits` per coordinate (1 to 16), x in the low bits.
#[inline(always)]
pub fn octahedral_from_f32(normal: [f32; 3], bits: u32) -> u32 {
    let magnitude = normal.map(|value| {
        let magnitude = value.to_bits() & 0x7fff_ffff;
        magnitude * u32::from(magnitude <= F32_INFINITY_BITS)
    });
    let negative =
        [0, 1, 2].map(|axis| (normal[axis].to_bits() >> 31) & u32::from(magnitude[axis] != 0));
    let parts = magnitude.map(significand_and_exponent);
    let largest = parts[0].1.max(parts[1].1).max(parts[2].1);
    let [x, y, z] =
        parts.map(|(significand, exponent)| (significand << 4) >> (largest - exponent).min(31));
    let sum = x + y + z;
    // The zero vector is +z.
    let z = z + u32::from(sum == 0);
    let sum = x + y + z;
    // The folded coordinates: |p.y| and |p.x| taken from 1, i.e. (x + z, y + z) over the sum.
    let lower = negative[2];
    let (along_x, along_y) = (x + lower * z, y + lower * z);
    let code = |along: u32, negative: u32| {
        // (1 +- along / sum) / 2 as numerator over 2 sum, rounded half up.
        let numerator = if negative == 1 {
            sum - along
        } else {
            sum + along
        };
        scaled_quotient(numerator, 2 * sum, sum, bits)
    };
    code(along_x, negative[0]) | (code(along_y, negative[1]) << bits)
}

/// The map's first half in f32 arithmetic, as the fast WGSL computes it: a non-zero vector to
/// `[-1, 1]^2`, the lower hemisphere folded over the diagonals.
#[inline]
pub fn octahedral_fold(normal: [f32; 3]) -> [f32; 2] {
    let [x, y, z] = normal;
    let sum = x.abs() + y.abs() + z.abs();
    let projected = [x / sum, y / sum];
    let sign_not_zero = projected.map(|value| if value >= 0.0 { 1.0 } else { -1.0 });
    if z < 0.0 {
        [
            (1.0 - projected[1].abs()) * sign_not_zero[0],
            (1.0 - projected[0].abs()) * sign_not_zero[1],
        ]
    } else {
        projected
    }
}

/// The map's second half: `[-1, 1]^2` back to a unit vector, the lower hemisphere unfolded
/// (Stubbe's branch-free form) and normalized, in f32 arithmetic (an adapter's `normalize` is
/// within a few ulp of this).
#[inline]
pub fn octahedral_unfold(folded: [f32; 2]) -> [f32; 3] {
    let [x, y] = folded;
    let z = 1.0 - x.abs() - y.abs();
    let fold = (-z).max(0.0);
    let unfold = |value: f32| {
        if value >= 0.0 {
            value - fold
        } else {
            value + fold
        }
    };
    let (x, y) = (unfold(x), unfold(y));
    let length = (x * x + y * y + z * z).sqrt();
    [x / length, y / length, z / length]
}

/// The decode at `bits` per coordinate: the codes back to `[-1, 1]`, then
/// [`octahedral_unfold`].
#[inline]
pub fn f32_from_octahedral(code: u32, bits: u32) -> [f32; 3] {
    let coordinate = |code: u32| f32_from_unorm(code & max_code(bits), bits) * 2.0 - 1.0;
    octahedral_unfold([coordinate(code), coordinate(code >> bits)])
}

/// The octahedral codec: `n / 2` bits a coordinate.
pub const CODEC: Codec = Codec::vector(
    "octahedral",
    Shape::Coordinates,
    (
        |normal, each, _| octahedral_from_f32(normal, each),
        |code, each, _| f32_from_octahedral(code, each),
    ),
)
.with_fast_form();

/// The directions where an octahedral encoding is hardest to get right, for tests of an
/// implementation (this codec's, a shader's): unit vectors at the map's poles, on its seam (the
/// equator, where the lower hemisphere folds) and just beside it, on its diagonals, with signed
/// zeros; and vectors that are not unit: the zero vector, tiny, huge, infinite and NaN ones.
pub fn edge_directions() -> Vec<[f32; 3]> {
    let root2 = std::f32::consts::FRAC_1_SQRT_2;
    let root3 = 1.0 / 3f32.sqrt();
    let mut edges = vec![
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [-0.0, -0.0, -1.0],
        [0.0, 0.0, -0.0],
        [0.0, 0.0, 0.0],
        [f32::NAN, 0.0, 1.0],
        [f32::NAN, f32::NAN, f32::NAN],
        [f32::INFINITY, 0.0, 0.0],
        [f32::INFINITY, f32::NEG_INFINITY, 1.0],
        [1e-40, -1e-42, 0.0],
        [3.0, 4.0, -12.0],
        [1.0, 1e-30, -1e-30],
    ];
    for x in [-1.0f32, -0.0, 0.0, 1.0] {
        for y in [-1.0f32, -0.0, 0.0, 1.0] {
            for z in [-1.0f32, -0.0, 0.0, 1.0] {
                edges.push([x, y, z]);
                edges.push([x * root2, y * root2, z]);
                edges.push([x * root3, y * root3, z * root3]);
                // Just beside the equator (the fold's seam).
                edges.push([x * root2, y * root2, z * 1e-7]);
            }
        }
    }
    edges
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The contract written another way: the magnitudes scaled by a power of two in f64 (exact)
    /// and floored, the ratios rounded in 128-bit integers, the hemisphere and sign rules
    /// spelled out.
    fn octahedral_reference(normal: [f32; 3], bits: u32) -> u32 {
        let magnitude = normal.map(|value| {
            if value.is_nan() {
                0.0
            } else {
                f64::from(value.abs())
            }
        });
        let exponent = normal.map(|value| {
            let field = (value.to_bits() >> 23) & 0xff;
            if value.is_nan() {
                1
            } else {
                field.max(1)
            }
        });
        let largest = exponent.iter().copied().max().unwrap_or(1) as i32;
        // Leading bit of the largest at bit 27: scale by 2^(27 - (largest - 127)).
        let scale = 2f64.powi(27 - (largest - 127));
        let [x, y, z] = magnitude.map(|value| {
            if value.is_infinite() {
                1u128 << 27 // infinity reads as 2^128, the largest exponent
            } else {
                (value * scale).floor() as u128
            }
        });
        let z = if x + y + z == 0 { 1 } else { z };
        let sum = x + y + z;
        let negative = |value: f32| value < 0.0;
        let (along_x, along_y) = if negative(normal[2]) {
            (x + z, y + z)
        } else {
            (x, y)
        };
        let code = |along: u128, negative: bool| {
            let numerator = if negative { sum - along } else { sum + along };
            ((u128::from(max_code(bits)) * numerator + sum) / (2 * sum)) as u32
        };
        code(along_x, negative(normal[0])) | (code(along_y, negative(normal[1])) << bits)
    }

    /// The angle between two vectors in radians, from their cross and dot products (accurate
    /// for small angles, where `acos` of the dot product is not).
    fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
        let cross = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        cross.iter().map(|c| c * c).sum::<f64>().sqrt().atan2(dot)
    }

    #[test]
    fn follows_its_contract_and_the_map() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::SmallRng::seed_from_u64(9);
        let mut vectors = edge_directions();
        for _ in 0..200_000 {
            let v = [0; 3].map(|_| rng.random_range(-1.0f32..1.0));
            vectors.push(v);
            // Raw bits too: any exponents, signs, NaNs.
            vectors.push([0; 3].map(|_| f32::from_bits(rng.random())));
        }
        for bits in [1, 2, 8, 12, 16] {
            let mut largest_angle = 0f64;
            for &v in &vectors {
                let code = octahedral_from_f32(v, bits);
                assert_eq!(code, octahedral_reference(v, bits), "{v:?} at {bits} bits");
                let length = v.iter().map(|c| f64::from(*c).powi(2)).sum::<f64>().sqrt();
                if !(length.is_finite() && length > 1e-30 && bits >= 8) {
                    continue;
                }
                // The round trip stays within the quantisation bound: sqrt(18) half-steps.
                let decoded = f32_from_octahedral(code, bits).map(f64::from);
                largest_angle = largest_angle.max(angle_between(decoded, v.map(f64::from)));
            }
            if bits >= 8 {
                let bound = 18f64.sqrt() / f64::from(max_code(bits)) + 1e-6;
                assert!(
                    largest_angle <= bound,
                    "{bits} bits: {largest_angle} > {bound}"
                );
            }
        }
        // The poles and the zero vector: +z is the centre, -z the corners.
        let centre = (1 << 15) | (1 << 31);
        assert_eq!(octahedral_from_f32([0.0, 0.0, 1.0], 16), centre);
        assert_eq!(octahedral_from_f32([0.0, 0.0, 0.0], 16), centre);
        assert_eq!(octahedral_from_f32([0.0, 0.0, -1.0], 16), 0xffff_ffff);
        assert_eq!(f32_from_octahedral(0xffff_ffff, 16), [0.0, 0.0, -1.0]);
        assert_eq!(octahedral_from_f32([-0.0, -0.0, -1.0], 16), 0xffff_ffff);
        assert_eq!(octahedral_from_f32([-1.0, -0.0, -0.0], 16), 0x8000_0000);
    }

    /// The f32 map and its inverse come back to the direction (away from the zero vector).
    #[test]
    fn the_f32_map_inverts() {
        for v in edge_directions() {
            let length = v.iter().map(|c| c * c).sum::<f32>().sqrt();
            if !(length.is_finite() && length > 1e-20) {
                continue;
            }
            let unit = v.map(|c| c / length);
            let back = octahedral_unfold(octahedral_fold(unit));
            let angle = angle_between(back.map(f64::from), unit.map(f64::from));
            assert!(angle < 1e-6, "{v:?}: {back:?}");
        }
    }
}
