//! Shared-exponent rgb9e5 (`gbuffer_core::codecs::rgb9e5`; EXT_texture_shared_exponent): the
//! extension's algorithm evaluated exactly on the floats' bits, as the mirror does. The shading
//! library's `rgb9e5_encode` and `rgb9e5_decode` (module `hdr`) are this WGSL
//! ([`exact_functions`]).

use gbuffer_core::Symbols;

use super::{BitField, Functions, Lanes};

/// One mantissa per lane (`PREFIX_LANES_rgb9e5_mantissa`), filled for one and three lanes.
const WGSL_MANTISSA: &str = "\
// floor(value * 2^(24 - exponent) + 0.5) for non-negative f32 bits; past a shift of 25 the
// result is 0, as it is at 25 (the shift is never negative: no channel exceeds the largest).
fn PREFIX_LANES_rgb9e5_mantissa(bits: UINTS, exponent: UINTS) -> UINTS {
    let significand = (bits & UINTS(0x7fffffu)) | UINTS(0x800000u);
    let shift = min(UINTS(126u) + exponent - (bits >> UINTS(23u)), UINTS(25u));
    return (significand + ((UINTS(1u) << shift) >> UINTS(1u))) >> shift;
}

";

/// The encode and decode (`PREFIX_f32x3_to_rgb9e5`, `PREFIX_f32x3_from_rgb9e5`).
const WGSL: &str = "\
// Shared-exponent rgb9e5 (EXT_texture_shared_exponent), its algorithm evaluated exactly: the
// channels clamped to [0, 65408] (NaN to 0; as unsigned integers, NaN and negatives lie above
// infinity's bits), the exponent max(-16, floor(log2(largest))) + 16 read from the exponent
// field, one more where the largest channel's mantissa rounds up to 512, and each mantissa
// floor(channel / 2^(exponent - 24) + 0.5) by shifting the significand with half its last
// place added. Red in bits 0-8, green 9-17, blue 18-26, the exponent 27-31.
fn PREFIX_f32x3_to_rgb9e5(value: vec3<f32>) -> u32 {
    let bits = bitcast<vec3<u32>>(value);
    let clamped = min(bits, vec3<u32>(0x477f8000u)) * vec3<u32>(bits <= vec3<u32>(0x7f800000u));
    let largest = max(clamped.x, max(clamped.y, clamped.z));
    let rough_exponent = max(largest >> 23u, 111u) - 111u;
    let exponent = rough_exponent + u32(PREFIX_f32_rgb9e5_mantissa(largest, rough_exponent) == 512u);
    let mantissas = PREFIX_f32x3_rgb9e5_mantissa(clamped, vec3<u32>(exponent)) << vec3<u32>(0u, 9u, 18u);
    return mantissas.x | mantissas.y | mantissas.z | (exponent << 27u);
}

// Decodes rgb9e5, exactly: each mantissa times 2^(exponent - 24).
fn PREFIX_f32x3_from_rgb9e5(word: u32) -> vec3<f32> {
    let scale = bitcast<f32>(((word >> 27u) + 103u) << 23u);
    return vec3<f32>((vec3<u32>(word) >> vec3<u32>(0u, 9u, 18u)) & vec3<u32>(0x1ffu)) * scale;
}

";

/// The encode and decode with the helpers they call, named for `symbols`' layout (or the
/// shading library's prefix).
pub fn exact_functions(symbols: &Symbols) -> Vec<String> {
    vec![
        Lanes(1).fill(WGSL_MANTISSA, symbols),
        Lanes(3).fill(WGSL_MANTISSA, symbols),
        Lanes(1).fill(WGSL, symbols),
    ]
}

/// An rgb9e5 bit field's WGSL: calls of the encode and decode.
pub fn functions(field: &BitField) -> Functions {
    Functions {
        encode: format!(
            "    return {}(value);\n",
            field.symbols.codec_helper(3, "to_rgb9e5")
        ),
        decode: format!(
            "    return {}(code);\n",
            field.symbols.codec_helper(3, "from_rgb9e5")
        ),
        helpers: exact_functions(field.symbols),
    }
}
