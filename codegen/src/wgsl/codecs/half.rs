//! IEEE binary16 (`gbuffer_core::codecs::half`). The exact encode rounds with
//! [`small_float`](super::small_float)'s integer algorithm, because WGSL lets `pack2x16float`
//! round either way; the fast form is `pack2x16float`, the adapter's rounding (which may flush
//! denormals and overflow to infinity). Both decode with `unpack2x16float`, which widening
//! makes exact, and which naga validates only with `Capabilities::SHADER_FLOAT16_IN_FLOAT32`.

use gbuffer_core::Symbols;

use super::{BitField, Functions};

/// The name of [`WGSL_ENCODE`]'s function, for [`Symbols::codec_helper`].
pub const ENCODE_HELPER: &str = "to_half";

/// The exact encode, per lane (`PREFIX_LANES_to_half`): the sign beside the magnitude's
/// rounding (`PREFIX_LANES_round_to_unsigned_half`, from
/// [`small_float::helpers`](super::small_float::helpers)).
pub const WGSL_ENCODE: &str = "\
// IEEE binary16 from f32, sign kept, saturating at +-65504; NaN gives 0.
fn PREFIX_LANES_to_half(value: FLOATS) -> UINTS {
    let bits = bitcast<UINTS>(value);
    let magnitude = bits & UINTS(0x7fffffffu);
    let signed = PREFIX_LANES_round_to_unsigned_half(magnitude) | ((bits >> UINTS(16u)) & UINTS(0x8000u));
    return signed * UINTS(magnitude <= UINTS(0x7f800000u));
}

";

/// The helpers of the exact encode of `lanes` halves.
fn helpers(symbols: &Symbols, lanes: usize) -> Vec<String> {
    super::small_float::helpers(symbols, "unsigned_half", WGSL_ENCODE, &vec![10; lanes])
}

/// A half bit field's WGSL: the exact encode, or `pack2x16float`; `unpack2x16float`.
pub fn functions(field: &BitField) -> Functions {
    let lanes = field.lanes;
    let scalar = lanes.0 == 1;
    let encode = match (field.fast, scalar) {
        (true, true) => "    return pack2x16float(vec2<f32>(value, 0.0));\n".to_string(),
        (true, false) => "    return pack2x16float(value);\n".to_string(),
        (false, _) => format!(
            "    let codes = {}(value);\n    return {};\n",
            field.helper(ENCODE_HELPER),
            field.joined("codes")
        ),
    };
    let decode = match scalar {
        true => "    return unpack2x16float(code).x;\n",
        false => "    return unpack2x16float(code);\n",
    };
    Functions {
        encode,
        decode: decode.to_string(),
        helpers: match field.fast {
            true => Vec::new(),
            false => helpers(field.symbols, lanes.0),
        },
    }
}
