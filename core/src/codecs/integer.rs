//! Integers: an unsigned integer clamped to `2^n - 1`, or a signed one clamped to `[-2^(n-1),
//! 2^(n-1) - 1]` and stored as an `n`-bit two's complement, sign-extended back. 1 to 32 bits
//! per component. The integer formats (`rgba8ui`, `rg16i`, `r32ui`, ...) are built from them.

use super::{max_code, Codec, Conversion, Shape};
use crate::field_type::ScalarKind;

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

/// The unsigned integer codec.
pub const UINT: Codec = Codec::new(
    "uint",
    ScalarKind::Uint,
    Shape::PerComponent(1, 32),
    Conversion::Integers(uint_saturate, |code, _| code),
);

/// The signed integer codec: lanes are `i32`s' bits.
pub const SINT: Codec = Codec::new(
    "sint",
    ScalarKind::Sint,
    Shape::PerComponent(1, 32),
    Conversion::Integers(
        |lane, each| sint_saturate(lane as i32, each),
        |code, each| i32_from_sint(code, each) as u32,
    ),
);

#[cfg(test)]
mod tests {
    use super::*;

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
}
