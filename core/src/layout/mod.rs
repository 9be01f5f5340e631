//! The layout model: named fields under a bit budget, each either a whole word of a pixel
//! local storage format or a bit field of a shared `r32ui` word. The derive and the layout
//! files both build a [`Layout`]; [`Layout::check`] is the one place that decides what is
//! valid, and [`Layout::word_contents`] the one place that places fields in words.
//!
//! Its parts: how the WGSL converts (`conversions.rs`), the checks and their messages
//! (`check.rs`), the Rust mirror's lane packing (`lanes.rs`) and the packed render targets' cost
//! (`targets.rs`). A field's type is the crate's [`FieldType`], which the codecs share.

mod check;
mod conversions;
mod lanes;
mod targets;

pub use check::{check_budget, fitting_types, Diagnostic, Subject, MAX_FIELDS};
pub use conversions::Conversions;

use crate::bit_field::BitField;
use crate::codecs::Encoding;
use crate::field_type::FieldType;
use crate::format::Format;
use crate::named::Named;
use crate::naming;
use crate::symbols::Symbols;

/// Where a field's bits live.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Storage {
    /// A whole word of a pixel local storage format (`#[pls(rgba8)]`).
    Word(Format),
    /// A bit field of a shared `r32ui` word (`#[bits(4, unorm)]`).
    Bits(BitField),
}

/// One field of a layout: a name, where its bits live and the type it holds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Field {
    /// The field's name, as in the struct.
    pub name: String,
    /// A whole word of a format, or a bit field.
    pub storage: Storage,
    /// The type it holds.
    pub ty: FieldType,
    /// Its own conversions, where they differ from the layout's (`#[pls(rgba8, conversions =
    /// fast)]`); `None` follows the layout's.
    pub conversions: Option<Conversions>,
}

impl Field {
    /// The bits this field uses: its channels' for a word (the rest is padding), its width
    /// for a bit field.
    pub fn used_bits(&self) -> u32 {
        match self.storage {
            Storage::Word(format) => format.used_bits(self.ty.components),
            Storage::Bits(field) => field.bits,
        }
    }

    /// The format of its word, for a whole-word field.
    pub fn format(&self) -> Option<Format> {
        match self.storage {
            Storage::Word(format) => Some(format),
            Storage::Bits(_) => None,
        }
    }

    /// Its bit field, for a bit field.
    pub fn bit_field(&self) -> Option<BitField> {
        match self.storage {
            Storage::Word(_) => None,
            Storage::Bits(field) => Some(field),
        }
    }

    /// The encodings of its channels (a format's) or of its bit field, in order.
    pub fn encodings(&self) -> Vec<Encoding> {
        match self.storage {
            Storage::Word(format) => format
                .channels()
                .iter()
                .map(|channel| channel.encoding)
                .collect(),
            Storage::Bits(field) => vec![field.encoding],
        }
    }

    /// How it is stored, for comments and reports: `rgba8` or `4-bit unorm`.
    pub fn storage_name(&self) -> String {
        match self.storage {
            Storage::Word(format) => format.name().to_string(),
            Storage::Bits(field) => field.to_string(),
        }
    }
}

/// A field's place in a word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Member {
    /// The field's index in the layout.
    pub field: usize,
    /// The position of its least significant bit in the word (0 for a whole word).
    pub offset: u32,
    /// Its width in bits (32 for a whole word).
    pub bits: u32,
}

impl Member {
    /// Its bits in the word, as reports and comments write them: `4-7`.
    pub fn bit_range(&self) -> String {
        format!("{}-{}", self.offset, self.offset + self.bits - 1)
    }
}

/// One 32-bit word of a layout: a whole-word field, or the bit fields that share an `r32ui`
/// word.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Word {
    /// The word's format: the field's, or `r32ui` for bit fields.
    pub format: Format,
    /// Its fields, from the least significant bit up.
    pub members: Vec<Member>,
    /// Whether it holds bit fields (rather than one whole-word field).
    pub is_bit_fields: bool,
}

/// A G-buffer layout: the fields in declaration order and, through
/// [`Layout::word_contents`], the words they fill.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The struct's name, in UpperCamelCase.
    pub name: String,
    /// Bits of tile memory available per pixel: a positive multiple of 32.
    pub budget: u32,
    /// The fields, in declaration order.
    pub fields: Vec<Field>,
}

/// The budget when a layout names none: PowerVR Series6 and Mali pixel local storage.
pub const DEFAULT_BUDGET: u32 = 128;

impl Layout {
    /// Builds a layout from borrowed parts (what the generated `layout()` functions call):
    /// per field its name, storage, type and own conversions.
    pub fn from_parts(
        name: &str,
        budget: u32,
        fields: &[(&str, Storage, FieldType, Option<Conversions>)],
    ) -> Self {
        Layout {
            name: name.to_string(),
            budget,
            fields: fields
                .iter()
                .map(|&(name, storage, ty, conversions)| Field {
                    name: name.to_string(),
                    storage,
                    ty,
                    conversions,
                })
                .collect(),
        }
    }

    /// The words the fields fill, in order. A whole-word field takes the next word;
    /// consecutive bit fields fill an `r32ui` word from its least significant bit up, in
    /// declaration order, and one that does not fit in what is left starts the next word
    /// (the bits left over are zero): no field straddles two words.
    pub fn word_contents(&self) -> Vec<Word> {
        let mut words: Vec<Word> = Vec::new();
        // The bits used of the last word, while it takes bit fields.
        let mut open: Option<u32> = None;
        for (index, field) in self.fields.iter().enumerate() {
            match field.storage {
                Storage::Word(format) => {
                    open = None;
                    words.push(Word {
                        format,
                        members: vec![Member {
                            field: index,
                            offset: 0,
                            bits: 32,
                        }],
                        is_bit_fields: false,
                    });
                }
                Storage::Bits(bit_field) => {
                    let bits = bit_field.bits.min(32);
                    let offset = match open {
                        Some(used) if used + bits <= 32 => used,
                        _ => {
                            words.push(Word {
                                format: Format::R32ui,
                                members: Vec::new(),
                                is_bit_fields: true,
                            });
                            0
                        }
                    };
                    open = Some(offset + bits);
                    if let Some(word) = words.last_mut() {
                        word.members.push(Member {
                            field: index,
                            offset,
                            bits,
                        });
                    }
                }
            }
        }
        words
    }

    /// The names of the fields in `word`, from its least significant bit up.
    pub fn field_names<'a>(&'a self, word: &Word) -> Vec<&'a str> {
        word.members
            .iter()
            .map(|member| self.fields[member.field].name.as_str())
            .collect()
    }

    /// Per field, its word and its member entry there ([`field_locations_in`] of its words).
    pub fn field_locations(&self) -> Vec<(usize, Member)> {
        field_locations_in(&self.word_contents(), self.fields.len())
    }

    /// Bits the layout occupies: 32 per word.
    pub fn bits(&self) -> u32 {
        32 * self.words() as u32
    }

    /// Bits of the channels and bit fields the fields use.
    pub fn used_bits(&self) -> u32 {
        self.fields.iter().map(Field::used_bits).sum()
    }

    /// Number of 32-bit words.
    pub fn words(&self) -> usize {
        self.word_contents().len()
    }

    /// Whether any field is a bit field.
    pub fn has_bit_fields(&self) -> bool {
        self.fields.iter().any(|field| field.bit_field().is_some())
    }

    /// The name in snake_case, used to name the generated WGSL functions.
    pub fn snake_name(&self) -> String {
        naming::snake_case(&self.name)
    }

    /// The names of what the emitters generate for this layout.
    pub fn symbols(&self) -> Symbols {
        Symbols::new(&self.name)
    }
}

/// Per field of a layout of `fields` fields, its word and its member entry there, read from the
/// layout's words ([`Layout::word_contents`]): for a caller that holds the words already, so
/// that they are not worked out again.
pub fn field_locations_in(words: &[Word], fields: usize) -> Vec<(usize, Member)> {
    let empty = Member {
        field: 0,
        offset: 0,
        bits: 0,
    };
    let mut locations = vec![(0, empty); fields];
    for (word, contents) in words.iter().enumerate() {
        for member in &contents.members {
            locations[member.field] = (word, *member);
        }
    }
    locations
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field(name: &str, format: Format, ty: &str) -> Field {
        Field {
            name: name.into(),
            storage: Storage::Word(format),
            ty: FieldType::from_rust_name(ty).unwrap(),
            conversions: None,
        }
    }

    fn listing_2_1(budget: u32) -> Layout {
        Layout {
            name: "SpecularWorkflow".into(),
            budget,
            fields: vec![
                field("light_accumulation", Format::Rgb10A2, "Vec3"),
                field("depth", Format::R32f, "f32"),
                field("normals_roughness", Format::Rgba8, "Vec4"),
                field("base_colour", Format::Rgba8, "Vec3"),
                field("specular_colour", Format::Rgba8, "Vec3"),
            ],
        }
    }

    #[test]
    fn listing_2_1_uses_142_of_160_bits_and_spills_at_128() {
        let layout = listing_2_1(128);
        assert_eq!((layout.bits(), layout.used_bits()), (160, 142));
        let diagnostics = layout.check();
        assert_eq!(diagnostics.len(), 1);
        assert!(
            diagnostics[0].message.contains("= 160 > 128"),
            "{}",
            diagnostics[0].message
        );
        assert!(listing_2_1(256).check().is_empty());
    }

    #[test]
    fn bit_fields_fill_words_from_the_low_bit_and_never_straddle() {
        use crate::codecs::Encoding;
        let bits = |name: &str, bits, encoding, ty: &str| Field {
            name: name.into(),
            storage: Storage::Bits(BitField { bits, encoding }),
            ty: FieldType::from_rust_name(ty).unwrap(),
            conversions: None,
        };
        let layout = Layout {
            name: "Packed".into(),
            budget: 128,
            fields: vec![
                bits("a", 20, Encoding::Unorm, "f32"),
                bits("b", 12, Encoding::Unorm, "f32"),
                // Does not fit beside a and b: starts word 1.
                bits("c", 4, Encoding::Uint, "u32"),
                field("whole", Format::Rgba8, "Vec4"),
                // After a whole word, a new word even though word 1 has room.
                bits("d", 1, Encoding::Bool, "bool"),
                bits("e", 30, Encoding::Octahedral, "Vec3"),
                // 31 bits do not fit beside d and e.
                bits("f", 31, Encoding::Sint, "i32"),
            ],
        };
        let places: Vec<(usize, u32, u32)> = layout
            .field_locations()
            .iter()
            .map(|(word, member)| (*word, member.offset, member.bits))
            .collect();
        assert_eq!(
            places,
            [
                (0, 0, 20),
                (0, 20, 12),
                (1, 0, 4),
                (2, 0, 32),
                (3, 0, 1),
                (3, 1, 30),
                (4, 0, 31)
            ]
        );
        assert_eq!(
            (layout.words(), layout.bits(), layout.used_bits()),
            (5, 160, 130)
        );
        let diagnostics = layout.check();
        assert_eq!(diagnostics.len(), 1, "{diagnostics:?}");
        assert!(
            diagnostics[0]
                .message
                .contains("(a | b) 32 + (c) 32 + whole 32 + (d | e) 32 + (f) 32 = 160 > 128"),
            "{}",
            diagnostics[0].message
        );
        // The words hold the lanes' codes, and decoding them gives the codes' values back.
        let lanes = [
            [0.5f32.to_bits(), 0, 0, 0],
            [1.0f32.to_bits(), 0, 0, 0],
            [9, 0, 0, 0],
            [0.25f32.to_bits(); 4],
            [1, 0, 0, 0],
            [0.0f32.to_bits(), 0.0f32.to_bits(), 1.0f32.to_bits(), 0],
            [(-5i32) as u32, 0, 0, 0],
        ];
        let words = layout.encode_lanes(&lanes);
        assert_eq!(words[0], 0x7ffff + 1 + (0xfff << 20)); // 0.5 of 20 bits rounds up
        assert_eq!(words[1], 9 & 0xf);
        let decoded = layout.decode_lanes(&words);
        assert_eq!(layout.encode_lanes(&decoded), words);
        assert_eq!(decoded[1], lanes[1]);
        assert_eq!(decoded[6], lanes[6]);
    }

    #[test]
    fn mismatched_types_name_what_fits() {
        let layout = Layout {
            name: "Bad".into(),
            budget: 96,
            fields: vec![
                field("a", Format::R32f, "Vec4"),
                field("b", Format::Rgba8, "i32"),
                field("c", Format::R11fG11fB10f, "Vec3"),
            ],
        };
        let messages: Vec<String> = layout.check().into_iter().map(|d| d.message).collect();
        assert_eq!(
            messages,
            [
                "`Vec4` has 4 components but `r32f` has 1 channel: use `f32`",
                "`i32` cannot be stored in `rgba8`, which holds floats: use `f32`, `Vec2`, `Vec3` or `Vec4`",
            ]
        );
    }

    #[test]
    fn budget_and_emptiness_are_checked() {
        let layout = Layout {
            name: "Empty".into(),
            budget: 100,
            fields: vec![],
        };
        let subjects: Vec<Subject> = layout.check().into_iter().map(|d| d.subject).collect();
        assert_eq!(subjects, [Subject::Budget, Subject::Name]);
    }
}
