//! A whole word's channels: the Rust mirror of a format, each channel converted by its codec
//! ([`crate::codecs`]) and placed from the least significant bit up.
//!
//! A field's scalar type need not be its channels' ([`Scalar`]): the layout check pairs float
//! fields with float and unorm formats and integer fields with their integer formats, and the
//! other pairings saturate as Rust's `as` does.

use crate::format::{Channel, Format, ScalarKind};

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
