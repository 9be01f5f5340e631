//! A whole word's channels: the Rust mirror of a format, each channel converted by its codec
//! ([`crate::codecs`]) and placed from the least significant bit up.
//!
//! A field's scalar type need not be its channels' ([`Scalar`]): the layout check pairs float
//! fields with float and unorm formats and integer fields with their integer formats, and the
//! other pairings saturate as Rust's `as` does.

use crate::field_type::ScalarKind;
use crate::format::{Channel, Format};

/// A scalar a field can hold: f32, u32 or i32, converted to and from a codec's lane.
///
/// The conversions are always inlined: with the channel known at compile time (as derived code
/// has it) the codec's dispatch disappears.
pub trait Scalar: Copy + Default {
    /// The value as the lane of a codec that holds `kind`: an f32's bits, a u32, or an i32 in
    /// two's complement, converted as Rust's `as` does (saturating).
    fn to_lane(self, kind: ScalarKind) -> u32;

    /// The value of a codec's lane of `kind`.
    fn from_lane(lane: u32, kind: ScalarKind) -> Self;

    /// The channel's code, in its low bits.
    #[inline(always)]
    fn encode(self, channel: Channel) -> u32 {
        let codec = channel.encoding.codec();
        let lane = self.to_lane(codec.scalar_kind);
        codec.encode([lane, 0, 0, 0], 1, channel.bits, None)
    }

    /// The value of a channel's code.
    #[inline(always)]
    fn decode(code: u32, channel: Channel) -> Self {
        let codec = channel.encoding.codec();
        let lane = codec.decode(code, 1, channel.bits, None)[0];
        Self::from_lane(lane, codec.scalar_kind)
    }
}

impl Scalar for f32 {
    #[inline(always)]
    fn to_lane(self, kind: ScalarKind) -> u32 {
        match kind {
            ScalarKind::Float => self.to_bits(),
            ScalarKind::Uint | ScalarKind::Bool => self as u32,
            ScalarKind::Sint => self as i32 as u32,
        }
    }

    #[inline(always)]
    fn from_lane(lane: u32, kind: ScalarKind) -> f32 {
        match kind {
            ScalarKind::Float => f32::from_bits(lane),
            ScalarKind::Uint | ScalarKind::Bool => lane as f32,
            ScalarKind::Sint => lane as i32 as f32,
        }
    }
}

impl Scalar for u32 {
    #[inline(always)]
    fn to_lane(self, kind: ScalarKind) -> u32 {
        match kind {
            ScalarKind::Float => (self as f32).to_bits(),
            ScalarKind::Uint | ScalarKind::Bool => self,
            ScalarKind::Sint => self.min(i32::MAX as u32),
        }
    }

    #[inline(always)]
    fn from_lane(lane: u32, kind: ScalarKind) -> u32 {
        match kind {
            ScalarKind::Float => f32::from_bits(lane) as u32,
            ScalarKind::Uint | ScalarKind::Bool => lane,
            ScalarKind::Sint => (lane as i32).max(0) as u32,
        }
    }
}

impl Scalar for i32 {
    #[inline(always)]
    fn to_lane(self, kind: ScalarKind) -> u32 {
        match kind {
            ScalarKind::Float => (self as f32).to_bits(),
            ScalarKind::Uint | ScalarKind::Bool => self.max(0) as u32,
            ScalarKind::Sint => self as u32,
        }
    }

    #[inline(always)]
    fn from_lane(lane: u32, kind: ScalarKind) -> i32 {
        match kind {
            ScalarKind::Float => f32::from_bits(lane) as i32,
            ScalarKind::Uint | ScalarKind::Bool => lane.min(i32::MAX as u32) as i32,
            ScalarKind::Sint => lane as i32,
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
            word |= channel.encode_lanes([value])[0];
        }
        word
    }

    /// Unpacks a word into its channel values; channels the format lacks read as zero.
    // Always inlined, as `encode`.
    #[inline(always)]
    pub fn decode<S: Scalar>(self, word: u32) -> [S; 4] {
        let mut values = [S::default(); 4];
        for (value, channel) in values.iter_mut().zip(self.channels()) {
            *value = channel.decode_lanes([word])[0];
        }
        values
    }
}

/// Many texels at once: the same conversions as [`Format::encode`] and [`Format::decode`],
/// lane by lane over `N` texels, one channel at a time. The derived `pack_slice` and
/// `unpack_slice` call them on eight texels at a time with each channel a constant (where the
/// CPU has no exact form of its own, as AVX-512's for unorm): the codec is then known at
/// compile time, its conversion inlined, and the loop over the lanes becomes vector
/// instructions (the per-texel form converts one texel's channels in turn, in scalar
/// code). Each lane's result is the per-texel function's, bit for bit: the same code runs on
/// every lane, and Rust never contracts or reorders float arithmetic.
impl Channel {
    /// The channel's bits, in place in the word, of `N` values.
    #[inline(always)]
    pub fn encode_lanes<S: Scalar, const N: usize>(self, values: [S; N]) -> [u32; N] {
        let mut codes = [0; N];
        for (code, value) in codes.iter_mut().zip(values) {
            *code = value.encode(self) << self.offset;
        }
        codes
    }

    /// The channel's values in `N` words.
    #[inline(always)]
    pub fn decode_lanes<S: Scalar, const N: usize>(self, words: [u32; N]) -> [S; N] {
        let mut values = [S::default(); N];
        for (value, word) in values.iter_mut().zip(words) {
            *value = S::decode((word >> self.offset) & self.mask(), self);
        }
        values
    }
}

impl crate::BitField {
    /// The codes of `N` texels' fields, in their low bits: `lanes[c][i]` is texel i's
    /// component c as [`crate::BitField::encode`] takes it.
    #[inline(always)]
    pub fn encode_lanes<const N: usize>(self, lanes: [[u32; N]; 4], components: usize) -> [u32; N] {
        let mut codes = [0; N];
        for (index, code) in codes.iter_mut().enumerate() {
            *code = self.encode(
                [
                    lanes[0][index],
                    lanes[1][index],
                    lanes[2][index],
                    lanes[3][index],
                ],
                components,
            );
        }
        codes
    }

    /// The lanes of `N` codes (each in its low bits): `[c][i]` is code i's component c, as
    /// [`crate::BitField::decode`] gives it.
    #[inline(always)]
    pub fn decode_lanes<const N: usize>(self, codes: [u32; N], components: usize) -> [[u32; N]; 4] {
        let mut lanes = [[0; N]; 4];
        for (index, code) in codes.into_iter().enumerate() {
            let decoded = self.decode(code, components);
            for (component, value) in decoded.into_iter().enumerate() {
                lanes[component][index] = value;
            }
        }
        lanes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
