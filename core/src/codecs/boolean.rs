//! A `bool` in one bit: 1 for true. Any set bit decodes as true.

use super::{Codec, Conversion, Shape};
use crate::field_type::ScalarKind;

/// The bool codec.
pub const CODEC: Codec = Codec::new(
    "bool",
    ScalarKind::Bool,
    Shape::Fixed(1, 1, "a `bool`"),
    Conversion::Integers(|lane, _| u32::from(lane != 0), |code, _| code & 1),
);
