//! The twelve storage formats of EXT_shader_pixel_local_storage, each one 32-bit word.
//!
//! Inside a word the channels r, g, b, a sit from the least significant bit up, at the
//! format's widths: the convention of GL's packed `_REV` types, so a packed word loads
//! unchanged into an `Rgba32Uint` render target.

use std::fmt;

use crate::codecs::Encoding;

/// One channel of a format: where its bits sit in the word and what they mean.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Channel {
    /// `'r'`, `'g'`, `'b'` or `'a'`.
    pub name: char,
    /// The position of its least significant bit in the word.
    pub offset: u32,
    /// Its width in bits.
    pub bits: u32,
    /// Its codec (a per-component one: unorm, half, float32, unsigned_float, uint or sint).
    pub encoding: Encoding,
}

impl Channel {
    const fn new(name: char, offset: u32, bits: u32, encoding: Encoding) -> Self {
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

/// A pixel local storage format. Every format is exactly one 32-bit word. Its facts are one
/// row of the format table ([`Format::row`]), in the variants' order.
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

/// A render-target format as each API names and costs it: what the report, the wgpu helpers,
/// the GLSL includes' interfaces and the renderer's GLES and Vulkan backends read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TargetFormat {
    /// The GLSL type a shader declares it with: `vec4`, `uvec4` or `ivec4`, whatever the
    /// channel count (framebuffer fetch and `subpassLoad` read four components; channels the
    /// format lacks read as 0, alpha as 1, and are dropped on write).
    pub glsl_type: &'static str,
    /// WebGPU's name and byte cost.
    pub webgpu: WebGpuTarget,
    /// GL's sized internal format.
    pub gl: GlFormat,
    /// Vulkan's format.
    pub vulkan: VulkanFormat,
}

/// A WebGPU texture format as a render target.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WebGpuTarget {
    /// The WebGPU name, e.g. `rgb10a2unorm`.
    pub name: &'static str,
    /// The "render target pixel byte cost" of the WebGPU spec (what wgpu counts).
    pub byte_cost: u32,
    /// The "render target component alignment": the running total is rounded up to it first.
    pub alignment: u32,
    /// The wgpu feature a render target of this format needs, if core WebGPU cannot render
    /// to it: `RG11B10UFLOAT_RENDERABLE` (WebGPU's "rg11b10ufloat-renderable") and
    /// `TEXTURE_FORMAT_16BIT_NORM` (a native-only feature).
    pub feature: Option<&'static str>,
}

/// A GL sized internal format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GlFormat {
    /// Its value, e.g. `0x8059` (`GL_RGB10_A2`).
    pub internal_format: u32,
    /// Its name, e.g. `GL_RGB10_A2`.
    pub name: &'static str,
    /// The extension a GLES 3.2 host needs to render to it, if any (`GL_EXT_texture_norm16`
    /// for the 16-bit unorm formats; the float formats are renderable in core GLES 3.2).
    pub host_extension: Option<&'static str>,
}

/// A `VkFormat`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VulkanFormat {
    /// Its value, e.g. `64` (`VK_FORMAT_A2B10G10R10_UNORM_PACK32`).
    pub format: i32,
    /// Its name.
    pub name: &'static str,
}

/// One row of the format table: everything the project knows of a pixel local storage format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FormatRow {
    /// The layout qualifier of EXT_shader_pixel_local_storage, e.g. `rgb10_a2`.
    pub qualifier: &'static str,
    /// The channels, from the least significant bit up.
    pub channels: &'static [Channel],
    /// How the channels are stored, for comments and reports.
    pub summary: &'static str,
    /// The render-target format that stores the channels in the same bits (so the driver's
    /// conversions are the extension's), with its WebGPU, GL and Vulkan names. rgba8unorm,
    /// rgb10a2unorm and rg11b10ufloat cost 8 bytes in WebGPU although they hold 4: the spec
    /// charges them for the wider formats implementations may use to blend them.
    pub target: TargetFormat,
}

use crate::field_type::ScalarKind;
use crate::named::Named;
use Encoding::{Float32, Half, Sint, Uint, Unorm, UnsignedFloat};

/// Channels r, g, b, a of these widths from the least significant bit up, each of `encoding`.
const fn channels<const N: usize>(widths: [u32; N], encoding: Encoding) -> [Channel; N] {
    let mut channels = [Channel::new('r', 0, 0, encoding); N];
    let (mut index, mut offset) = (0, 0);
    while index < N {
        let name = [b'r', b'g', b'b', b'a'][index] as char;
        channels[index] = Channel::new(name, offset, widths[index], encoding);
        offset += widths[index];
        index += 1;
    }
    channels
}

const R11F_G11F_B10F: [Channel; 3] = channels([11, 11, 10], UnsignedFloat);
const fn rgb10_a2(encoding: Encoding) -> [Channel; 4] {
    channels([10, 10, 10, 2], encoding)
}
const fn rgba8(encoding: Encoding) -> [Channel; 4] {
    channels([8; 4], encoding)
}
const fn rg16(encoding: Encoding) -> [Channel; 2] {
    channels([16; 2], encoding)
}
const fn r32(encoding: Encoding) -> [Channel; 1] {
    channels([32], encoding)
}

/// A row's target: its GLSL type, then WebGPU (name, byte cost, alignment, feature), GL
/// (internal format, name) and Vulkan (format, name).
const fn target(
    glsl_type: &'static str,
    (webgpu, byte_cost, alignment, feature): (&'static str, u32, u32, Option<&'static str>),
    (internal_format, gl_name): (u32, &'static str),
    (vulkan_format, vulkan_name): (i32, &'static str),
) -> TargetFormat {
    TargetFormat {
        glsl_type,
        webgpu: WebGpuTarget {
            name: webgpu,
            byte_cost,
            alignment,
            feature,
        },
        gl: GlFormat {
            internal_format,
            name: gl_name,
            host_extension: None,
        },
        vulkan: VulkanFormat {
            format: vulkan_format,
            name: vulkan_name,
        },
    }
}

const UNORM: &str = "unsigned normalized";
const SIGNED_INTEGERS: &str = "signed integers";
const UNSIGNED_INTEGERS: &str = "unsigned integers";

/// The format table, in the order of [`Format`]'s variants (the extension's table).
#[rustfmt::skip] // one format a row
const ROWS: [FormatRow; 12] = [
    FormatRow { qualifier: "r11f_g11f_b10f", channels: &R11F_G11F_B10F, summary: "unsigned floats (5-bit exponent; 6, 6, 5-bit mantissas)", target: target("vec4", ("rg11b10ufloat", 8, 4, Some("RG11B10UFLOAT_RENDERABLE")), (0x8C3A, "GL_R11F_G11F_B10F"), (122, "VK_FORMAT_B10G11R11_UFLOAT_PACK32")) },
    FormatRow { qualifier: "r32f", channels: &r32(Float32), summary: "IEEE binary32", target: target("vec4", ("r32float", 4, 4, None), (0x822E, "GL_R32F"), (100, "VK_FORMAT_R32_SFLOAT")) },
    FormatRow { qualifier: "rg16f", channels: &rg16(Half), summary: "IEEE binary16", target: target("vec4", ("rg16float", 4, 2, None), (0x822F, "GL_RG16F"), (83, "VK_FORMAT_R16G16_SFLOAT")) },
    FormatRow { qualifier: "rgb10_a2", channels: &rgb10_a2(Unorm), summary: UNORM, target: target("vec4", ("rgb10a2unorm", 8, 4, None), (0x8059, "GL_RGB10_A2"), (64, "VK_FORMAT_A2B10G10R10_UNORM_PACK32")) },
    FormatRow { qualifier: "rgba8", channels: &rgba8(Unorm), summary: UNORM, target: target("vec4", ("rgba8unorm", 8, 1, None), (0x8058, "GL_RGBA8"), (37, "VK_FORMAT_R8G8B8A8_UNORM")) },
    FormatRow { qualifier: "rg16", channels: &rg16(Unorm), summary: UNORM, target: norm16(target("vec4", ("rg16unorm", 4, 2, Some("TEXTURE_FORMAT_16BIT_NORM")), (0x822C, "GL_RG16_EXT"), (77, "VK_FORMAT_R16G16_UNORM"))) },
    FormatRow { qualifier: "rgba8i", channels: &rgba8(Sint), summary: SIGNED_INTEGERS, target: target("ivec4", ("rgba8sint", 4, 1, None), (0x8D8E, "GL_RGBA8I"), (42, "VK_FORMAT_R8G8B8A8_SINT")) },
    FormatRow { qualifier: "rg16i", channels: &rg16(Sint), summary: SIGNED_INTEGERS, target: target("ivec4", ("rg16sint", 4, 2, None), (0x8239, "GL_RG16I"), (82, "VK_FORMAT_R16G16_SINT")) },
    FormatRow { qualifier: "rgb10_a2ui", channels: &rgb10_a2(Uint), summary: UNSIGNED_INTEGERS, target: target("uvec4", ("rgb10a2uint", 8, 4, None), (0x906F, "GL_RGB10_A2UI"), (68, "VK_FORMAT_A2B10G10R10_UINT_PACK32")) },
    FormatRow { qualifier: "rgba8ui", channels: &rgba8(Uint), summary: UNSIGNED_INTEGERS, target: target("uvec4", ("rgba8uint", 4, 1, None), (0x8D7C, "GL_RGBA8UI"), (41, "VK_FORMAT_R8G8B8A8_UINT")) },
    FormatRow { qualifier: "rg16ui", channels: &rg16(Uint), summary: UNSIGNED_INTEGERS, target: target("uvec4", ("rg16uint", 4, 2, None), (0x823A, "GL_RG16UI"), (81, "VK_FORMAT_R16G16_UINT")) },
    FormatRow { qualifier: "r32ui", channels: &r32(Uint), summary: UNSIGNED_INTEGERS, target: target("uvec4", ("r32uint", 4, 4, None), (0x8236, "GL_R32UI"), (98, "VK_FORMAT_R32_UINT")) },
];

/// GLES renders to the 16-bit unorm formats only with `GL_EXT_texture_norm16`.
const fn norm16(mut target: TargetFormat) -> TargetFormat {
    target.gl.host_extension = Some("GL_EXT_texture_norm16");
    target
}

/// The render targets a layout's packed words go to: `Rgba32Uint` for every four words, and a
/// narrower one for the last one or two (three take `Rgba32Uint`: there is no three-channel
/// format).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PackedTarget {
    /// One word: `r32uint`.
    OneWord,
    /// Two words: `rg32uint`.
    TwoWords,
    /// Three or four words: `rgba32uint`.
    FourWords,
}

#[rustfmt::skip] // one format a row
const PACKED_TARGETS: [TargetFormat; 3] = [
    target("uvec4", ("r32uint", 4, 4, None), (0x8236, "GL_R32UI"), (98, "VK_FORMAT_R32_UINT")),
    target("uvec4", ("rg32uint", 8, 4, None), (0x823C, "GL_RG32UI"), (101, "VK_FORMAT_R32G32_UINT")),
    target("uvec4", ("rgba32uint", 16, 4, None), (0x8D70, "GL_RGBA32UI"), (107, "VK_FORMAT_R32G32B32A32_UINT")),
];

impl PackedTarget {
    /// How many targets `words` packed words take: one per four words.
    pub const fn count_for_words(words: usize) -> usize {
        words.div_ceil(4)
    }

    /// The last target of `words` packed words (`words` > 0): as narrow as the words it holds.
    /// Every other is [`PackedTarget::FourWords`].
    pub const fn last_for_words(words: usize) -> PackedTarget {
        match words % 4 {
            1 => PackedTarget::OneWord,
            2 => PackedTarget::TwoWords,
            _ => PackedTarget::FourWords,
        }
    }

    /// The targets of `words` packed words, in order.
    pub fn for_words(words: usize) -> Vec<PackedTarget> {
        let mut targets = vec![PackedTarget::FourWords; PackedTarget::count_for_words(words)];
        if let Some(last) = targets.last_mut() {
            *last = PackedTarget::last_for_words(words);
        }
        targets
    }

    /// Its row of the table.
    pub const fn target(self) -> &'static TargetFormat {
        &PACKED_TARGETS[self as usize]
    }
}

impl Named for Format {
    /// Every format, in the order of the extension's table.
    const ALL: &'static [Self] = &[
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
    fn name(self) -> &'static str {
        self.row().qualifier
    }

    /// Parses a layout qualifier. Also accepts `rgb10a2` and `rgb10a2ui`, the spelling of
    /// the book chapter's listings.
    fn from_name(name: &str) -> Option<Format> {
        match name {
            "rgb10a2" => return Some(Format::Rgb10A2),
            "rgb10a2ui" => return Some(Format::Rgb10A2ui),
            _ => {}
        }
        Format::ALL
            .iter()
            .copied()
            .find(|format| format.name() == name)
    }
}

impl Format {
    /// Its row of the format table.
    #[inline(always)]
    pub const fn row(self) -> &'static FormatRow {
        &ROWS[self as usize]
    }

    /// The render-target format that stores its channels in the same bits.
    pub const fn target(self) -> &'static TargetFormat {
        &self.row().target
    }

    /// The format whose name is closest to `name` (by edit distance; on a tie, one that
    /// `name` begins), for "did you mean".
    pub fn nearest(name: &str) -> Format {
        Format::ALL
            .iter()
            .copied()
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
    pub const fn channels(self) -> &'static [Channel] {
        self.row().channels
    }

    /// The scalar type a shader reads from this format.
    pub fn scalar_kind(self) -> ScalarKind {
        self.channels()[0].encoding.scalar_kind()
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
        self.row().summary
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
        for &format in Format::ALL {
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

    /// The table is indexed by variant: each row must describe its own format. GL names its
    /// formats as the extension does (`GL_` and the qualifier, `_EXT` for the one from an
    /// extension); WebGPU ends its names with the scalar kind.
    #[test]
    fn every_row_describes_its_own_format() {
        for &format in Format::ALL {
            let target = format.target();
            let gl = target.gl.name.trim_end_matches("_EXT").to_ascii_lowercase();
            assert_eq!(gl, format!("gl_{}", format.name()), "{format}");
            let kind = match format.scalar_kind() {
                ScalarKind::Uint => "uint",
                ScalarKind::Sint => "sint",
                _ if format.name().ends_with('f') => "float",
                _ => "unorm",
            };
            assert!(target.webgpu.name.ends_with(kind), "{format}");
        }
    }

    #[test]
    fn packed_words_take_wide_targets_and_a_narrow_last_one() {
        assert_eq!(
            PackedTarget::for_words(6),
            [PackedTarget::FourWords, PackedTarget::TwoWords]
        );
        assert_eq!(PackedTarget::for_words(3), [PackedTarget::FourWords]);
        assert_eq!(PackedTarget::OneWord.target().webgpu.name, "r32uint");
        assert_eq!(PackedTarget::TwoWords.target().webgpu.name, "rg32uint");
        assert_eq!(PackedTarget::FourWords.target().webgpu.name, "rgba32uint");
    }

    #[test]
    fn names_round_trip_and_seed_spelling_is_accepted() {
        for &format in Format::ALL {
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
