//! The Rust mirror at run time: field values as lanes of bits, packed into words and back.

use crate::field_type::ScalarKind;
use crate::format::Format;

use super::{Layout, Storage};

impl Layout {
    /// Packs field values, given per field as lanes of bits (f32 bits, u32, i32 as u32, bool
    /// as 0 or 1), into words: the Rust mirror at run time, for tests and tools (derived code
    /// does the same with the layout known at compile time).
    pub fn encode_lanes(&self, values: &[[u32; 4]]) -> Vec<u32> {
        self.word_contents()
            .iter()
            .map(|word| {
                word.members.iter().fold(0, |packed, member| {
                    let field = &self.fields[member.field];
                    let lanes = values[member.field];
                    packed
                        | match field.storage {
                            Storage::Word(format) => encode_word(format, field.ty.scalar, lanes),
                            Storage::Bits(bit_field) => {
                                bit_field.encode(lanes, field.ty.components) << member.offset
                            }
                        }
                })
            })
            .collect()
    }

    /// Unpacks words into field values as lanes of bits, as [`Layout::encode_lanes`] takes
    /// them; lanes past a field's components are 0.
    pub fn decode_lanes(&self, words: &[u32]) -> Vec<[u32; 4]> {
        self.field_locations()
            .iter()
            .zip(&self.fields)
            .map(|(&(word, member), field)| {
                let mut lanes = match field.storage {
                    Storage::Word(format) => decode_word(format, field.ty.scalar, words[word]),
                    Storage::Bits(bit_field) => bit_field.decode(
                        (words[word] >> member.offset) & crate::codecs::max_code(member.bits),
                        field.ty.components,
                    ),
                };
                lanes[field.ty.components..].fill(0);
                lanes
            })
            .collect()
    }
}

/// The lanes of a whole word's field from its channels' values.
fn encode_word(format: Format, scalar: ScalarKind, lanes: [u32; 4]) -> u32 {
    match scalar {
        ScalarKind::Float => format.encode(lanes.map(f32::from_bits)),
        ScalarKind::Uint | ScalarKind::Bool => format.encode(lanes),
        ScalarKind::Sint => format.encode(lanes.map(|bits| bits as i32)),
    }
}

/// A whole word's channels as lanes of bits.
fn decode_word(format: Format, scalar: ScalarKind, word: u32) -> [u32; 4] {
    match scalar {
        ScalarKind::Float => format.decode::<f32>(word).map(f32::to_bits),
        ScalarKind::Uint | ScalarKind::Bool => format.decode::<u32>(word),
        ScalarKind::Sint => format.decode::<i32>(word).map(|value| value as u32),
    }
}
