//! IEEE binary32, stored bit for bit: `r32f`, or a 32-bit bit field of one `f32`.

use super::{Codec, Conversion, Shape};
use crate::field_type::ScalarKind;

/// The f32 codec.
pub const CODEC: Codec = Codec::new(
    "float32",
    ScalarKind::Float,
    Shape::Fixed(32, 1, "an `f32`"),
    Conversion::Floats(|value, _| value.to_bits(), |code, _| f32::from_bits(code)),
);
