//! Unsigned normalized (`gbuffer_core::codecs::unorm`). The exact encode rounds in f32
//! arithmetic and checks its rounding with one more product, exact by construction (the proof
//! is the mirror's, `unorm_from_f32`); the fast form is that first rounding alone. The decode
//! multiplies by the largest code's correctly rounded reciprocal.

use gbuffer_core::codecs::max_code;

use super::{BitField, Functions};

/// The name of [`WGSL_ENCODE`]'s function, for
/// [`Symbols::codec_helper`](gbuffer_core::Symbols::codec_helper).
pub const ENCODE_HELPER: &str = "to_unorm";

/// The exact encode, per lane (`PREFIX_LANES_to_unorm`).
pub const WGSL_ENCODE: &str = "\
// Unsigned normalized encode, per lane: floor(0.5 + max_code * clamp(value, 0, 1)), exact.
// NaN and negatives give 0 (as unsigned integers their bits lie above infinity's; saturate's
// NaN is the adapter's, so it is not trusted), values from 1.0 up max_code. The candidate,
// rounded in f32 as engines round, is the code or one above it whatever the adapter's rounding;
// it is one too high exactly when x * max_code + 0.5 < candidate, tested as x * two_to_bits -
// candidate + 0.5 < x, whose every step is exact (a power-of-two product, Sterbenz's lemma, a
// sum exact wherever it could equal x), so no rounding mode, fused multiply-add or reordering
// changes the answer (the proof: unorm_from_f32 in gbuffer-core). Float selects only: GLSL ES
// 3.00 has none on integer vectors. max_code = 2^bits - 1 and two_to_bits = 2^bits.
fn PREFIX_LANES_to_unorm(value: FLOATS, max_code: FLOATS, two_to_bits: FLOATS) -> UINTS {
    let x = select(FLOATS(0.0), saturate(value), bitcast<UINTS>(value) <= UINTS(0x7f800000u));
    let candidate = floor(x * max_code + FLOATS(0.5));
    let below = (x * two_to_bits - candidate) + FLOATS(0.5);
    return UINTS(candidate - select(FLOATS(0.0), FLOATS(1.0), below < x));
}

";

/// The fast encode of the `rgb10_a2` format (`ENCODE` is the function's name).
pub const WGSL_FAST_RGB10_A2: &str = "\
// Fast conversions: the codes are rounded in f32 arithmetic, one code from the exact ones at
// most (where the product lies within f32's rounding of a half-integer); the decode is exact.
fn ENCODE(c: vec4<f32>) -> u32 {
    let scale = vec4<f32>(1023.0, 1023.0, 1023.0, 3.0);
    let codes = vec4<u32>(clamp(c, vec4<f32>(0.0), vec4<f32>(1.0)) * scale + vec4<f32>(0.5));
    return codes.x | (codes.y << 10u) | (codes.z << 20u) | (codes.w << 30u);
}

";

/// The fast encode of the `rgba8` format for GLSL ES 3.00, which has no `packUnorm4x8`
/// (`ENCODE` is the function's name).
pub const WGSL_FAST_RGBA8_ARITHMETIC: &str = "\
// Fast conversions for GLSL ES 3.00, which has no packUnorm4x8: rounded in f32 arithmetic like
// the builtin (one code from the exact ones at most); the decode is the exact one.
fn ENCODE(c: vec4<f32>) -> u32 {
    let codes = vec4<u32>(clamp(c, vec4<f32>(0.0), vec4<f32>(1.0)) * 255.0 + vec4<f32>(0.5));
    let placed = codes << vec4<u32>(0u, 8u, 16u, 24u);
    return placed.x | placed.y | placed.z | placed.w;
}

";

/// The decode body of a unorm bit field: each code times the correctly rounded reciprocal of
/// its largest code (within 1 ulp of the exact quotient; the largest code decodes to 1.0).
fn decode(field: &BitField) -> String {
    format!(
        "{}    return {}(codes) * {};\n",
        field.split_codes(),
        field.lanes.of("f32"),
        field.reciprocal(field.each)
    )
}

/// A unorm bit field's WGSL: the exact encode (the engines' f32 rounding, checked), or that
/// rounding alone; the decode, each code times its largest code's reciprocal.
pub fn functions(field: &BitField) -> Functions {
    let (lanes, each) = (field.lanes, field.each);
    let max = max_code(each);
    let encode = if field.fast {
        format!(
            "    let codes = {}(clamp(value, {}, {}) * {} + {});\n    return {};\n",
            lanes.of("u32"),
            lanes.splat_f32(0.0),
            lanes.splat_f32(1.0),
            lanes.splat_f32(max as f32),
            lanes.splat_f32(0.5),
            field.joined("codes")
        )
    } else {
        format!(
            "    let codes = {}(value, {}, {});\n    return {};\n",
            field.helper(ENCODE_HELPER),
            lanes.splat_f32(max as f32),
            lanes.splat_f32((1u32 << each) as f32),
            field.joined("codes")
        )
    };
    let helpers = match field.fast {
        true => Vec::new(),
        false => vec![field.fill(WGSL_ENCODE)],
    };
    Functions {
        encode,
        decode: decode(field),
        helpers,
    }
}
