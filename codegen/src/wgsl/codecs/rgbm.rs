//! RGBM (`gbuffer_core::codecs::rgbm`; Karis 2009), laid out as rgba8. The exact encode is
//! the mirror's fixed-point algorithm with [`scaled_quotient`]
//! rounding the ratios; the fast encode is Karis's f32 arithmetic; the decode is f32
//! arithmetic. The shading library's `rgbm_encode` and `rgbm_decode` (module `hdr`, for rgba8
//! render targets and textures) are this WGSL ([`exact_functions`]): the exact encode's codes
//! over 255, and the decode of four unorm values, which a filtered texture sample also is.

use gbuffer_core::Symbols;

use super::{scaled_quotient, BitField, Functions, Lanes};

/// The exact encode (`PREFIX_rgbm_from_f32x3`).
const WGSL_EXACT: &str = "\
// RGBM encode (Karis 2009), exact, laid out as rgba8: the multiplier m = ceil(255 max / range)
// (at least 1) in bits 24-31, each channel round(255 c / (m / 255 range)) below it. Channels
// are clamped to [0, range] (NaN to 0) and taken in multiples of range 2^-22, rounded down;
// range is a normal float with at most 16 significant bits, so range 2^(22 - floor(log2
// range)) is its significand halved, exactly.
fn PREFIX_rgbm_from_f32x3(value: vec3<f32>, range: f32) -> u32 {
    let range_bits = bitcast<u32>(range);
    let range_fixed = ((range_bits & 0x7fffffu) | 0x800000u) >> 1u;
    let bits = bitcast<vec3<u32>>(value);
    let clamped = min(bits, vec3<u32>(range_bits)) * vec3<u32>(bits <= vec3<u32>(0x7f800000u));
    let exponent_field = clamped >> vec3<u32>(23u);
    let significand = (clamped & vec3<u32>(0x7fffffu)) | (vec3<u32>(exponent_field != vec3<u32>(0u)) << vec3<u32>(23u));
    let shift = vec3<u32>((range_bits >> 23u) + 1u) - max(exponent_field, vec3<u32>(1u));
    let fixed = significand >> min(shift, vec3<u32>(31u));
    let largest = max(fixed.x, max(fixed.y, fixed.z));
    let multiplier = max(PREFIX_f32_scaled_quotient(largest, range_fixed, range_fixed - 1u, 8u), 1u);
    let denominator = multiplier * range_fixed;
    let codes = PREFIX_f32x3_scaled_quotient(vec3<u32>(255u) * fixed, vec3<u32>(denominator), vec3<u32>(denominator >> 1u), 8u);
    return codes.x | (codes.y << 8u) | (codes.z << 16u) | (multiplier << 24u);
}

";

/// The fast encode (`PREFIX_rgbm_from_f32x3_fast`).
const WGSL_FAST: &str = "\
// RGBM encode, fast: Karis's f32 arithmetic and rounding: each decoded channel within two
// steps of the exact one (the multiplier may come out one step apart, the channels trading it).
fn PREFIX_rgbm_from_f32x3_fast(value: vec3<f32>, range: f32) -> u32 {
    let colour = clamp(value, vec3<f32>(0.0), vec3<f32>(range));
    let multiplier = max(ceil(max(colour.x, max(colour.y, colour.z)) / range * 255.0), 1.0);
    let unit = clamp(vec4<f32>(colour * (255.0 / (multiplier * range)), multiplier / 255.0), vec4<f32>(0.0), vec4<f32>(1.0));
    let codes = vec4<u32>(unit * 255.0 + vec4<f32>(0.5)) << vec4<u32>(0u, 8u, 16u, 24u);
    return codes.x | codes.y | codes.z | codes.w;
}

";

/// The decodes (`PREFIX_rgbm_decode` of four unorm values, `PREFIX_f32x3_from_rgbm` of a
/// word).
const WGSL_DECODE: &str = "\
// RGBM decode (Karis 2009) of four unorm values (a word's codes over 255, or an rgba8
// texture's sample): rgb * m * range.
fn PREFIX_rgbm_decode(unit: vec4<f32>, range: f32) -> vec3<f32> {
    return unit.xyz * (unit.w * range);
}

// RGBM decode of a word.
fn PREFIX_f32x3_from_rgbm(code: u32, range: f32) -> vec3<f32> {
    let unit = vec4<f32>((vec4<u32>(code) >> vec4<u32>(0u, 8u, 16u, 24u)) & vec4<u32>(0xffu)) * (1.0 / 255.0);
    return PREFIX_rgbm_decode(unit, range);
}

";

/// The exact encode and the decodes with the helpers they call, named for `symbols`' layout
/// (or the shading library's prefix).
pub fn exact_functions(symbols: &Symbols) -> Vec<String> {
    vec![
        Lanes(1).fill(scaled_quotient::WGSL, symbols),
        Lanes(3).fill(scaled_quotient::WGSL, symbols),
        Lanes(1).fill(WGSL_EXACT, symbols),
        Lanes(1).fill(WGSL_DECODE, symbols),
    ]
}

/// An RGBM bit field's WGSL: the exact or fast encode and the decodes.
pub fn functions(field: &BitField) -> Functions {
    let symbols = field.symbols;
    let range = field.range.unwrap_or(1.0);
    let helpers = match field.fast {
        true => vec![
            Lanes(1).fill(WGSL_FAST, symbols),
            Lanes(1).fill(WGSL_DECODE, symbols),
        ],
        false => exact_functions(symbols),
    };
    let fast = if field.fast { "_fast" } else { "" };
    Functions {
        encode: format!(
            "    return {}(value, {range:?});\n",
            symbols.codec_function(&format!("rgbm_from_f32x3{fast}"))
        ),
        decode: format!(
            "    return {}(code, {range:?});\n",
            symbols.codec_helper(3, "from_rgbm")
        ),
        helpers,
    }
}
