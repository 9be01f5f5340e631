//! Bit-exact conversions between shader values and channel codes.
//!
//! These are the CPU mirrors of the WGSL helpers in `gbuffer_codegen::emit::wgsl`, so that a G-buffer
//! packed on the CPU and on any conforming adapter holds the same bits: the encoders run the
//! WGSL's own algorithms (integer operations on the float's bits, no branch), and the tests
//! check them on every f32 against references written the plain way (the exact formula in f64
//! for unorm, IEEE's rounding for half, a branching bit-level rounding for the small floats).
//!
//! The rules, per encoding:
//! - unorm: `floor(0.5 + (2^n - 1) * clamp(x, 0, 1))`, evaluated exactly; NaN gives 0.
//! - half and the unsigned small floats of `r11f_g11f_b10f`: round to nearest even, denormals
//!   kept, values past the largest finite value give that value (never infinity), NaN gives 0;
//!   the unsigned floats store negatives as 0, half keeps the sign.
//! - r32f: the f32 bits unchanged.
//! - integers: clamped to the channel's range.

use crate::format::{Channel, ChannelEncoding, Format};

/// The bits of +infinity as f32; a magnitude above it is a NaN.
const F32_INFINITY_BITS: u32 = 0x7f80_0000;
/// The bits of 1.0 as f32.
const F32_ONE_BITS: u32 = 0x3f80_0000;
/// The largest code of an unsigned integer of `bits` bits (`bits` from 1 to 32).
#[inline]
pub fn max_code(bits: u32) -> u32 {
    u32::MAX >> (32 - bits)
}

/// Unsigned normalized encode: `floor(0.5 + (2^bits - 1) * clamp(value, 0, 1))`, exact; NaN
/// gives 0. Valid for `bits` from 1 to 23 (past that an f32 has no more bits to give).
///
/// The WGSL's algorithm (`PREFIX_<lanes>_to_unorm`): with `value = significand *
/// 2^-(shift + bits)` and `2^bits - 1 = max_code`, the code is `(significand - significand /
/// 2^bits + 2^(shift - 1)) >> shift`, where rounding `significand / 2^bits` up changes no
/// result. NaN and negatives (as unsigned integers above infinity's bits) clamp to 0, values
/// from 1.0 up to 1.0; past a shift of 26 every code is 0, as it is at 26.
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

/// Signed normalized encode, GL's formula `round(clamp(value, -1, 1) * (2^(bits - 1) - 1))`
/// with halves rounded away from zero, exact; the code is the `bits`-bit two's complement. NaN
/// gives 0. Valid for `bits` from 2 to 24.
///
/// The magnitude is [`unorm_from_f32`] of `|value|` at `bits - 1` bits (the same formula), and
/// the sign is applied to the code, so the encoding is symmetric about zero.
#[inline(always)]
pub fn snorm_from_f32(value: f32, bits: u32) -> u32 {
    // NaN's magnitude encodes as 0, whatever its sign.
    let magnitude = unorm_from_f32(f32::from_bits(value.to_bits() & 0x7fff_ffff), bits - 1);
    if value.to_bits() >> 31 == 1 {
        magnitude.wrapping_neg() & max_code(bits)
    } else {
        magnitude
    }
}

/// Signed normalized decode, GL's formula `max(code / (2^(bits - 1) - 1), -1)`: the most
/// negative code decodes to -1, as the next one does.
#[inline]
pub fn f32_from_snorm(code: u32, bits: u32) -> f32 {
    (i32_from_sint(code, bits) as f32 / (max_code(bits) >> 1) as f32).max(-1.0)
}

/// The largest value rgb9e5 holds: (511 / 512) 2^16.
const RGB9E5_MAX_BITS: u32 = 0x477f_8000;

/// Shared-exponent rgb9e5 (EXT_texture_shared_exponent), its algorithm evaluated exactly: each
/// channel clamped to [0, 65408] (NaN to 0); the shared exponent `max(-16, floor(log2(max))) +
/// 16`, one more where the largest channel rounds up to 512; each mantissa `floor(channel /
/// 2^(exponent - 24) + 0.5)`. Red in bits 0-8, green 9-17, blue 18-26, the exponent 27-31.
///
/// On the float's bits: `floor(log2)` is the exponent field, and rounding a value scaled by a
/// power of two is a shift of its significand with half its last place added.
#[inline(always)]
pub fn rgb9e5_from_f32(rgb: [f32; 3]) -> u32 {
    // Non-negative floats order like their bits; NaN and negatives lie above infinity's.
    let clamped = rgb.map(|value| {
        let bits = value.to_bits();
        if bits > F32_INFINITY_BITS {
            0
        } else {
            bits.min(RGB9E5_MAX_BITS)
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

/// `floor(((2^bits - 1) numerator + bias) / denominator)`, exactly, for `numerator <=
/// denominator < 2^31` and `bias < denominator`: the rounding step of the octahedral and RGBM
/// encodings (bias `denominator / 2` rounds to nearest, `denominator - 1` rounds up).
///
/// The WGSL's algorithm (`PREFIX_<lanes>_scaled_quotient`): `bits` steps of binary long
/// division give `floor(2^bits numerator / denominator)` and its remainder in 32-bit integers;
/// taking `numerator` away and adding `bias` moves the quotient by at most one either way.
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

/// A float's significand (the implicit bit included) and its exponent field (denormals read
/// as exponent 1, as their value is), for a non-negative float given as bits.
#[inline(always)]
fn significand_and_exponent(bits: u32) -> (u32, u32) {
    let exponent = bits >> 23;
    (
        (bits & 0x7f_ffff) | (u32::from(exponent != 0) << 23),
        exponent.max(1),
    )
}

/// Octahedral encode (Cigolle et al. 2014, "A Survey of Efficient Representations for
/// Independent Unit Vectors"): `p = n.xy / (|x| + |y| + |z|)`, folded for `z < 0` to `(1 -
/// |p.yx|) * sign_not_zero(p)`, each coordinate mapped to `[0, 1]` and rounded to
/// `bits`-bit unorm (half up), x in the low bits. Evaluated exactly: the magnitudes are
/// aligned to the largest one's exponent with 28 bits below its leading one (smaller
/// components lose the bits under that, and a component 2^31 times smaller than the largest
/// counts as 0), every coordinate is a ratio of their integer sums, and
/// [`scaled_quotient`] rounds it. NaN components count as 0 and so does the zero vector,
/// which encodes as +z. `-0.0` is not negative: sign_not_zero gives +1. `bits` from 1 to 16.
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

/// Octahedral decode: the coordinates back to `[-1, 1]`, the lower hemisphere unfolded
/// (Stubbe's branch-free form) and the vector normalized, in f32 arithmetic (an adapter's
/// `normalize` is within a few ulp of this).
#[inline]
pub fn f32_from_octahedral(code: u32, bits: u32) -> [f32; 3] {
    let coordinate = |code: u32| f32_from_unorm(code & max_code(bits), bits) * 2.0 - 1.0;
    let (x, y) = (coordinate(code), coordinate(code >> bits));
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

/// RGBM encode (Karis 2009) of a colour in `[0, range]`: the multiplier `m = ceil(255
/// max(r, g, b) / range) / 255` (at least 1/255) in bits 24-31, and each channel
/// `round(255 c / (m range))` in bits 0-7, 8-15 and 16-23. Evaluated exactly: channels are
/// clamped to `[0, range]` (NaN to 0) and taken in multiples of `range 2^-22` (rounded
/// down), and [`scaled_quotient`] rounds the ratios. `range` has at most 16 significant bits
/// ([`crate::encoding::RgbmRange`]).
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

/// RGBM decode: `rgb * m * range`, each unorm code divided by 255 (f32 arithmetic; an
/// adapter's product may differ from this in the last place).
#[inline]
pub fn f32_from_rgbm(word: u32, range: f32) -> [f32; 3] {
    let scale = f32_from_unorm(word >> 24, 8) * range;
    [0, 8, 16].map(|offset| f32_from_unorm((word >> offset) & 0xff, 8) * scale)
}

/// The largest finite code of a float with a 5-bit exponent and `mantissa_bits` of mantissa.
#[inline]
pub fn small_float_max_code(mantissa_bits: u32) -> u32 {
    (30 << mantissa_bits) | ((1 << mantissa_bits) - 1)
}

/// Rounds a non-negative f32, given as its bits with the sign bit clear, to a float with a
/// 5-bit exponent (bias 15) and `mantissa_bits` of mantissa: round to nearest even, denormals
/// kept, saturating at the largest finite code. NaN gives 0.
///
/// The WGSL's algorithm (`PREFIX_<lanes>_round_to_<name>`): normal results round the f32 bits
/// in integer arithmetic, rebiasing the exponent in the same add (a carry moves into the
/// exponent, as it should); denormal results scale the value by a power of two, exactly, and
/// round it to nearest even. Each path gives at least the code where the other applies (under
/// 2^-14 the rebias wraps around; from 2^-14 up the scaled value is at least the code), so the
/// smaller is the code. NaN scales to NaN, which converts to 0.
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
    let denormal = ((scaled + 8_388_608.0) - 8_388_608.0) as u32;
    normal
        .min(denormal)
        .min(small_float_max_code(mantissa_bits))
}

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

/// f32 to an unsigned small float (`mantissa_bits` 6 for r11f and g11f, 5 for b10f).
/// Negatives and NaN give 0 (as unsigned integers, both lie above infinity's bits).
#[inline(always)]
pub fn unsigned_float_from_f32(value: f32, mantissa_bits: u32) -> u32 {
    let value_bits = value.to_bits();
    let code = small_float_from_magnitude(value_bits, mantissa_bits);
    if value_bits > F32_INFINITY_BITS {
        0
    } else {
        code
    }
}

/// Decodes an unsigned small float code, exactly. Exponent 31 decodes to infinity or NaN as
/// the format defines (the encoders never produce it).
#[inline]
pub fn f32_from_small_float(code: u32, mantissa_bits: u32) -> f32 {
    let exponent = code >> mantissa_bits;
    let mantissa = code & ((1 << mantissa_bits) - 1);
    if exponent == 0 {
        // Denormal: mantissa * 2^-(14 + mantissa_bits); the power of two is exact.
        return mantissa as f32 * f32::from_bits((113 - mantissa_bits) << 23);
    }
    let f32_exponent = if exponent == 31 { 255 } else { exponent + 112 };
    f32::from_bits((f32_exponent << 23) | (mantissa << (23 - mantissa_bits)))
}

/// Decodes the 16-bit code of an IEEE binary16, exactly.
#[inline]
pub fn f32_from_half(code: u32) -> f32 {
    let magnitude = f32_from_small_float(code & 0x7fff, 10);
    f32::from_bits(magnitude.to_bits() | ((code & 0x8000) << 16))
}

/// Clamps an unsigned integer to `bits` bits.
#[inline]
pub fn uint_saturate(value: u32, bits: u32) -> u32 {
    value.min(max_code(bits))
}

/// Clamps a signed integer to the range of `bits` bits and returns its two's complement code.
#[inline]
pub fn sint_saturate(value: i32, bits: u32) -> u32 {
    let highest = (max_code(bits) >> 1) as i32;
    (value.clamp(-highest - 1, highest) as u32) & max_code(bits)
}

/// Sign-extends a `bits`-bit two's complement code.
#[inline]
pub fn i32_from_sint(code: u32, bits: u32) -> i32 {
    ((code << (32 - bits)) as i32) >> (32 - bits)
}

/// A scalar a field can hold: f32, u32 or i32. Each converts to and from any channel; the
/// layout check pairs float fields with float and unorm formats and integer fields with their
/// integer formats, and the other pairings saturate as Rust's `as` does.
///
/// The implementations are always inlined: with the channel known at compile time (as derived
/// code has it) the match on its encoding disappears.
pub trait Scalar: Copy + Default {
    /// The channel's code, in its low bits.
    fn encode(self, channel: Channel) -> u32;
    /// The value of a channel's code.
    fn decode(code: u32, channel: Channel) -> Self;
}

impl Scalar for f32 {
    #[inline(always)]
    fn encode(self, channel: Channel) -> u32 {
        match channel.encoding {
            ChannelEncoding::Unorm => unorm_from_f32(self, channel.bits),
            ChannelEncoding::Float32 => self.to_bits(),
            ChannelEncoding::Half => half_from_f32(self),
            ChannelEncoding::UnsignedFloat { mantissa_bits } => {
                unsigned_float_from_f32(self, mantissa_bits)
            }
            ChannelEncoding::Uint => uint_saturate(self as u32, channel.bits),
            ChannelEncoding::Sint => sint_saturate(self as i32, channel.bits),
        }
    }

    #[inline(always)]
    fn decode(code: u32, channel: Channel) -> f32 {
        match channel.encoding {
            ChannelEncoding::Unorm => f32_from_unorm(code, channel.bits),
            ChannelEncoding::Float32 => f32::from_bits(code),
            ChannelEncoding::Half => f32_from_half(code),
            ChannelEncoding::UnsignedFloat { mantissa_bits } => {
                f32_from_small_float(code, mantissa_bits)
            }
            ChannelEncoding::Uint => code as f32,
            ChannelEncoding::Sint => i32_from_sint(code, channel.bits) as f32,
        }
    }
}

impl Scalar for u32 {
    #[inline(always)]
    fn encode(self, channel: Channel) -> u32 {
        match channel.encoding {
            ChannelEncoding::Uint => uint_saturate(self, channel.bits),
            ChannelEncoding::Sint => sint_saturate(self.min(i32::MAX as u32) as i32, channel.bits),
            _ => (self as f32).encode(channel),
        }
    }

    #[inline(always)]
    fn decode(code: u32, channel: Channel) -> u32 {
        match channel.encoding {
            ChannelEncoding::Uint => code,
            ChannelEncoding::Sint => i32_from_sint(code, channel.bits).max(0) as u32,
            _ => f32::decode(code, channel) as u32,
        }
    }
}

impl Scalar for i32 {
    #[inline(always)]
    fn encode(self, channel: Channel) -> u32 {
        match channel.encoding {
            ChannelEncoding::Sint => sint_saturate(self, channel.bits),
            ChannelEncoding::Uint => uint_saturate(self.max(0) as u32, channel.bits),
            _ => (self as f32).encode(channel),
        }
    }

    #[inline(always)]
    fn decode(code: u32, channel: Channel) -> i32 {
        match channel.encoding {
            ChannelEncoding::Sint => i32_from_sint(code, channel.bits),
            ChannelEncoding::Uint => code.min(i32::MAX as u32) as i32,
            _ => f32::decode(code, channel) as i32,
        }
    }
}

impl Format {
    /// Packs up to four channel values into the format's word. Channels the format lacks are
    /// ignored; a field with fewer components passes zeros, which encode as zero bits.
    // Always inlined: derived code calls it with a constant format, and inlined the channel
    // loop unrolls and each channel's conversion is chosen at compile time (several times
    // faster than a call that matches on the format at run time).
    #[inline(always)]
    pub fn encode<S: Scalar>(self, values: [S; 4]) -> u32 {
        let mut word = 0;
        for (channel, value) in self.channels().iter().zip(values) {
            word |= value.encode(*channel) << channel.offset;
        }
        word
    }

    /// Unpacks a word into its channel values; channels the format lacks read as zero.
    // Always inlined, as `encode`.
    #[inline(always)]
    pub fn decode<S: Scalar>(self, word: u32) -> [S; 4] {
        let mut values = [S::default(); 4];
        for (value, channel) in values.iter_mut().zip(self.channels()) {
            *value = S::decode((word >> channel.offset) & channel.mask(), *channel);
        }
        values
    }
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

    /// The unorm formula evaluated plainly, in f64: exact for every f32 (the product has at
    /// most 40 significant bits, and adding one half cannot round up to the next integer: a
    /// product within 2^-41 of a half-integer would need bits the value does not have).
    fn unorm_reference(value: f32, bits: u32) -> u32 {
        (f64::from(value).clamp(0.0, 1.0) * f64::from(max_code(bits)) + 0.5) as u32
    }

    /// Snorm evaluated plainly, in f64 (exact, as for unorm), halves rounded away from zero.
    fn snorm_reference(value: f32, bits: u32) -> u32 {
        if value.is_nan() {
            return 0;
        }
        let scaled = f64::from(value).clamp(-1.0, 1.0) * f64::from(max_code(bits) >> 1);
        let rounded = (scaled.abs() + 0.5).floor().copysign(scaled) as i32;
        (rounded as u32) & max_code(bits)
    }

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

    /// Small-float rounding written the branching way, bit by bit: the reference the
    /// branch-free algorithm is checked against on every f32.
    fn small_float_by_branches(magnitude_bits: u32, mantissa_bits: u32) -> u32 {
        if magnitude_bits > F32_INFINITY_BITS {
            return 0;
        }
        let exponent = magnitude_bits >> 23;
        let significand = (magnitude_bits & 0x7f_ffff) | 0x80_0000;
        // A normal result (2^-14 and up) drops 23 - mantissa_bits bits; a denormal one more,
        // and past 25 the value is under half the smallest denormal.
        let (exponent_part, extra) = if exponent >= 113 {
            ((exponent - 113) << mantissa_bits, 0)
        } else if exponent == 0 {
            return 0;
        } else {
            (0, 113 - exponent)
        };
        let shift = (23 - mantissa_bits + extra).min(25);
        let kept = significand >> shift;
        let remainder = significand & ((1 << shift) - 1);
        let halfway = 1 << (shift - 1);
        let round_up = remainder > halfway || (remainder == halfway && kept & 1 == 1);
        (exponent_part + kept + u32::from(round_up)).min(small_float_max_code(mantissa_bits))
    }

    /// Runs `check` on every bit pattern in `patterns`, split over two threads; the first
    /// failure, if any.
    fn every_pattern(
        patterns: std::ops::RangeInclusive<u32>,
        check: impl Fn(u32) -> Option<String> + Sync,
    ) -> Option<String> {
        let (first, last) = (*patterns.start(), *patterns.end());
        let middle = first + (last - first) / 2;
        std::thread::scope(|scope| {
            let workers: Vec<_> = [first..=middle, middle + 1..=last]
                .into_iter()
                .map(|half| scope.spawn(|| half.into_iter().find_map(&check)))
                .collect();
            workers
                .into_iter()
                .find_map(|worker| worker.join().expect("a worker finishes"))
        })
    }

    #[test]
    fn the_unorm_and_snorm_algorithms_are_exact_for_every_f32() {
        let failure = every_pattern(0..=u32::MAX, |value_bits| {
            let value = f32::from_bits(value_bits);
            let unorm = [2, 8, 10, 16, 20, 23].iter().find_map(|&bits| {
                let (got, want) = (unorm_from_f32(value, bits), unorm_reference(value, bits));
                (got != want).then(|| {
                    format!("{value:e} ({value_bits:#010x}) as unorm{bits}: {got}, exact {want}")
                })
            });
            unorm.or_else(|| {
                [8, 16, 24].iter().find_map(|&bits| {
                    let (got, want) = (snorm_from_f32(value, bits), snorm_reference(value, bits));
                    (got != want).then(|| {
                        format!(
                            "{value:e} ({value_bits:#010x}) as snorm{bits}: {got}, exact {want}"
                        )
                    })
                })
            })
        });
        assert_eq!(failure, None);
    }

    /// On every f32: half is IEEE's rounding (the half crate's, which overflows to infinity
    /// where ours saturates at the largest finite value and stores NaN as 0), and the unsigned
    /// floats are the branching reference's.
    #[test]
    fn small_floats_round_every_f32_as_the_references_do() {
        let failure = every_pattern(0..=u32::MAX, |value_bits| {
            let value = f32::from_bits(value_bits);
            let ieee = u32::from(half::f16::from_f32(value).to_bits());
            let want = if value.is_nan() {
                0
            } else if ieee & 0x7fff == 0x7c00 {
                (ieee & 0x8000) | 0x7bff
            } else {
                ieee
            };
            let got = half_from_f32(value);
            if got != want {
                return Some(format!(
                    "half of {value:e} ({value_bits:#010x}): {got:#06x}, IEEE {want:#06x}"
                ));
            }
            [6, 5].iter().find_map(|&mantissa_bits| {
                let got = unsigned_float_from_f32(value, mantissa_bits);
                let want = if value_bits >> 31 == 1 {
                    0
                } else {
                    small_float_by_branches(value_bits, mantissa_bits)
                };
                (got != want).then(|| {
                    format!("{value:e} with {mantissa_bits} mantissa bits: {got:#x}, reference {want:#x}")
                })
            })
        });
        assert_eq!(failure, None);
    }

    /// The WGSL decodes r11f_g11f_b10f by widening each code into a half (`unpack2x16float`):
    /// every code decodes to the mirror's value that way.
    #[test]
    fn unsigned_floats_widened_into_halves_decode_as_the_mirror_does() {
        for (mantissa_bits, widen) in [(6, 4), (5, 5)] {
            for code in 0..(32u32 << mantissa_bits) {
                let half = half::f16::from_bits((code << widen) as u16).to_f32();
                let mirror = f32_from_small_float(code, mantissa_bits);
                assert!(
                    half.to_bits() == mirror.to_bits() || (half.is_nan() && mirror.is_nan()),
                    "code {code:#x} with {mantissa_bits} mantissa bits: {half:e}, mirror {mirror:e}"
                );
            }
        }
    }

    #[test]
    fn snorm_is_symmetric_and_decodes_the_most_negative_code_to_minus_one() {
        for bits in [2, 4, 8, 12, 16, 24] {
            let highest = max_code(bits) >> 1;
            for (value, expected) in [
                (1.0f32, highest),
                (-1.0, highest.wrapping_neg() & max_code(bits)),
                (-0.0, 0),
                (f32::NAN, 0),
                (-f32::NAN, 0),
                (f32::NEG_INFINITY, highest.wrapping_neg() & max_code(bits)),
            ] {
                assert_eq!(
                    snorm_from_f32(value, bits),
                    expected,
                    "{value} at {bits} bits"
                );
            }
            assert_eq!(f32_from_snorm(highest + 1, bits), -1.0);
            assert_eq!(f32_from_snorm(highest, bits), 1.0);
            for code in [0, 1, highest / 2, highest] {
                let negative = code.wrapping_neg() & max_code(bits);
                assert_eq!(f32_from_snorm(negative, bits), -f32_from_snorm(code, bits));
                assert_eq!(snorm_from_f32(f32_from_snorm(code, bits), bits), code);
            }
        }
    }

    /// rgb9e5 against the extension's algorithm: edge cases, the exponent carry beside every
    /// power of two, the largest value, and a million random triples.
    #[test]
    fn rgb9e5_is_the_extensions_algorithm_evaluated_exactly() {
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

    #[test]
    fn unorm_edges() {
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

    #[test]
    fn small_floats_match_a_textbook_rounding_on_every_boundary() {
        for mantissa_bits in [5, 6, 10] {
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

    #[test]
    fn half_agrees_with_known_codes() {
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

    #[test]
    fn unsigned_floats_store_negatives_as_zero_and_saturate() {
        assert_eq!(unsigned_float_from_f32(-1.0, 6), 0);
        assert_eq!(unsigned_float_from_f32(f32::INFINITY, 6), 0x7bf);
        assert_eq!(unsigned_float_from_f32(f32::INFINITY, 5), 0x3df);
        assert_eq!(f32_from_small_float(0x7bf, 6), 65024.0);
        assert_eq!(f32_from_small_float(0x3df, 5), 64512.0);
        assert_eq!(f32_from_small_float(0x7c0, 6), f32::INFINITY);
    }

    #[test]
    fn integers_clamp_and_sign_extend() {
        assert_eq!(sint_saturate(-200, 8), 0x80);
        assert_eq!(sint_saturate(200, 8), 0x7f);
        assert_eq!(sint_saturate(-1, 16), 0xffff);
        assert_eq!(i32_from_sint(0x80, 8), -128);
        assert_eq!(i32_from_sint(0xffff, 16), -1);
        assert_eq!(uint_saturate(300, 8), 255);
        assert_eq!(uint_saturate(7, 2), 3);
        assert_eq!(uint_saturate(u32::MAX, 32), u32::MAX);
    }

    #[test]
    fn words_put_channels_from_the_least_significant_bit_up() {
        let word = Format::Rgb10A2.encode([1.0f32, 0.0, 1.0, 1.0]);
        assert_eq!(word, 0x3ff | (0x3ff << 20) | (3 << 30));
        let word = Format::Rgba8ui.encode([1u32, 2, 3, 4]);
        assert_eq!(word, 0x0403_0201);
        assert_eq!(Format::Rgba8ui.decode::<u32>(word), [1, 2, 3, 4]);
        assert_eq!(
            Format::Rg16i.decode::<i32>(Format::Rg16i.encode([-5i32, 7, 0, 0])),
            [-5, 7, 0, 0]
        );
    }

    /// `floor(((2^bits - 1) numerator + bias) / denominator)` in 128-bit integers.
    fn scaled_quotient_reference(numerator: u32, denominator: u32, bias: u32, bits: u32) -> u32 {
        let product = u128::from(max_code(bits)) * u128::from(numerator) + u128::from(bias);
        (product / u128::from(denominator)) as u32
    }

    #[test]
    fn scaled_quotient_is_the_exact_floor() {
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

    /// The octahedral contract written another way: the magnitudes scaled by a power of two
    /// in f64 (exact) and floored, the ratios rounded in 128-bit integers, the hemisphere and
    /// sign rules spelled out.
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

    /// Unit vectors at the octahedral map's poles, seams and diagonals, with signed zeros,
    /// non-unit, tiny, infinite and NaN ones.
    fn octahedral_edges() -> Vec<[f32; 3]> {
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

    #[test]
    fn octahedral_follows_its_contract_and_the_map() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::SmallRng::seed_from_u64(9);
        let mut vectors = octahedral_edges();
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

    /// The RGBM contract written another way: fixed point by scaling in f64 (exact) and
    /// flooring, the multiplier and channels rounded in 128-bit integers.
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
    fn rgbm_follows_its_contract_within_its_bound() {
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
