//! The WGSL of bit fields: per field an encode function that returns its code in the low
//! bits and a decode function that takes it back, and the conversion helpers they call. The
//! pack function shifts each code into place and combines a word's codes with `|`.
//!
//! Exact conversions keep [`crate::encoding`]'s contracts bit for bit with integer operations
//! only (the decodes of unorm, snorm, octahedral and RGBM are f32 arithmetic, within a few ulp
//! of the mirror); fast conversions use f32 arithmetic and builtins where the encoding has a
//! fast form (unorm, half, octahedral, RGBM), one code from the exact ones at most (for
//! octahedral and RGBM, which name some values by two codes, two steps of the decoded value).

use crate::convert::max_code;
use crate::encoding::{BitField, Encoding};
use crate::layout::{Conversions, Field};

use super::{Lanes, HALF, RGB9E5, RGB9E5_MANTISSA, SNORM_FROM_F32, UNORM_FROM_F32};

/// `<prefix>_<verb>_field_<index>_bits`: the functions of bit field `index` (the field's place
/// in the layout, not its name: naga's GLSL writer would rename a name with `__` or one that
/// another collapses into, and the GLSL includes call these by name).
pub(super) fn function_name(prefix: &str, verb: &str, index: usize) -> String {
    format!("{prefix}_{verb}_field_{index}_bits")
}

/// Joins per-component codes (`codes`, a vector of `components` lanes) into one code, x in
/// the low bits.
fn joined(codes: &str, components: usize, each: u32) -> String {
    if components == 1 {
        return codes.to_string();
    }
    let parts: Vec<String> = "xyzw"[..components]
        .chars()
        .enumerate()
        .map(|(index, lane)| match index {
            0 => format!("{codes}.{lane}"),
            _ => format!("({codes}.{lane} << {}u)", each * index as u32),
        })
        .collect();
    parts.join(" | ")
}

/// A splat of a `u32` over `lanes`: `4u` or `vec3<u32>(4u)`.
fn splat(lanes: Lanes, value: u32) -> String {
    lanes.literal("u32", &[format!("{value}u")])
}

/// A splat of an `f32` over `lanes`.
fn splat_f32(lanes: Lanes, value: f32) -> String {
    lanes.literal("f32", &[format!("{value:?}")])
}

/// The encode and decode functions of a bit field, under `conversions`.
pub(super) fn functions(
    prefix: &str,
    index: usize,
    field: &Field,
    bit_field: BitField,
    conversions: Conversions,
) -> String {
    let components = field.ty.components;
    let each = bit_field.component_bits(components);
    let lanes = Lanes(components);
    let ty = field.ty.wgsl();
    let fast = !conversions.is_exact_for_encoding(bit_field.encoding);
    let max = max_code(each);
    let reciprocal = |bits: u32| splat_f32(lanes, 1.0 / max_code(bits) as f32);
    // The codes of every component, as a vector of `lanes`, from `value`.
    let (encode, decode) = match bit_field.encoding {
        Encoding::Unorm if fast => (
            format!(
                "    let codes = {}(clamp(value, {}, {}) * {} + {});\n    return {};\n",
                lanes.of("u32"),
                splat_f32(lanes, 0.0),
                splat_f32(lanes, 1.0),
                splat_f32(lanes, max as f32),
                splat_f32(lanes, 0.5),
                joined("codes", components, each)
            ),
            unorm_decode(lanes, each, &reciprocal(each)),
        ),
        Encoding::Unorm => (
            format!(
                "    let codes = {prefix}_{}_to_unorm(value, {}, {}, {});\n    return {};\n",
                lanes.name(),
                splat(lanes, each),
                splat(lanes, max),
                splat(lanes, 150 - each),
                joined("codes", components, each)
            ),
            unorm_decode(lanes, each, &reciprocal(each)),
        ),
        Encoding::Snorm => (
            format!(
                "    let codes = {prefix}_{}_to_snorm(value, {}, {}, {}, {});\n    return {};\n",
                lanes.name(),
                splat(lanes, each - 1),
                splat(lanes, max >> 1),
                splat(lanes, 150 - (each - 1)),
                splat(lanes, max),
                joined("codes", components, each)
            ),
            format!(
                "{}    return {prefix}_{}_from_snorm(codes, {}, {});\n",
                split_codes(lanes, each),
                lanes.name(),
                splat(lanes, 32 - each),
                reciprocal(each - 1)
            ),
        ),
        Encoding::Uint => (
            format!(
                "    let codes = min(value, {});\n    return {};\n",
                splat(lanes, max),
                joined("codes", components, each)
            ),
            format!("{}    return codes;\n", split_codes(lanes, each)),
        ),
        Encoding::Sint => {
            let highest = i64::from(max >> 1);
            let bound = |value: i64| lanes.literal("i32", &[value.to_string()]);
            (
                format!(
                    "    let codes = {}(clamp(value, {}, {})) & {};\n    return {};\n",
                    if components == 1 {
                        "bitcast<u32>".to_string()
                    } else {
                        format!("bitcast<{}>", lanes.of("u32"))
                    },
                    bound(-highest - 1),
                    bound(highest),
                    splat(lanes, max),
                    joined("codes", components, each)
                ),
                // The top bit moved to bit 31, then shifted back arithmetically.
                format!(
                    "{}    return bitcast<{}>(codes << {up}) >> {up};\n",
                    split_codes(lanes, each),
                    lanes.of("i32"),
                    up = splat(lanes, 32 - each)
                ),
            )
        }
        Encoding::Bool => (
            "    return u32(value);\n".to_string(),
            "    return code != 0u;\n".to_string(),
        ),
        Encoding::Half => {
            let encode = if fast {
                match components {
                    1 => "    return pack2x16float(vec2<f32>(value, 0.0));\n".to_string(),
                    _ => "    return pack2x16float(value);\n".to_string(),
                }
            } else {
                format!(
                    "    let codes = {prefix}_{}_to_half(value);\n    return {};\n",
                    lanes.name(),
                    joined("codes", components, each)
                )
            };
            let decode = match components {
                1 => "    return unpack2x16float(code).x;\n".to_string(),
                _ => "    return unpack2x16float(code);\n".to_string(),
            };
            (encode, decode)
        }
        Encoding::Rgb9e5 => (
            format!("    return {prefix}_f32x3_to_rgb9e5(value);\n"),
            format!("    return {prefix}_f32x3_from_rgb9e5(code);\n"),
        ),
        Encoding::Octahedral => (
            format!(
                "    return {prefix}_octahedral_from_f32x3{}(value, {each}u);\n",
                if fast { "_fast" } else { "" }
            ),
            format!(
                "    return {prefix}_f32x3_from_octahedral(code, {each}u, {:?});\n",
                1.0 / max as f32
            ),
        ),
        Encoding::Rgbm(range) => (
            format!(
                "    return {prefix}_rgbm_from_f32x3{}(value, {:?});\n",
                if fast { "_fast" } else { "" },
                range.get()
            ),
            format!(
                "    return {prefix}_f32x3_from_rgbm(code, {:?});\n",
                range.get()
            ),
        ),
    };
    let encode_name = function_name(prefix, "encode", index);
    let decode_name = function_name(prefix, "decode", index);
    let mode = if fast { ", fast conversions" } else { "" };
    format!(
        "// `{}`: {bit_field}{mode}; the code in the low {} bits.\n\
         fn {encode_name}(value: {ty}) -> u32 {{\n{encode}}}\n\n\
         fn {decode_name}(code: u32) -> {ty} {{\n{decode}}}\n\n",
        field.name, bit_field.bits
    )
}

/// `let codes = ...;`: the components' codes of a field's code, one per lane.
fn split_codes(lanes: Lanes, each: u32) -> String {
    if lanes.0 == 1 {
        return "    let codes = code;\n".to_string();
    }
    let offsets: Vec<String> = (0..lanes.0)
        .map(|index| format!("{}u", each * index as u32))
        .collect();
    format!(
        "    let codes = ({}(code) >> {}) & {};\n",
        lanes.of("u32"),
        lanes.literal("u32", &offsets),
        splat(lanes, max_code(each))
    )
}

/// Unorm decode: each code times the correctly rounded reciprocal of its largest code.
fn unorm_decode(lanes: Lanes, each: u32, reciprocal: &str) -> String {
    format!(
        "{}    return {}(codes) * {reciprocal};\n",
        split_codes(lanes, each),
        lanes.of("f32")
    )
}

/// The conversion helpers a bit field's functions call, each a complete WGSL text (the
/// caller writes each distinct text once).
pub(super) fn helpers(
    prefix: &str,
    field: &Field,
    bit_field: BitField,
    conversions: Conversions,
) -> Vec<String> {
    let lanes = Lanes(field.ty.components);
    let fast = !conversions.is_exact_for_encoding(bit_field.encoding);
    match bit_field.encoding {
        Encoding::Unorm if !fast => vec![lanes.fill(UNORM_FROM_F32, prefix)],
        Encoding::Snorm => vec![
            lanes.fill(UNORM_FROM_F32, prefix),
            lanes.fill(SNORM_FROM_F32, prefix),
        ],
        Encoding::Half if !fast => {
            super::small_float_helpers(prefix, "unsigned_half", HALF, &vec![10; lanes.0])
        }
        Encoding::Rgb9e5 => vec![
            Lanes(1).fill(RGB9E5_MANTISSA, prefix),
            Lanes(3).fill(RGB9E5_MANTISSA, prefix),
            Lanes(3).fill(RGB9E5, prefix),
        ],
        Encoding::Octahedral if fast => vec![
            Lanes(1).fill(FAST_OCTAHEDRAL, prefix),
            Lanes(1).fill(OCTAHEDRAL_DECODE, prefix),
        ],
        Encoding::Octahedral => vec![
            Lanes(2).fill(SCALED_QUOTIENT, prefix),
            Lanes(1).fill(OCTAHEDRAL, prefix),
            Lanes(1).fill(OCTAHEDRAL_DECODE, prefix),
        ],
        Encoding::Rgbm(_) if fast => vec![
            Lanes(1).fill(FAST_RGBM, prefix),
            Lanes(1).fill(RGBM_DECODE, prefix),
        ],
        Encoding::Rgbm(_) => vec![
            Lanes(1).fill(SCALED_QUOTIENT, prefix),
            Lanes(3).fill(SCALED_QUOTIENT, prefix),
            Lanes(1).fill(RGBM, prefix),
            Lanes(1).fill(RGBM_DECODE, prefix),
        ],
        _ => Vec::new(),
    }
}

const SCALED_QUOTIENT: &str = "\
// floor(((2^bits - 1) numerator + bias) / denominator), exactly, for numerator <= denominator
// < 2^31 and bias < denominator: bits steps of binary long division give floor(2^bits
// numerator / denominator) and its remainder in 32-bit integers, and taking numerator away
// and adding bias moves the quotient by at most one either way. The loop's count is the same
// for every fragment, so they never diverge.
fn PREFIX_LANES_scaled_quotient(numerator: UINTS, denominator: UINTS, bias: UINTS, bits: u32) -> UINTS {
    let whole = UINTS(numerator >= denominator);
    var quotient = whole;
    var remainder = numerator - whole * denominator;
    for (var step = 0u; step < bits; step++) {
        remainder = remainder << UINTS(1u);
        let bit = UINTS(remainder >= denominator);
        quotient = (quotient << UINTS(1u)) | bit;
        remainder = remainder - bit * denominator;
    }
    let up = UINTS(remainder + bias >= numerator + denominator);
    let down = UINTS(remainder + bias < numerator);
    return quotient + up - down;
}

";

const OCTAHEDRAL: &str = "\
// Octahedral encode (Cigolle et al. 2014), exact: p = n.xy / (|x| + |y| + |z|), folded for
// z < 0 to (1 - |p.yx|) * sign_not_zero(p), mapped to [0, 1] and rounded half up to
// bits-bit codes, x in the low bits. The magnitudes are aligned to the largest one's exponent
// with 28 bits below its leading one, each coordinate (1 +- along / sum) / 2 is a ratio of
// integer sums, and scaled_quotient rounds it. NaN components count as 0, the zero vector
// encodes as +z, and -0.0 is not negative.
fn PREFIX_octahedral_from_f32x3(normal: vec3<f32>, bits: u32) -> u32 {
    let signed = bitcast<vec3<u32>>(normal);
    let unsigned = signed & vec3<u32>(0x7fffffffu);
    let magnitude = unsigned * vec3<u32>(unsigned <= vec3<u32>(0x7f800000u));
    let negative = (signed >> vec3<u32>(31u)) * vec3<u32>(magnitude != vec3<u32>(0u));
    let exponent_field = magnitude >> vec3<u32>(23u);
    let significand = (magnitude & vec3<u32>(0x7fffffu)) | (vec3<u32>(exponent_field != vec3<u32>(0u)) << vec3<u32>(23u));
    let exponent = max(exponent_field, vec3<u32>(1u));
    let largest = max(exponent.x, max(exponent.y, exponent.z));
    let aligned = (significand << vec3<u32>(4u)) >> min(vec3<u32>(largest) - exponent, vec3<u32>(31u));
    let z = aligned.z + u32(aligned.x + aligned.y + aligned.z == 0u);
    let sum = aligned.x + aligned.y + z;
    let along = aligned.xy + vec2<u32>(negative.z * z);
    let numerator = vec2<u32>(sum) + along - vec2<u32>(2u) * along * negative.xy;
    let codes = PREFIX_f32x2_scaled_quotient(numerator, vec2<u32>(2u * sum), vec2<u32>(sum), bits);
    return codes.x | (codes.y << bits);
}

";

const FAST_OCTAHEDRAL: &str = "\
// Octahedral encode, fast: Cigolle et al.'s f32 arithmetic, the adapter's division and
// rounding: the decoded normal within twice the quantisation bound of the exact one (on the
// fold's border the other of two twin codes may come out); the zero vector is undefined.
fn PREFIX_octahedral_from_f32x3_fast(normal: vec3<f32>, bits: u32) -> u32 {
    let projected = normal.xy / (abs(normal.x) + abs(normal.y) + abs(normal.z));
    let sign_not_zero = vec2<f32>(projected >= vec2<f32>(0.0)) * 2.0 - vec2<f32>(1.0);
    let folded = select(projected, (vec2<f32>(1.0) - abs(projected.yx)) * sign_not_zero, normal.z < 0.0);
    let max_code = f32((1u << bits) - 1u);
    let codes = vec2<u32>(clamp(folded * 0.5 + vec2<f32>(0.5), vec2<f32>(0.0), vec2<f32>(1.0)) * max_code + vec2<f32>(0.5));
    return codes.x | (codes.y << bits);
}

";

const OCTAHEDRAL_DECODE: &str = "\
// Octahedral decode: the coordinates back to [-1, 1], the lower hemisphere unfolded (Stubbe's
// branch-free form), normalized.
fn PREFIX_f32x3_from_octahedral(code: u32, bits: u32, reciprocal: f32) -> vec3<f32> {
    let codes = (vec2<u32>(code) >> vec2<u32>(0u, bits)) & vec2<u32>((1u << bits) - 1u);
    let folded = vec2<f32>(codes) * reciprocal * 2.0 - vec2<f32>(1.0);
    let z = 1.0 - abs(folded.x) - abs(folded.y);
    let fold = max(-z, 0.0);
    let unfolded = folded - fold * (vec2<f32>(folded >= vec2<f32>(0.0)) * 2.0 - vec2<f32>(1.0));
    return normalize(vec3<f32>(unfolded, z));
}

";

const RGBM: &str = "\
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

const FAST_RGBM: &str = "\
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

const RGBM_DECODE: &str = "\
// RGBM decode: rgb * m * range, each code over 255.
fn PREFIX_f32x3_from_rgbm(code: u32, range: f32) -> vec3<f32> {
    let unit = vec4<f32>((vec4<u32>(code) >> vec4<u32>(0u, 8u, 16u, 24u)) & vec4<u32>(0xffu)) * (1.0 / 255.0);
    return unit.xyz * (unit.w * range);
}

";
