//! How the generated WGSL converts values to and from channel codes: exactly, or with WGSL's
//! pack builtins where a format has them.

use crate::codecs::Encoding;
use crate::format::Format;

/// How the WGSL converts values to and from channel codes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub enum Conversions {
    /// Steps no adapter can round its own way (integer operations on the float's bits, and
    /// float arithmetic only where every rounding and order gives one answer): the same words
    /// on every adapter as the Rust mirror, and portable to every backend.
    #[default]
    Exact,
    /// What engines write: WGSL's builtins where a format has one (`pack4x8unorm` for rgba8,
    /// `pack2x16unorm` for rg16, `pack2x16float` for rg16f), f32 arithmetic for rgb10_a2,
    /// `pack2x16float` with cut mantissas for r11f_g11f_b10f; the integer formats and r32f are
    /// exact either way. Bit fields: f32 arithmetic for unorm, octahedral and RGBM,
    /// `pack2x16float` for half; the others are exact either way. Fewer instructions; the
    /// rounding is the adapter's, so a channel's code can differ from the Rust mirror's by one
    /// (an octahedral normal or RGBM colour by two steps of its decoded value, as those name
    /// some values by two codes), and for the floats the adapter may flush values under 2^-14
    /// to zero and turn values past 65504 into infinity.
    /// `integration-tests/tests/gpu_packing.rs` and `gpu_bit_fields.rs` measure the deviation on the adapter.
    Fast,
}

// Both, exact first.
crate::named!(
    /// The name layout files and `#[gbuffer(conversions = ...)]` give them: `exact` or `fast`.
    Conversions {
        Exact => "exact",
        Fast => "fast",
    }
);

impl Conversions {
    /// Whether a format's encode is the exact one under these conversions (fast conversions
    /// replace it for rgba8, rg16, rg16f, rgb10_a2 and r11f_g11f_b10f).
    pub fn is_exact_for(self, format: Format) -> bool {
        self == Conversions::Exact
            || !(self.builtins(format).is_some()
                || matches!(format, Format::Rgb10A2 | Format::R11fG11fB10f))
    }

    /// Whether a bit field's encode is the exact one under these conversions (fast conversions
    /// replace it for unorm, half, octahedral and RGBM).
    pub fn is_exact_for_encoding(self, encoding: Encoding) -> bool {
        self == Conversions::Exact || !encoding.has_fast_form()
    }

    /// What the generated functions of a field with these conversions add to their names
    /// where the layout's conversions differ: `_exact` or `_fast`.
    pub fn name_suffix(self) -> &'static str {
        match self {
            Conversions::Exact => "_exact",
            Conversions::Fast => "_fast",
        }
    }

    /// The builtin pack and unpack functions for a format, under these conversions.
    pub fn builtins(self, format: Format) -> Option<(&'static str, &'static str)> {
        match (self, format) {
            (Conversions::Fast, Format::Rgba8) => Some(("pack4x8unorm", "unpack4x8unorm")),
            (Conversions::Fast, Format::Rg16) => Some(("pack2x16unorm", "unpack2x16unorm")),
            (Conversions::Fast, Format::Rg16f) => Some(("pack2x16float", "unpack2x16float")),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Named;

    #[test]
    fn conversions_are_found_by_their_names_only() {
        assert_eq!(Conversions::from_name("exact"), Some(Conversions::Exact));
        assert_eq!(Conversions::from_name("fast"), Some(Conversions::Fast));
        assert_eq!(Conversions::from_name("Fast"), None);
        assert_eq!(Conversions::from_name(""), None);
        assert_eq!(Conversions::Fast.name_suffix(), "_fast");
    }
}
