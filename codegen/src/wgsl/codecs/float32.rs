//! IEEE binary32 bit for bit (`gbuffer_core::codecs::float32`): a bitcast each way.

use super::{BitField, Functions};

/// An f32 bit field's WGSL: its bits.
pub fn functions(_: &BitField) -> Functions {
    Functions::inline(
        "    return bitcast<u32>(value);\n",
        "    return bitcast<f32>(code);\n",
    )
}
