//! Log luminance (`gbuffer_core::codecs::log_luminance`): the piecewise-linear logarithm is
//! the float's own bits read as fixed point, so both ways are integer operations per lane,
//! exact on every adapter.

use gbuffer_core::codecs::log_luminance::shift;
use gbuffer_core::codecs::max_code;

use super::{BitField, Functions};

/// The encode and decode, per lane (`PREFIX_LANES_to_log_luminance`,
/// `PREFIX_LANES_from_log_luminance`).
pub const WGSL: &str = "\
// Log luminance encode, per lane: the piecewise-linear log2 of the value over [2^-16, 2^16),
// which is its float's bits above 2^-16's read as fixed point, rounded half up to `shift` bits
// fewer, plus one (code 0 holds zero); exact, in integers. NaN and negatives (as unsigned
// integers, above infinity's bits), zero and values under 2^-16 give 0; the top saturates.
fn PREFIX_LANES_to_log_luminance(value: FLOATS, shift: UINTS, max_code: UINTS) -> UINTS {
    let bits = bitcast<UINTS>(value);
    let held = UINTS(bits <= UINTS(0x7f800000u)) * UINTS(bits >= UINTS(0x37800000u));
    let offset = min(bits, UINTS(0x7f800000u)) - UINTS(0x37800000u);
    let code = min(((offset + ((UINTS(1u) << shift) >> UINTS(1u))) >> shift) + UINTS(1u), max_code);
    return code * held;
}

// Log luminance decode, per lane, exact: the float whose bits are code - 1 steps above 2^-16's,
// zero for code 0 (the bits are zeroed before they become a float).
fn PREFIX_LANES_from_log_luminance(code: UINTS, shift: UINTS) -> FLOATS {
    let bits = (((code - UINTS(1u)) << shift) + UINTS(0x37800000u)) * UINTS(code != UINTS(0u));
    return bitcast<FLOATS>(bits);
}

";

/// A log luminance bit field's WGSL: the per-lane encode and decode.
pub fn functions(field: &BitField) -> Functions {
    let (lanes, each) = (field.lanes, field.each);
    Functions {
        encode: format!(
            "    let codes = {}(value, {}, {});\n    return {};\n",
            field.helper("to_log_luminance"),
            lanes.splat(shift(each)),
            lanes.splat(max_code(each)),
            field.joined("codes")
        ),
        decode: format!(
            "{}    return {}(codes, {});\n",
            field.split_codes(),
            field.helper("from_log_luminance"),
            lanes.splat(shift(each))
        ),
        helpers: vec![field.fill(WGSL)],
    }
}
