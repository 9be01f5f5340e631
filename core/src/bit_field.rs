//! Bit fields: a field of `N` bits in a shared `r32ui` word, encoded by one of the
//! [`codecs`](crate::codecs) (`#[bits(N, ENCODING)]` in the derive, `bits` and `encoding` in
//! a layout file). A vector field of a per-component codec splits its bits evenly, x in the
//! lowest.

use std::fmt;

use crate::codecs::Encoding;
use crate::field_type::{FieldType, ScalarKind};

/// A bit field: `bits` bits of a shared `r32ui` word and how they encode the field's value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BitField {
    /// Its width, 1 to 32.
    pub bits: u32,
    /// How the bits encode the value.
    pub encoding: Encoding,
}

impl BitField {
    /// Why a field of type `ty` cannot be this bit field, if it cannot: the width, the type
    /// and the codec's own rules, in one sentence.
    pub fn mismatch(self, ty: FieldType) -> Option<String> {
        let BitField { bits, encoding } = self;
        if !(1..=32).contains(&bits) {
            return Some(format!(
                "a bit field has 1 to 32 bits (it lives in one 32-bit word), not {bits}"
            ));
        }
        let codec = encoding.codec();
        if ty.scalar != codec.scalar_kind {
            let wants = match codec.scalar_kind {
                ScalarKind::Float => "floats (`f32` or a `Vec`)",
                ScalarKind::Uint => "unsigned integers (`u32` or a `UVec`)",
                ScalarKind::Sint => "signed integers (`i32` or an `IVec`)",
                ScalarKind::Bool => "a `bool`",
            };
            return Some(format!(
                "`{encoding}` holds {wants}, not `{}`",
                ty.rust_name()
            ));
        }
        codec.mismatch(encoding, bits, ty)
    }

    /// The bits of each component (per-component codecs) or of each octahedral coordinate.
    pub fn component_bits(self, components: usize) -> u32 {
        self.encoding.codec().component_bits(self.bits, components)
    }

    /// The field's code: its value's lanes as bits (f32 bits, u32, i32 as u32, bool as 0 or 1;
    /// `components` of them) encoded into the low `bits` bits. The Rust mirror of the WGSL.
    // Always inlined: derived code calls it with a constant bit field, and the codec's
    // dispatch folds away.
    #[inline(always)]
    pub fn encode(self, lanes: [u32; 4], components: usize) -> u32 {
        let each = self.component_bits(components);
        self.encoding
            .codec()
            .encode(lanes, components, each, self.encoding.range())
    }

    /// The value of a field's code (in its low bits) as lanes, as [`BitField::encode`] takes
    /// them; lanes past the field's components are 0.
    #[inline(always)]
    pub fn decode(self, code: u32, components: usize) -> [u32; 4] {
        let each = self.component_bits(components);
        self.encoding
            .codec()
            .decode(code, components, each, self.encoding.range())
    }
}

impl fmt::Display for BitField {
    /// `4-bit unorm`, `32-bit rgbm(8.0)`.
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(out, "{}-bit {}", self.bits, self.encoding)
    }
}
