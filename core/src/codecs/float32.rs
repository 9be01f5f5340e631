//! IEEE binary32, stored bit for bit: `r32f`, or a 32-bit bit field of one `f32`.

use super::wgsl::{BitField, Functions};
use super::{Codec, Conversion, Shape};
use crate::field_type::ScalarKind;

/// The f32 codec.
pub const CODEC: Codec = Codec::new(
    "float32",
    ScalarKind::Float,
    Shape::Fixed(32, 1, "an `f32`"),
    Conversion::Floats(|value, _| value.to_bits(), |code, _| f32::from_bits(code)),
    wgsl,
);

/// An f32 bit field's WGSL: its bits.
fn wgsl(_: &BitField) -> Functions {
    Functions::inline(
        "    return bitcast<u32>(value);\n",
        "    return bitcast<f32>(code);\n",
    )
}
