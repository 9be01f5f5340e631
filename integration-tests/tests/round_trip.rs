//! unpack(pack(x)) stays within each format's quantization bound, over a million random
//! values per format plus the edge set. The bounds, per channel encoding:
//!
//! | encoding | bound on `|unpack(pack(x)) - x|` |
//! |---|---|
//! | unorm, n bits | half a step, `0.5 / (2^n - 1)`, of `clamp(x, 0, 1)` (plus f32 rounding of the quotient, 2^-24 relative) |
//! | rg16f | half an ulp: `2^-11 |x|` for normals, `2^-25` for denormals; past +-65504, exactly +-65504 |
//! | r11f, g11f (6-bit mantissa) | `2^-7 |x|`, `2^-21` for denormals; negatives 0; past 65024, 65024 |
//! | b10f (5-bit mantissa) | `2^-6 |x|`, `2^-20` for denormals; negatives 0; past 64512, 64512 |
//! | r32f | none: the bits are kept |
//! | integers | none inside the channel's range; outside, the nearest end of it |
//!
//! NaN stores as 0 in every format but r32f, which keeps it.

use gbuffer::layout::{Channel, Encoding, Format, Scalar, ScalarKind};
use gbuffer_core::Named;
use gbuffer_gpu::values::{float_edges, sint_edges, uint_edges, Values};

const RANDOM_VALUES_PER_FORMAT: usize = 1_000_000;

/// Checks one float through one channel; the reason it is out of bounds, if it is.
fn float_error(channel: Channel, value: f32, decoded: f32) -> Option<String> {
    let within = |bound: f64, target: f64| (f64::from(decoded) - target).abs() <= bound;
    let ok = match channel.encoding {
        Encoding::Float32 => decoded.to_bits() == value.to_bits(),
        _ if value.is_nan() => decoded.to_bits() == 0,
        Encoding::Unorm => {
            let max = f64::from((1u32 << channel.bits) - 1);
            let target = f64::from(value).clamp(0.0, 1.0);
            within(0.5 / max + target * 2f64.powi(-24), target)
        }
        Encoding::Half => small_float_ok(value, decoded, 10, 65504.0, true),
        Encoding::UnsignedFloat => {
            let mantissa_bits = channel.bits - 5;
            let largest = if mantissa_bits == 6 { 65024.0 } else { 64512.0 };
            small_float_ok(value, decoded, mantissa_bits, largest, false)
        }
        other => unreachable!("{other} is not a float format's channel codec"),
    };
    (!ok).then(|| format!("{value:e} decoded as {decoded:e}"))
}

fn small_float_ok(
    value: f32,
    decoded: f32,
    mantissa_bits: u32,
    largest: f64,
    signed: bool,
) -> bool {
    let value = f64::from(value);
    let decoded = f64::from(decoded);
    if !signed && value <= 0.0 {
        return decoded == 0.0;
    }
    if value.abs() >= largest {
        return decoded == largest.copysign(value);
    }
    let relative = 2f64.powi(-(mantissa_bits as i32 + 1));
    let denormal = 2f64.powi(-(14 + mantissa_bits as i32 + 1));
    (decoded - value).abs() <= (value.abs() * relative).max(denormal)
}

fn int_expected(channel: Channel, value: i64) -> i64 {
    match channel.encoding {
        Encoding::Uint => value.clamp(0, (1i64 << channel.bits) - 1),
        _ => value.clamp(
            -(1i64 << (channel.bits - 1)),
            (1i64 << (channel.bits - 1)) - 1,
        ),
    }
}

/// Each channel of an integer format's round trip of `values`: its index, and what went wrong
/// where the value read back is not the value clamped to the channel's range.
fn integer_round_trip<T>(format: Format, values: [T; 4]) -> Vec<(u32, Option<String>)>
where
    T: Scalar + Into<i64> + std::fmt::Display,
{
    let channels = format.channels();
    let back = format.decode::<T>(format.encode(values));
    (0..channels.len())
        .map(|index| {
            let expected = int_expected(channels[index], values[index].into());
            let ok = back[index].into() == expected;
            let problem = format!("{} decoded as {}", values[index], back[index]);
            (index as u32, (!ok).then_some(problem))
        })
        .collect()
}

#[test]
fn every_format_round_trips_within_its_quantization_bound() {
    let mut failures = Vec::new();
    for (seed, format) in Format::ALL.iter().copied().enumerate() {
        let mut values = Values::new(seed as u64);
        let channels = format.channels();
        let count = channels.len();
        let mut format_failures = 0;
        let mut check = |inputs: [u32; 4]| {
            let decoded: Vec<(u32, Option<String>)> = match format.scalar_kind() {
                ScalarKind::Float => {
                    let values = inputs.map(f32::from_bits);
                    let back = format.decode::<f32>(format.encode(values));
                    (0..count)
                        .map(|index| {
                            (
                                index as u32,
                                float_error(channels[index], values[index], back[index]),
                            )
                        })
                        .collect()
                }
                ScalarKind::Uint => integer_round_trip(format, inputs),
                ScalarKind::Sint => integer_round_trip(format, inputs.map(|bits| bits as i32)),
                ScalarKind::Bool => unreachable!("no format holds booleans"),
            };
            for (index, error) in decoded {
                if let Some(error) = error {
                    format_failures += 1;
                    if format_failures <= 5 {
                        failures.push(format!(
                            "{format} channel {}: {error}",
                            channels[index as usize].name
                        ));
                    }
                }
            }
        };
        // The edge set, each value in every channel.
        let edges: Vec<u32> = match format.scalar_kind() {
            ScalarKind::Float => float_edges().into_iter().map(f32::to_bits).collect(),
            ScalarKind::Uint => uint_edges(),
            ScalarKind::Sint => sint_edges().into_iter().map(|value| value as u32).collect(),
            ScalarKind::Bool => unreachable!("no format holds booleans"),
        };
        for &edge in &edges {
            check([edge; 4]);
        }
        for _ in 0..RANDOM_VALUES_PER_FORMAT.div_ceil(count) {
            let kind = format.scalar_kind();
            check([
                values.bits(kind),
                values.bits(kind),
                values.bits(kind),
                values.bits(kind),
            ]);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
