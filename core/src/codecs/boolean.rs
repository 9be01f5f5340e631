//! A `bool` in one bit: 1 for true. Any set bit decodes as true.

use super::wgsl::{BitField, Functions};
use super::{exact_shape_mismatch, without_range, Codec, Encoding};
use crate::format::ScalarKind;
use crate::layout::FieldType;

/// The bool codec.
pub struct Bool;

impl Codec for Bool {
    fn name(&self) -> &'static str {
        "bool"
    }

    fn scalar_kind(&self) -> ScalarKind {
        ScalarKind::Bool
    }

    fn encoding(&self, range: Option<f32>) -> Result<Encoding, String> {
        without_range(Encoding::Bool, range)
    }

    fn mismatch(&self, encoding: Encoding, bits: u32, ty: FieldType) -> Option<String> {
        exact_shape_mismatch(encoding, bits, ty, (1, 1, "a `bool`"))
    }

    #[inline(always)]
    fn encode(&self, lanes: [u32; 4], _: usize, _: u32, _: Option<f32>) -> u32 {
        u32::from(lanes[0] != 0)
    }

    #[inline(always)]
    fn decode(&self, code: u32, _: usize, _: u32, _: Option<f32>) -> [u32; 4] {
        [u32::from(code & 1 != 0), 0, 0, 0]
    }

    fn wgsl(&self, _: &BitField) -> Functions {
        Functions {
            encode: "    return u32(value);\n".to_string(),
            decode: "    return code != 0u;\n".to_string(),
            helpers: Vec::new(),
        }
    }
}
