//! A `bool` in one bit: 1 for true. Any set bit decodes as true.

use super::wgsl::{BitField, Functions};
use super::{Codec, Conversion, Shape};
use crate::field_type::ScalarKind;

/// The bool codec.
pub const CODEC: Codec = Codec::new(
    "bool",
    ScalarKind::Bool,
    Shape::Fixed(1, 1, "a `bool`"),
    Conversion::Integers(|lane, _| u32::from(lane != 0), |code, _| code & 1),
    wgsl,
);

/// A bool bit field's WGSL: WGSL converts `bool` to and from `u32` itself.
fn wgsl(_: &BitField) -> Functions {
    Functions::inline("    return u32(value);\n", "    return code != 0u;\n")
}
