//! IEEE binary32, stored bit for bit: `r32f`, or a 32-bit bit field of one `f32`.

use super::wgsl::{BitField, Functions};
use super::{exact_shape_mismatch, without_range, Codec, Encoding};
use crate::layout::FieldType;

/// The f32 codec.
pub struct Float32;

impl Codec for Float32 {
    fn name(&self) -> &'static str {
        "float32"
    }

    fn encoding(&self, range: Option<f32>) -> Result<Encoding, String> {
        without_range(Encoding::Float32, range)
    }

    fn mismatch(&self, encoding: Encoding, bits: u32, ty: FieldType) -> Option<String> {
        exact_shape_mismatch(encoding, bits, ty, (32, 1, "an `f32`"))
    }

    #[inline(always)]
    fn encode(&self, lanes: [u32; 4], _: usize, _: u32, _: Option<f32>) -> u32 {
        lanes[0]
    }

    #[inline(always)]
    fn decode(&self, code: u32, _: usize, _: u32, _: Option<f32>) -> [u32; 4] {
        [code, 0, 0, 0]
    }

    fn wgsl(&self, _: &BitField) -> Functions {
        Functions {
            encode: "    return bitcast<u32>(value);\n".to_string(),
            decode: "    return bitcast<f32>(code);\n".to_string(),
            helpers: Vec::new(),
        }
    }
}
