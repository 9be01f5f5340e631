//! IEEE binary32, stored bit for bit: `r32f`, or a 32-bit bit field of one `f32`.

use super::wgsl::{BitField, Functions};
use super::{Codec, Shape};

/// The f32 codec.
pub const CODEC: Codec = Codec::floats(
    "float32",
    (32, 32),
    (|value, _| value.to_bits(), |code, _| f32::from_bits(code)),
    wgsl,
)
.with_shape(Shape::Fixed(32, 1, "an `f32`"));

/// An f32 bit field's WGSL: its bits.
fn wgsl(_: &BitField) -> Functions {
    Functions::inline(
        "    return bitcast<u32>(value);\n",
        "    return bitcast<f32>(code);\n",
    )
}
