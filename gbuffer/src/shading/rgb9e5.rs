// Mirrors rgb9e5_mantissa, rgb9e5_encode and rgb9e5_decode of hdr.wgsl, on the same bits.

use glam::{UVec3, Vec3};

/// One channel's 9-bit mantissa for a shared biased exponent: round half up of
/// value * 2^(24 - exponent).
fn rgb9e5_mantissa(value: f32, shared_exponent: u32) -> u32 {
    let bits = value.to_bits();
    let exponent = bits >> 23;
    let significand = if exponent != 0 { (bits & 0x7f_ffff) | 0x80_0000 } else { bits & 0x7f_ffff };
    // As in the WGSL, u32 arithmetic wraps: a value larger than the one that set the exponent
    // gives a huge shift and 0, never a panic.
    let shift = (126 + shared_exponent).wrapping_sub(exponent.max(1));
    if shift > 24 {
        return 0;
    }
    (significand + (1 << (shift - 1))) >> shift
}

/// Shared-exponent HDR (EXT_texture_shared_exponent): 9-bit mantissas at bits 0, 9, 18 and a
/// 5-bit exponent (bias 15) at 27. Negatives and NaN give 0; values past 65408 saturate.
pub fn rgb9e5_encode(linear: Vec3) -> u32 {
    let clamped = linear.to_array().map(|channel| {
        let positive = if channel.to_bits() > 0x7f80_0000 { 0.0 } else { channel };
        positive.min(65408.0)
    });
    let largest = clamped[0].max(clamped[1]).max(clamped[2]);
    let mut shared_exponent = ((largest.to_bits() >> 23) as i32 - 111).max(0) as u32;
    if rgb9e5_mantissa(largest, shared_exponent) == 512 {
        shared_exponent += 1;
    }
    rgb9e5_mantissa(clamped[0], shared_exponent)
        | (rgb9e5_mantissa(clamped[1], shared_exponent) << 9)
        | (rgb9e5_mantissa(clamped[2], shared_exponent) << 18)
        | (shared_exponent << 27)
}

/// Shared-exponent decode: mantissa * 2^(exponent - 24), exact.
pub fn rgb9e5_decode(packed: u32) -> Vec3 {
    let mantissas = UVec3::new(packed, packed >> 9, packed >> 18) & UVec3::splat(0x1ff);
    let scale = f32::from_bits(((packed >> 27) + 103) << 23);
    mantissas.as_vec3() * scale
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_within_half_a_step_of_the_largest_channel() {
        for value in [0.0f32, 1e-9, 0.25, 1.0, 3.999, 511.0, 1000.0, 65408.0] {
            let colour = Vec3::new(value, value * 0.5, value * 0.01);
            let decoded = rgb9e5_decode(rgb9e5_encode(colour));
            // The step is 2^(exponent - 24) with the largest channel below 512 steps.
            let step = value / 256.0 + 2f32.powi(-24);
            assert!((decoded - colour).abs().max_element() <= step, "{colour} -> {decoded}");
        }
    }

    #[test]
    fn clamps_negatives_nan_and_overflow() {
        assert_eq!(rgb9e5_decode(rgb9e5_encode(Vec3::new(-1.0, f32::NAN, f32::INFINITY))), Vec3::new(0.0, 0.0, 65408.0));
        // 511.75 rounds the mantissa up to 512 at the first exponent: the exponent steps up.
        assert_eq!(rgb9e5_decode(rgb9e5_encode(Vec3::splat(511.75))), Vec3::splat(512.0));
    }
}
