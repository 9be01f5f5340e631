//! Signed normalized (`gbuffer_core::codecs::snorm`): the magnitude is unorm's exact code at
//! one bit fewer ([`unorm::WGSL_ENCODE`]), the sign applied to the
//! code; the decode sign-extends and scales.

use gbuffer_core::codecs::max_code;

use super::{unorm, BitField, Functions};

/// The exact encode and the decode, per lane (`PREFIX_LANES_to_snorm`,
/// `PREFIX_LANES_from_snorm`); the encode calls unorm's.
pub const WGSL: &str = "\
// Signed normalized encode, per lane: GL's round(clamp(value, -1, 1) * (2^(bits - 1) - 1)),
// halves away from zero, exact: the magnitude's unorm code at bits - 1 bits (NaN's is 0),
// negated in the bits-bit two's complement for a set sign bit (a multiply-free negation, as
// GLSL ES 3.00 has no `select` on integer vectors). magnitude_max and two_to_magnitude_bits
// are to_unorm's parameters at bits - 1 bits; mask is 2^bits - 1.
fn PREFIX_LANES_to_snorm(value: FLOATS, magnitude_max: FLOATS, two_to_magnitude_bits: FLOATS, mask: UINTS) -> UINTS {
    let value_bits = bitcast<UINTS>(value);
    let magnitude = bitcast<FLOATS>(value_bits & UINTS(0x7fffffffu));
    let code = PREFIX_LANES_to_unorm(magnitude, magnitude_max, two_to_magnitude_bits);
    let negative = value_bits >> UINTS(31u);
    return ((code ^ (UINTS(0u) - negative)) + negative) & mask;
}

// Signed normalized decode: max(code / (2^(bits - 1) - 1), -1), the code sign-extended by
// moving its top bit to bit 31 and shifting back arithmetically (up is 32 - bits).
fn PREFIX_LANES_from_snorm(code: UINTS, up: UINTS, reciprocal: FLOATS) -> FLOATS {
    let signed = bitcast<SINTS>(code << up) >> up;
    return max(FLOATS(signed) * reciprocal, FLOATS(-1.0));
}

";

/// A snorm bit field's WGSL: the exact encode and the decode helpers, per lane.
pub fn functions(field: &BitField) -> Functions {
    let (lanes, each) = (field.lanes, field.each);
    let max = max_code(each);
    Functions {
        encode: format!(
            "    let codes = {}(value, {}, {}, {});\n    return {};\n",
            field.helper("to_snorm"),
            lanes.splat_f32((max >> 1) as f32),
            lanes.splat_f32((1u32 << (each - 1)) as f32),
            lanes.splat(max),
            field.joined("codes")
        ),
        decode: format!(
            "{}    return {}(codes, {}, {});\n",
            field.split_codes(),
            field.helper("from_snorm"),
            lanes.splat(32 - each),
            field.reciprocal(each - 1)
        ),
        helpers: vec![field.fill(unorm::WGSL_ENCODE), field.fill(WGSL)],
    }
}
