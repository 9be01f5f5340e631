//! A `bool` in one bit (`gbuffer_core::codecs::boolean`): WGSL converts `bool` to and from
//! `u32` itself, 1 for true, and any set bit reads as true.

use super::{BitField, Functions};

/// A bool bit field's WGSL.
pub fn functions(_: &BitField) -> Functions {
    Functions::inline("    return u32(value);\n", "    return code != 0u;\n")
}
