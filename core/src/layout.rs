//! The layout model: named fields under a bit budget, each either a whole word of a pixel
//! local storage format or a bit field of a shared `r32ui` word. The derive and the layout
//! files both build a [`Layout`]; [`Layout::check`] is the one place that decides what is
//! valid, and [`Layout::word_contents`] the one place that places fields in words.

use std::fmt::Write as _;

use crate::bit_field::BitField;
use crate::codecs::Encoding;
use crate::format::{Format, PackedTarget, ScalarKind};
use crate::naming;

/// The type of a field: a scalar or a vector of 2 to 4 components.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FieldType {
    /// Float, unsigned or signed integer.
    pub scalar: ScalarKind,
    /// 1 to 4.
    pub components: usize,
}

impl FieldType {
    /// Every supported type: the scalars and vectors of f32, u32 and i32, and `bool`.
    pub const ALL: [FieldType; 13] = {
        let kinds = [ScalarKind::Float, ScalarKind::Uint, ScalarKind::Sint];
        let mut all = [FieldType {
            scalar: ScalarKind::Bool,
            components: 1,
        }; 13];
        let mut index = 0;
        while index < 12 {
            all[index] = FieldType {
                scalar: kinds[index / 4],
                components: index % 4 + 1,
            };
            index += 1;
        }
        all
    };

    /// A type of `components` scalars of kind `scalar` (1 to 4).
    pub fn new(scalar: ScalarKind, components: usize) -> Self {
        FieldType { scalar, components }
    }

    /// The Rust type's name as the derive sees it: `f32`, `Vec3`, `UVec2`, `i32`, `bool`, ...
    pub fn rust_name(self) -> &'static str {
        const NAMES: [[&str; 4]; 3] = [
            ["f32", "Vec2", "Vec3", "Vec4"],
            ["u32", "UVec2", "UVec3", "UVec4"],
            ["i32", "IVec2", "IVec3", "IVec4"],
        ];
        let row = match self.scalar {
            ScalarKind::Float => 0,
            ScalarKind::Uint => 1,
            ScalarKind::Sint => 2,
            ScalarKind::Bool => return "bool",
        };
        NAMES[row][self.components - 1]
    }

    /// Recognises a Rust type name (the last segment of its path).
    pub fn from_rust_name(name: &str) -> Option<FieldType> {
        FieldType::ALL.into_iter().find(|ty| ty.rust_name() == name)
    }

    /// The WGSL type: `f32`, `vec3<f32>`, ...
    pub fn wgsl(self) -> String {
        match self.components {
            1 => self.scalar.wgsl().to_string(),
            n => format!("vec{n}<{}>", self.scalar.wgsl()),
        }
    }
}

/// How the WGSL converts values to and from channel codes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum Conversions {
    /// Steps no adapter can round its own way (integer operations on the float's bits, and
    /// float arithmetic only where every rounding and order gives one answer): the same words
    /// on every adapter as the Rust mirror, and portable to every backend.
    #[default]
    Exact,
    /// What engines write: WGSL's builtins where a format has one (`pack4x8unorm` for rgba8,
    /// `pack2x16unorm` for rg16, `pack2x16float` for rg16f), f32 arithmetic for rgb10_a2,
    /// `pack2x16float` with cut mantissas for r11f_g11f_b10f; the integer formats and r32f are
    /// exact either way. Bit fields: f32 arithmetic for unorm, octahedral and RGBM,
    /// `pack2x16float` for half; the others are exact either way. Fewer instructions; the
    /// rounding is the adapter's, so a channel's code can differ from the Rust mirror's by one
    /// (an octahedral normal or RGBM colour by two steps of its decoded value, as those name
    /// some values by two codes), and for the floats the adapter may flush values under 2^-14
    /// to zero and turn values past 65504 into infinity.
    /// `integration-tests/tests/gpu_packing.rs` and `gpu_bit_fields.rs` measure the deviation on the adapter.
    Fast,
}

impl Conversions {
    /// Whether a format's encode is the exact one under these conversions (fast conversions
    /// replace it for rgba8, rg16, rg16f, rgb10_a2 and r11f_g11f_b10f).
    pub fn is_exact_for(self, format: Format) -> bool {
        self == Conversions::Exact
            || !(self.builtins(format).is_some()
                || matches!(format, Format::Rgb10A2 | Format::R11fG11fB10f))
    }

    /// Whether a bit field's encode is the exact one under these conversions (fast conversions
    /// replace it for unorm, half, octahedral and RGBM).
    pub fn is_exact_for_encoding(self, encoding: Encoding) -> bool {
        self == Conversions::Exact || !encoding.has_fast_form()
    }

    /// The name layout files and `#[gbuffer(conversions = ...)]` give them: `exact` or `fast`.
    pub fn name(self) -> &'static str {
        match self {
            Conversions::Exact => "exact",
            Conversions::Fast => "fast",
        }
    }

    /// The conversions [`Conversions::name`] names.
    pub fn from_name(name: &str) -> Option<Conversions> {
        [Conversions::Exact, Conversions::Fast]
            .into_iter()
            .find(|conversions| conversions.name() == name)
    }

    /// What the generated functions of a field with these conversions add to their names
    /// where the layout's conversions differ: `_exact` or `_fast`.
    pub fn name_suffix(self) -> &'static str {
        match self {
            Conversions::Exact => "_exact",
            Conversions::Fast => "_fast",
        }
    }

    /// The builtin pack and unpack functions for a format, under these conversions.
    pub fn builtins(self, format: Format) -> Option<(&'static str, &'static str)> {
        match (self, format) {
            (Conversions::Fast, Format::Rgba8) => Some(("pack4x8unorm", "unpack4x8unorm")),
            (Conversions::Fast, Format::Rg16) => Some(("pack2x16unorm", "unpack2x16unorm")),
            (Conversions::Fast, Format::Rg16f) => Some(("pack2x16float", "unpack2x16float")),
            _ => None,
        }
    }
}

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

/// What a diagnostic is about, so each front end can point at it (a span, a file position).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Subject {
    /// The layout's name.
    Name,
    /// The budget setting (or the name, where the budget is the default).
    Budget,
    /// Field `index`'s name.
    FieldName(usize),
    /// Field `index`'s storage: its format, or its bit field's width and encoding.
    FieldFormat(usize),
    /// Field `index`'s type.
    FieldType(usize),
}

/// One problem with a layout.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// What the problem is about: the name, the budget or a field.
    pub subject: Subject,
    /// What is wrong, in one sentence.
    pub message: String,
}

/// The most fields a layout may have: far more than a G-buffer holds (eight render targets of
/// 128 bits), and few enough that every output generates in well under a second (naga's
/// translation grows faster than linearly with the number of functions, one a bit field).
pub const MAX_FIELDS: usize = 256;

/// Why `budget` bits cannot be a budget, if they cannot: a budget is whole 32-bit words.
pub fn check_budget(budget: u32) -> Result<(), String> {
    match budget != 0 && budget % 32 == 0 {
        true => Ok(()),
        false => Err(format!(
            "budget must be a positive multiple of 32 bits (the fields fill 32-bit words), not \
             {budget}"
        )),
    }
}

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

    /// Per field, its word and its member entry there.
    pub fn field_locations(&self) -> Vec<(usize, Member)> {
        let mut locations = vec![
            (
                0,
                Member {
                    field: 0,
                    offset: 0,
                    bits: 0
                }
            );
            self.fields.len()
        ];
        for (word, contents) in self.word_contents().iter().enumerate() {
            for member in &contents.members {
                locations[member.field] = (word, *member);
            }
        }
        locations
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

    /// Number of packed render targets the words need: one per four words.
    pub fn targets(&self) -> usize {
        self.words().div_ceil(4)
    }

    /// The packed render targets: `rgba32uint` for every four words, the last as narrow as the
    /// words it holds ([`PackedTarget::for_words`]).
    pub fn packed_targets(&self) -> Vec<PackedTarget> {
        PackedTarget::for_words(self.words())
    }

    /// The WebGPU names of the packed render targets, e.g. `["rgba32uint", "r32uint"]`.
    pub fn packed_target_formats(&self) -> Vec<&'static str> {
        self.packed_targets()
            .into_iter()
            .map(|target| target.target().webgpu.name)
            .collect()
    }

    /// Bytes per sample of the packed render targets, as WebGPU counts them against
    /// `maxColorAttachmentBytesPerSample`: 4 per 32-bit channel.
    pub fn packed_target_bytes(&self) -> u32 {
        self.packed_targets()
            .into_iter()
            .map(|target| target.target().webgpu.byte_cost)
            .sum()
    }

    /// The name in snake_case, used to name the generated WGSL functions.
    pub fn snake_name(&self) -> String {
        naming::snake_case(&self.name)
    }

    /// Every problem with the layout, in source order; empty when it is valid.
    pub fn check(&self) -> Vec<Diagnostic> {
        let mut diagnostics = Vec::new();
        let mut report =
            |subject, message: String| diagnostics.push(Diagnostic { subject, message });

        if let Err(reason) = naming::check_layout_name(&self.name) {
            report(
                Subject::Name,
                format!("layout name `{}` {reason}", self.name),
            );
        }
        if let Err(problem) = check_budget(self.budget) {
            report(Subject::Budget, problem);
        }
        if self.fields.len() > MAX_FIELDS {
            // The per-field checks are not run: their cost is what the limit bounds.
            report(
                Subject::Name,
                format!(
                    "layout `{}` has {} fields; layouts are limited to {MAX_FIELDS}",
                    self.name,
                    self.fields.len()
                ),
            );
            return diagnostics;
        }
        if self.fields.is_empty() {
            report(
                Subject::Name,
                format!(
                    "layout `{}` has no fields: a G-buffer needs at least one word",
                    self.name
                ),
            );
        }
        for (index, field) in self.fields.iter().enumerate() {
            if let Err(reason) = naming::check_identifier(&field.name) {
                report(
                    Subject::FieldName(index),
                    format!("field name `{}` {reason}", field.name),
                );
            }
            if let Some(first) = self.fields[..index]
                .iter()
                .position(|other| other.name == field.name)
            {
                report(
                    Subject::FieldName(index),
                    format!(
                        "field `{}` is declared twice (first as field {first})",
                        field.name
                    ),
                );
            }
            match field.storage {
                Storage::Word(format) => {
                    if let Some(reason) = type_mismatch(format, field.ty) {
                        report(Subject::FieldType(index), reason);
                    }
                }
                Storage::Bits(bit_field) => {
                    if let Some(reason) = bit_field.mismatch(field.ty) {
                        report(
                            Subject::FieldFormat(index),
                            format!("field `{}`: {reason}", field.name),
                        );
                    }
                }
            }
        }
        if self.budget > 0 && self.budget % 32 == 0 && self.bits() > self.budget {
            report(Subject::Budget, self.over_budget_message());
        }
        diagnostics
    }

    fn over_budget_message(&self) -> String {
        let mut message = format!(
            "layout `{}` needs {} bits but the budget is {}: ",
            self.name,
            self.bits(),
            self.budget
        );
        let terms: Vec<String> = self
            .word_contents()
            .iter()
            .map(|word| {
                let names = self.field_names(word);
                match names.as_slice() {
                    [name] if !word.is_bit_fields => format!("{name} 32"),
                    _ => format!("({}) 32", names.join(" | ")),
                }
            })
            .collect();
        let spill = self.bits() - self.budget;
        let _ = write!(
            message,
            "{} = {} > {}; {} bits ({} word{}) would spill to main memory",
            terms.join(" + "),
            self.bits(),
            self.budget,
            spill,
            spill / 32,
            if spill == 32 { "" } else { "s" }
        );
        message
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

/// Why a type cannot be stored in a format, if it cannot.
fn type_mismatch(format: Format, ty: FieldType) -> Option<String> {
    let channels = format.channels().len();
    let fitting = fitting_types(format);
    if ty.scalar != format.scalar_kind() {
        let holds = match format.scalar_kind() {
            ScalarKind::Float => "floats",
            ScalarKind::Uint => "unsigned integers",
            ScalarKind::Sint => "signed integers",
            ScalarKind::Bool => "booleans",
        };
        return Some(format!(
            "`{}` cannot be stored in `{format}`, which holds {holds}: use {fitting}",
            ty.rust_name()
        ));
    }
    if ty.components > channels {
        return Some(format!(
            "`{}` has {} components but `{format}` has {channels} channel{}: use {fitting}",
            ty.rust_name(),
            ty.components,
            if channels == 1 { "" } else { "s" }
        ));
    }
    None
}

/// The types that fit a format, as a phrase: "`f32`, `Vec2` or `Vec3`".
pub fn fitting_types(format: Format) -> String {
    let names: Vec<String> = (1..=format.channels().len())
        .map(|components| {
            format!(
                "`{}`",
                FieldType::new(format.scalar_kind(), components).rust_name()
            )
        })
        .collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.concat(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_are_found_by_their_names_only() {
        assert_eq!(Conversions::from_name("exact"), Some(Conversions::Exact));
        assert_eq!(Conversions::from_name("fast"), Some(Conversions::Fast));
        assert_eq!(Conversions::from_name("Fast"), None);
        assert_eq!(Conversions::from_name(""), None);
        assert_eq!(Conversions::Fast.name_suffix(), "_fast");
    }

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
    fn type_names_round_trip() {
        for ty in FieldType::ALL {
            assert_eq!(FieldType::from_rust_name(ty.rust_name()), Some(ty));
        }
        assert_eq!(FieldType::new(ScalarKind::Uint, 3).wgsl(), "vec3<u32>");
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
