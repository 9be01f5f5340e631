//! Integers (`gbuffer_core::codecs::integer`): unsigned ones clamped with `min`, signed ones
//! with `clamp` into an `n`-bit two's complement and sign-extended back by two shifts.

use gbuffer_core::codecs::max_code;

use super::{BitField, Functions};

/// An unsigned bit field's WGSL: `min`, and the codes split.
pub fn uint_functions(field: &BitField) -> Functions {
    Functions {
        encode: format!(
            "    let codes = min(value, {});\n    return {};\n",
            field.lanes.splat(max_code(field.each)),
            field.joined("codes")
        ),
        decode: format!("{}    return codes;\n", field.split_codes()),
        helpers: Vec::new(),
    }
}

/// A signed bit field's WGSL: `clamp`, and the codes sign-extended.
pub fn sint_functions(field: &BitField) -> Functions {
    let lanes = field.lanes;
    let highest = i64::from(max_code(field.each) >> 1);
    let bound = |value: i64| lanes.literal("i32", &[value.to_string()]);
    let to_bits = match lanes.0 {
        1 => "bitcast<u32>".to_string(),
        _ => format!("bitcast<{}>", lanes.of("u32")),
    };
    Functions {
        encode: format!(
            "    let codes = {to_bits}(clamp(value, {}, {})) & {};\n    return {};\n",
            bound(-highest - 1),
            bound(highest),
            lanes.splat(max_code(field.each)),
            field.joined("codes")
        ),
        // The top bit moved to bit 31, then shifted back arithmetically.
        decode: format!(
            "{}    return bitcast<{}>(codes << {up}) >> {up};\n",
            field.split_codes(),
            lanes.of("i32"),
            up = lanes.splat(32 - field.each)
        ),
        helpers: Vec::new(),
    }
}
