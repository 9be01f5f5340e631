//! The twelve storage formats of EXT_shader_pixel_local_storage, each one 32-bit word.
//!
//! Inside a word the channels r, g, b, a sit from the least significant bit up, at the
//! format's widths: the convention of GL's packed `_REV` types, so a packed word loads
//! unchanged into an `Rgba32Uint` render target.

use std::fmt;

/// What a shader sees when it reads a channel: the scalar type of the field that stores it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ScalarKind {
    /// `f32` (float and unsigned-normalized formats).
    Float,
    /// `u32` (the `ui` formats).
    Uint,
    /// `i32` (the `i` formats).
    Sint,
    /// `bool` (bit fields only).
    Bool,
}

impl ScalarKind {
    /// The WGSL scalar type.
    pub fn wgsl(self) -> &'static str {
        match self {
            ScalarKind::Float => "f32",
            ScalarKind::Uint => "u32",
            ScalarKind::Sint => "i32",
            ScalarKind::Bool => "bool",
        }
    }
}

/// How the bits of one channel encode its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ChannelEncoding {
    /// Unsigned normalized: the code `c` of `n` bits means `c / (2^n - 1)`.
    Unorm,
    /// IEEE-754 binary32, stored bit for bit.
    Float32,
    /// IEEE-754 binary16, sign kept.
    Half,
    /// An unsigned float with a 5-bit exponent (bias 15), as in `r11f_g11f_b10f`.
    UnsignedFloat {
        /// Bits of mantissa: 6 for the 11-bit channels, 5 for the 10-bit one.
        mantissa_bits: u32,
    },
    /// Unsigned integer.
    Uint,
    /// Two's-complement signed integer.
    Sint,
}

/// One channel of a format: where its bits sit in the word and what they mean.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Channel {
    /// `'r'`, `'g'`, `'b'` or `'a'`.
    pub name: char,
    /// The position of its least significant bit in the word.
    pub offset: u32,
    /// Its width in bits.
    pub bits: u32,
    /// How its bits encode its value.
    pub encoding: ChannelEncoding,
}

impl Channel {
    const fn new(name: char, offset: u32, bits: u32, encoding: ChannelEncoding) -> Self {
        Channel {
            name,
            offset,
            bits,
            encoding,
        }
    }

    /// Its bits in the word, as comments write them: `r 0-9`.
    pub fn bit_range(self) -> String {
        format!(
            "{} {}-{}",
            self.name,
            self.offset,
            self.offset + self.bits - 1
        )
    }

    /// The mask of the channel's bits once shifted down to bit 0.
    #[inline]
    pub fn mask(self) -> u32 {
        if self.bits == 32 {
            u32::MAX
        } else {
            (1u32 << self.bits) - 1
        }
    }
}

/// A pixel local storage format. Every format is exactly one 32-bit word.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Format {
    /// Three unsigned floats: 11, 11 and 10 bits (6, 6 and 5 of mantissa).
    R11fG11fB10f,
    /// One IEEE-754 binary32 float.
    R32f,
    /// Two IEEE-754 binary16 floats.
    Rg16f,
    /// Three 10-bit unorm channels and a 2-bit one.
    Rgb10A2,
    /// Four 8-bit unorm channels.
    Rgba8,
    /// Two 16-bit unorm channels.
    Rg16,
    /// Four 8-bit signed integers.
    Rgba8i,
    /// Two 16-bit signed integers.
    Rg16i,
    /// Three 10-bit unsigned integers and a 2-bit one.
    Rgb10A2ui,
    /// Four 8-bit unsigned integers.
    Rgba8ui,
    /// Two 16-bit unsigned integers.
    Rg16ui,
    /// One 32-bit unsigned integer.
    R32ui,
}

use ChannelEncoding::{Float32, Half, Sint, Uint, Unorm, UnsignedFloat};

const R11F_G11F_B10F: [Channel; 3] = [
    Channel::new('r', 0, 11, UnsignedFloat { mantissa_bits: 6 }),
    Channel::new('g', 11, 11, UnsignedFloat { mantissa_bits: 6 }),
    Channel::new('b', 22, 10, UnsignedFloat { mantissa_bits: 5 }),
];
const R32F: [Channel; 1] = [Channel::new('r', 0, 32, Float32)];
const RG16F: [Channel; 2] = [
    Channel::new('r', 0, 16, Half),
    Channel::new('g', 16, 16, Half),
];
const fn rgb10_a2(encoding: ChannelEncoding) -> [Channel; 4] {
    [
        Channel::new('r', 0, 10, encoding),
        Channel::new('g', 10, 10, encoding),
        Channel::new('b', 20, 10, encoding),
        Channel::new('a', 30, 2, encoding),
    ]
}
const fn rgba8(encoding: ChannelEncoding) -> [Channel; 4] {
    [
        Channel::new('r', 0, 8, encoding),
        Channel::new('g', 8, 8, encoding),
        Channel::new('b', 16, 8, encoding),
        Channel::new('a', 24, 8, encoding),
    ]
}
const fn rg16(encoding: ChannelEncoding) -> [Channel; 2] {
    [
        Channel::new('r', 0, 16, encoding),
        Channel::new('g', 16, 16, encoding),
    ]
}
const RGB10_A2: [Channel; 4] = rgb10_a2(Unorm);
const RGBA8: [Channel; 4] = rgba8(Unorm);
const RG16: [Channel; 2] = rg16(Unorm);
const RGBA8I: [Channel; 4] = rgba8(Sint);
const RG16I: [Channel; 2] = rg16(Sint);
const RGB10_A2UI: [Channel; 4] = rgb10_a2(Uint);
const RGBA8UI: [Channel; 4] = rgba8(Uint);
const RG16UI: [Channel; 2] = rg16(Uint);
const R32UI: [Channel; 1] = [Channel::new('r', 0, 32, Uint)];

impl Format {
    /// Every format, in the order of the extension's table.
    pub const ALL: [Format; 12] = [
        Format::R11fG11fB10f,
        Format::R32f,
        Format::Rg16f,
        Format::Rgb10A2,
        Format::Rgba8,
        Format::Rg16,
        Format::Rgba8i,
        Format::Rg16i,
        Format::Rgb10A2ui,
        Format::Rgba8ui,
        Format::Rg16ui,
        Format::R32ui,
    ];

    /// The layout qualifier of EXT_shader_pixel_local_storage, e.g. `rgb10_a2`.
    pub fn name(self) -> &'static str {
        match self {
            Format::R11fG11fB10f => "r11f_g11f_b10f",
            Format::R32f => "r32f",
            Format::Rg16f => "rg16f",
            Format::Rgb10A2 => "rgb10_a2",
            Format::Rgba8 => "rgba8",
            Format::Rg16 => "rg16",
            Format::Rgba8i => "rgba8i",
            Format::Rg16i => "rg16i",
            Format::Rgb10A2ui => "rgb10_a2ui",
            Format::Rgba8ui => "rgba8ui",
            Format::Rg16ui => "rg16ui",
            Format::R32ui => "r32ui",
        }
    }

    /// Parses a layout qualifier. Also accepts `rgb10a2` and `rgb10a2ui`, the spelling of
    /// the book chapter's listings.
    pub fn from_name(name: &str) -> Option<Format> {
        match name {
            "rgb10a2" => return Some(Format::Rgb10A2),
            "rgb10a2ui" => return Some(Format::Rgb10A2ui),
            _ => {}
        }
        Format::ALL.into_iter().find(|format| format.name() == name)
    }

    /// The format whose name is closest to `name` (by edit distance; on a tie, one that
    /// `name` begins), for "did you mean".
    pub fn nearest(name: &str) -> Format {
        Format::ALL
            .into_iter()
            .min_by_key(|format| {
                (
                    edit_distance(name, format.name()),
                    !format.name().starts_with(name),
                )
            })
            .unwrap_or(Format::Rgba8)
    }

    /// The channels, from the least significant bit up.
    #[inline(always)]
    pub fn channels(self) -> &'static [Channel] {
        match self {
            Format::R11fG11fB10f => &R11F_G11F_B10F,
            Format::R32f => &R32F,
            Format::Rg16f => &RG16F,
            Format::Rgb10A2 => &RGB10_A2,
            Format::Rgba8 => &RGBA8,
            Format::Rg16 => &RG16,
            Format::Rgba8i => &RGBA8I,
            Format::Rg16i => &RG16I,
            Format::Rgb10A2ui => &RGB10_A2UI,
            Format::Rgba8ui => &RGBA8UI,
            Format::Rg16ui => &RG16UI,
            Format::R32ui => &R32UI,
        }
    }

    /// The scalar type a shader reads from this format.
    pub fn scalar_kind(self) -> ScalarKind {
        match self.channels()[0].encoding {
            Unorm | Float32 | Half | UnsignedFloat { .. } => ScalarKind::Float,
            Uint => ScalarKind::Uint,
            Sint => ScalarKind::Sint,
        }
    }

    /// The bits of the first `components` channels: what a field of that many components uses.
    pub fn used_bits(self, components: usize) -> u32 {
        self.channels()
            .iter()
            .take(components)
            .map(|channel| channel.bits)
            .sum()
    }

    /// A short description of how the channels are stored, for comments and reports.
    pub fn encoding_summary(self) -> &'static str {
        match self {
            Format::R11fG11fB10f => "unsigned floats (5-bit exponent; 6, 6, 5-bit mantissas)",
            Format::R32f => "IEEE binary32",
            Format::Rg16f => "IEEE binary16",
            Format::Rgb10A2 | Format::Rgba8 | Format::Rg16 => "unsigned normalized",
            Format::Rgba8i | Format::Rg16i => "signed integers",
            Format::Rgb10A2ui | Format::Rgba8ui | Format::Rg16ui | Format::R32ui => {
                "unsigned integers"
            }
        }
    }
}

/// Levenshtein distance: the fewest single-character insertions, deletions and substitutions
/// that turn `a` into `b`.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    for (i, a_char) in a.chars().enumerate() {
        let mut current = vec![i + 1; b.len() + 1];
        for (j, b_char) in b.iter().enumerate() {
            let substitution = previous[j] + usize::from(a_char != *b_char);
            current[j + 1] = substitution.min(previous[j + 1] + 1).min(current[j] + 1);
        }
        previous = current;
    }
    previous[b.len()]
}

impl fmt::Display for Format {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_format_fills_exactly_one_word_without_overlap() {
        for format in Format::ALL {
            let mut covered = 0u64;
            for channel in format.channels() {
                let bits = u64::from(channel.mask()) << channel.offset;
                assert_eq!(
                    covered & bits,
                    0,
                    "{format}: channel {} overlaps",
                    channel.name
                );
                covered |= bits;
            }
            assert_eq!(
                covered,
                u64::from(u32::MAX),
                "{format} does not fill 32 bits"
            );
        }
    }

    #[test]
    fn names_round_trip_and_seed_spelling_is_accepted() {
        for format in Format::ALL {
            assert_eq!(Format::from_name(format.name()), Some(format));
        }
        assert_eq!(Format::from_name("rgb10a2"), Some(Format::Rgb10A2));
        assert_eq!(Format::from_name("rgba16f"), None);
    }

    #[test]
    fn nearest_names_the_likely_typo() {
        assert_eq!(Format::nearest("rgba16f"), Format::Rg16f);
        assert_eq!(Format::nearest("rgb10_a2u"), Format::Rgb10A2ui);
        assert_eq!(Format::nearest("r32"), Format::R32f);
        assert_eq!(Format::nearest("rgb8"), Format::Rgba8);
    }
}
