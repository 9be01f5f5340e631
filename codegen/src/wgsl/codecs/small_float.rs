//! The rounding the small floats share (`gbuffer_core::codecs::small_float`): an f32 to a
//! float with a 5-bit exponent and a few mantissa bits, to nearest even, in integer arithmetic
//! where WGSL's `pack2x16float` would leave the rounding to the adapter. The half and unsigned
//! float encodes wrap it ([`half`](super::half), [`unsigned_float`](super::unsigned_float)).

use std::collections::BTreeSet;

use gbuffer_core::Symbols;

use super::Lanes;

/// The rounding, per lane (`PREFIX_LANES_round_to_NAME`); the other placeholders are per-lane
/// literals (see [`helpers`]).
pub const WGSL_ROUND: &str = "\
// Rounds non-negative f32s, given as bits, to floats with a 5-bit exponent (bias 15) and
// MANTISSA_BITS bits of mantissa: to nearest even, denormals kept, saturating at the largest finite
// code (never infinity); the caller maps NaN. Normal results round the f32 bits in integer
// arithmetic, rebiasing the exponent in the same add (a carry moves into the exponent, as it
// should). Denormal results scale the value by a power of two, exactly, and round it to
// nearest even from its floor and fraction, both exact: not with `round`, whose direction at
// an exact half a translator may leave to the driver (Tint writes GLSL's round(), which GLSL
// ES leaves open at ties). No step depends on how the adapter rounds. Each path gives at least
// the code where the other applies (under 2^-14 the rebias wraps around; from 2^-14 up the
// scaled value is at least the code), so `min` picks the right one. The scaled value is capped
// at 2^16, above every code, before it becomes an integer: WGSL's conversion saturates, but
// naga's GLSL and SPIR-V write the bare conversion, which is undefined out of range (SwiftShader
// gives 0 where lavapipe saturates).
fn PREFIX_LANES_round_to_NAME(magnitude: UINTS) -> UINTS {
    let odd = (magnitude >> SHIFT) & UINTS(1u);
    let normal = ((magnitude + ROUNDING_AND_REBIAS + odd) >> SHIFT) + SMALLEST_NORMAL;
    let scaled = min(bitcast<FLOATS>(magnitude) * DENORMAL_SCALE, FLOATS(65536.0));
    let whole = floor(scaled);
    let fraction = scaled - whole;
    let up = UINTS(fraction > FLOATS(0.5)) | (UINTS(fraction == FLOATS(0.5)) & UINTS(whole) & UINTS(1u));
    let denormal = UINTS(whole) + up;
    return min(min(normal, denormal), MAX_CODE);
}

";

/// The helpers that round f32s to small floats of the given mantissa widths (one lane each)
/// and `wrapper`, which calls them, with their constants written out: `NAME` names the pair
/// (`PREFIX_LANES_round_to_NAME`, and the wrapper's own function).
pub fn helpers(symbols: &Symbols, name: &str, wrapper: &str, mantissas: &[u32]) -> Vec<String> {
    let lanes = Lanes(mantissas.len());
    let literal = |scalar: &str, write: &dyn Fn(u32) -> String| {
        let values: Vec<String> = mantissas.iter().map(|&bits| write(bits)).collect();
        lanes.literal(scalar, &values)
    };
    let distinct: BTreeSet<u32> = mantissas.iter().copied().collect();
    let distinct: Vec<String> = distinct.iter().map(u32::to_string).collect();
    let constants = [
        ("MANTISSA_BITS", distinct.join(" or ")),
        (
            "ROUNDING_AND_REBIAS",
            literal("u32", &|bits| {
                let shift = 23 - bits;
                format!(
                    "{:#x}u",
                    ((1u32 << (shift - 1)) - 1).wrapping_sub(113 << 23)
                )
            }),
        ),
        ("SHIFT", literal("u32", &|bits| format!("{}u", 23 - bits))),
        (
            "DENORMAL_SCALE",
            literal("f32", &|bits| format!("{:?}", ((14 + bits) as f32).exp2())),
        ),
        (
            "MAX_CODE",
            literal("u32", &|bits| format!("{}u", (31 << bits) - 1)),
        ),
        (
            "SMALLEST_NORMAL",
            literal("u32", &|bits| format!("{}u", 1 << bits)),
        ),
        ("NAME", name.to_string()),
    ];
    [WGSL_ROUND, wrapper]
        .iter()
        .map(|template| {
            let mut helper = lanes.fill(template, symbols);
            for (placeholder, value) in &constants {
                helper = helper.replace(placeholder, value);
            }
            helper
        })
        .collect()
}
