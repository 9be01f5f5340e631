//! Octahedral normals (`gbuffer_core::codecs::octahedral`; Cigolle et al. 2014). The exact
//! encode is the integer algorithm of the mirror, `octahedral_from_f32`, with
//! [`scaled_quotient`] rounding each coordinate; the fast encode is the
//! map in f32 arithmetic ([`WGSL_FOLD`], the mirror's `octahedral_fold`); the decode unfolds
//! ([`WGSL_UNFOLD`]) and normalizes. The shading library's `octahedral_encode` and
//! `octahedral_decode` (module `normals`) are the map's two halves ([`map_functions`]).

use gbuffer_core::codecs::max_code;
use gbuffer_core::Symbols;

use super::{scaled_quotient, BitField, Functions, Lanes};

/// The map's first half in f32 arithmetic (`PREFIX_octahedral_fold`): what the fast encode
/// is made of.
pub const WGSL_FOLD: &str = "\
// Octahedral map (Cigolle et al. 2014): a non-zero vector to [-1, 1]^2, p = n.xy / (|x| + |y|
// + |z|), the lower hemisphere folded over the diagonals to (1 - |p.yx|) * sign_not_zero(p)
// (+1 for zero, so the fold keeps the zero's side). f32 arithmetic, no branch; the zero vector
// divides by zero.
fn PREFIX_octahedral_fold(normal: vec3<f32>) -> vec2<f32> {
    let projected = normal.xy / (abs(normal.x) + abs(normal.y) + abs(normal.z));
    let sign_not_zero = vec2<f32>(projected >= vec2<f32>(0.0)) * 2.0 - vec2<f32>(1.0);
    return select(projected, (vec2<f32>(1.0) - abs(projected.yx)) * sign_not_zero, normal.z < 0.0);
}

";

/// The map's second half (`PREFIX_octahedral_unfold`): what the decode is made of.
pub const WGSL_UNFOLD: &str = "\
// The octahedral map's inverse: [-1, 1]^2 to a unit vector, the lower hemisphere unfolded
// (Stubbe's branch-free form), normalized.
fn PREFIX_octahedral_unfold(folded: vec2<f32>) -> vec3<f32> {
    let z = 1.0 - abs(folded.x) - abs(folded.y);
    let fold = max(-z, 0.0);
    let unfolded = folded - fold * (vec2<f32>(folded >= vec2<f32>(0.0)) * 2.0 - vec2<f32>(1.0));
    return normalize(vec3<f32>(unfolded, z));
}

";

/// The exact encode (`PREFIX_octahedral_from_f32x3`).
const WGSL_EXACT: &str = "\
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

/// The fast encode (`PREFIX_octahedral_from_f32x3_fast`).
const WGSL_FAST: &str = "\
// Octahedral encode, fast: the map in f32 arithmetic, the adapter's division and rounding: the
// decoded normal within twice the quantisation bound of the exact one (on the fold's border
// the other of two twin codes may come out); the zero vector is undefined.
fn PREFIX_octahedral_from_f32x3_fast(normal: vec3<f32>, bits: u32) -> u32 {
    let folded = PREFIX_octahedral_fold(normal);
    let max_code = f32((1u << bits) - 1u);
    let codes = vec2<u32>(clamp(folded * 0.5 + vec2<f32>(0.5), vec2<f32>(0.0), vec2<f32>(1.0)) * max_code + vec2<f32>(0.5));
    return codes.x | (codes.y << bits);
}

";

/// The decode (`PREFIX_f32x3_from_octahedral`).
const WGSL_DECODE: &str = "\
// Octahedral decode: the coordinates back to [-1, 1], then the map's inverse.
fn PREFIX_f32x3_from_octahedral(code: u32, bits: u32, reciprocal: f32) -> vec3<f32> {
    let codes = (vec2<u32>(code) >> vec2<u32>(0u, bits)) & vec2<u32>((1u << bits) - 1u);
    return PREFIX_octahedral_unfold(vec2<f32>(codes) * reciprocal * 2.0 - vec2<f32>(1.0));
}

";

/// The map's two halves, `PREFIX_octahedral_fold` and `PREFIX_octahedral_unfold`, named for
/// `symbols`' layout (or the shading library's prefix).
pub fn map_functions(symbols: &Symbols) -> Vec<String> {
    [WGSL_FOLD, WGSL_UNFOLD]
        .map(|text| Lanes(1).fill(text, symbols))
        .to_vec()
}

/// An octahedral bit field's WGSL: the exact or fast encode, the decode, and the map's halves
/// they call.
pub fn functions(field: &BitField) -> Functions {
    let (symbols, each) = (field.symbols, field.each);
    let fast = if field.fast { "_fast" } else { "" };
    let encode = match field.fast {
        true => vec![
            Lanes(1).fill(WGSL_FOLD, symbols),
            Lanes(1).fill(WGSL_FAST, symbols),
        ],
        false => vec![
            Lanes(2).fill(scaled_quotient::WGSL, symbols),
            Lanes(1).fill(WGSL_EXACT, symbols),
        ],
    };
    let decode = [WGSL_UNFOLD, WGSL_DECODE].map(|text| Lanes(1).fill(text, symbols));
    Functions {
        encode: format!(
            "    return {}(value, {each}u);\n",
            symbols.codec_function(&format!("octahedral_from_f32x3{fast}"))
        ),
        decode: format!(
            "    return {}(code, {each}u, {:?});\n",
            symbols.codec_helper(3, "from_octahedral"),
            1.0 / max_code(each) as f32
        ),
        helpers: [encode, decode.to_vec()].concat(),
    }
}
