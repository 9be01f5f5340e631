//! Texels for the packing tests on real drivers: inputs that walk the edge sets before random
//! values, and the comparison of what a driver produced with the Rust mirror. The wgpu,
//! GLES and Vulkan tests share them, so every path is held to the same contract.

use gbuffer::packing::{ChannelEncoding, Format, Layout, ScalarKind};

use crate::harness::{expected_scalars, expected_words, scalars_per_texel};
use crate::values::{float_edges, sint_edges, uint_edges, Values};

/// One scalar slot of a texel: `field.channel`, its scalar kind and its channel's encoding.
pub struct Slot {
    /// `field.channel`.
    pub name: String,
    /// Float, unsigned or signed.
    pub kind: ScalarKind,
    /// How the channel's bits encode it.
    pub encoding: ChannelEncoding,
}

/// The slots of a texel, field by field, component by component.
pub fn slots(layout: &Layout) -> Vec<Slot> {
    layout
        .fields
        .iter()
        .flat_map(|field| {
            field.format.channels()[..field.ty.components]
                .iter()
                .map(move |channel| Slot {
                    name: format!("{}.{}", field.name, channel.name),
                    kind: field.ty.scalar,
                    encoding: channel.encoding,
                })
        })
        .collect()
}

/// Inputs (scalar bits) for `count` texels starting at texel `first`: the first texels walk
/// through the edge sets (slot s of texel t takes edge t + s), the rest are random.
pub fn inputs(layout: &Layout, first: usize, count: usize, values: &mut Values) -> Vec<u32> {
    let slots = slots(layout);
    let (floats, uints, sints) = (float_edges(), uint_edges(), sint_edges());
    let edge_texels = floats.len().max(uints.len()).max(sints.len());
    let mut inputs = Vec::with_capacity(count * slots.len());
    for texel in first..first + count {
        for (index, slot) in slots.iter().enumerate() {
            let bits = if texel < edge_texels {
                let pick = texel + index;
                match slot.kind {
                    ScalarKind::Float => floats[pick % floats.len()].to_bits(),
                    ScalarKind::Uint => uints[pick % uints.len()],
                    ScalarKind::Sint => sints[pick % sints.len()] as u32,
                }
            } else {
                values.bits(slot.kind)
            };
            inputs.push(bits);
        }
    }
    inputs
}

/// The inputs of one texel, named and printed by kind.
pub fn describe(input: &[u32], slots: &[Slot]) -> Vec<String> {
    input
        .iter()
        .zip(slots)
        .map(|(&bits, slot)| match slot.kind {
            ScalarKind::Float => format!("{}={:e}", slot.name, f32::from_bits(bits)),
            ScalarKind::Uint => format!("{}={bits}", slot.name),
            ScalarKind::Sint => format!("{}={}", slot.name, bits as i32),
        })
        .collect()
}

/// How far a decoded scalar may be from the mirror's: unorm channels 2 ulp (shaders multiply
/// by a correctly rounded reciprocal where the mirror divides), everything else not at all.
pub fn decode_tolerance(encoding: ChannelEncoding) -> u32 {
    if encoding == ChannelEncoding::Unorm {
        2
    } else {
        0
    }
}

/// Compares what a driver produced for `inputs` with the Rust mirror: `words` (packed words
/// per texel, when the path exposes them) and `decoded` (scalar bits per texel, when it
/// decodes). Pushes a line per mismatch onto `failures`, at most `limit` in all.
pub fn compare(
    what: &str,
    layout: &Layout,
    inputs: &[u32],
    words: Option<&[u32]>,
    decoded: Option<&[u32]>,
    failures: &mut Vec<String>,
    limit: usize,
) {
    let slots = slots(layout);
    let word_count = layout.words();
    let expected: Vec<u32> = inputs
        .chunks_exact(slots.len())
        .flat_map(|input| expected_words(layout, input))
        .collect();
    if let Some(words) = words {
        for (index, (want, have)) in expected.iter().zip(words).enumerate() {
            if want != have && failures.len() < limit {
                let (texel, word) = (index / word_count, index % word_count);
                let field = &layout.fields[word];
                let input = &inputs[texel * slots.len()..][..slots.len()];
                failures.push(format!(
                    "{what}: {}: word {word} ({}, {}): mirror {want:#010x}, driver {have:#010x}; inputs {:?}",
                    layout.name,
                    field.name,
                    field.format,
                    describe(input, &slots)
                ));
            }
        }
    }
    if let Some(decoded) = decoded {
        compare_decoded(what, layout, &expected, decoded, failures, limit);
    }
}

/// Compares what a shader decoded (scalar bits per texel) with the mirror's decoding of
/// `words` (packed words per texel). Pushes a line per mismatch onto `failures`, at most
/// `limit` in all. A half-float code that is a NaN (which only a driver's own conversions
/// store) may decode to any NaN: GLES leaves the payload to the driver.
pub fn compare_decoded(
    what: &str,
    layout: &Layout,
    words: &[u32],
    decoded: &[u32],
    failures: &mut Vec<String>,
    limit: usize,
) {
    let slots = slots(layout);
    let scalars = scalars_per_texel(layout);
    for (texel, texel_words) in words.chunks_exact(layout.words()).enumerate() {
        let want = expected_scalars(layout, texel_words);
        let got = &decoded[texel * scalars..][..scalars];
        for (slot, (want, have)) in slots.iter().zip(want.iter().zip(got)) {
            let small_float = matches!(
                slot.encoding,
                ChannelEncoding::Half | ChannelEncoding::UnsignedFloat { .. }
            );
            let both_nan = f32::from_bits(*want).is_nan() && f32::from_bits(*have).is_nan();
            if small_float && both_nan {
                continue;
            }
            if want.abs_diff(*have) > decode_tolerance(slot.encoding) && failures.len() < limit {
                failures.push(format!(
                    "{what}: {}: decoded {}: mirror {want:#010x} ({:e}), driver {have:#010x} ({:e})",
                    layout.name,
                    slot.name,
                    f32::from_bits(*want),
                    f32::from_bits(*have)
                ));
            }
        }
    }
}

/// Whether the driver's word for a channel may be compared with the mirror's: a finite input
/// within the range the channel represents (where GL defines the conversion).
fn defined_input(value: f32, encoding: ChannelEncoding) -> bool {
    match encoding {
        ChannelEncoding::Unorm => (0.0..=1.0).contains(&value),
        ChannelEncoding::Half => value.is_finite() && value.abs() <= 65504.0,
        ChannelEncoding::UnsignedFloat { mantissa_bits } => {
            let largest = f32::from_bits(
                ((15 + 127) << 23) | (((1 << mantissa_bits) - 1) << (23 - mantissa_bits)),
            );
            value.is_finite() && (0.0..=largest).contains(&value)
        }
        _ => true,
    }
}

/// The words a driver converted itself (native attachments) against the mirror's: within one
/// code per channel where the input is defined (see `defined_input`); GL lets a driver round
/// to either neighbour of the exact value and leaves the rest to it.
pub fn check_native_words(
    what: &str,
    layout: &Layout,
    inputs: &[u32],
    stored: &[u32],
    failures: &mut Vec<String>,
) {
    let scalars = scalars_per_texel(layout);
    let words = layout.words();
    for (texel, input) in inputs.chunks_exact(scalars).enumerate() {
        let expected = expected_words(layout, input);
        let mut values = input.iter();
        for (word, field) in layout.fields.iter().enumerate() {
            let got = stored[texel * words + word];
            let float = field.ty.scalar == ScalarKind::Float;
            for (index, channel) in field.format.channels().iter().enumerate() {
                // Channels past the field's components are padding: zero on both sides.
                let value = if index < field.ty.components {
                    values.next().map(|&bits| f32::from_bits(bits))
                } else {
                    None
                };
                let defined =
                    !float || value.is_none_or(|value| defined_input(value, channel.encoding));
                let code = |bits: u32| (bits >> channel.offset) & channel.mask();
                let distance = code(expected[word]).abs_diff(code(got));
                if defined && distance > u32::from(float) && failures.len() < 24 {
                    failures.push(format!(
                        "{what}: {}: {}.{}: driver code {:#x}, mirror {:#x}, for input {:?}",
                        layout.name,
                        field.name,
                        channel.name,
                        code(got),
                        code(expected[word]),
                        value
                    ));
                }
            }
        }
    }
}

/// The word a native attachment holds, from the four components a shader read from it as bits
/// (floats through `floatBitsToUint`, integers as they are); components past the format's
/// channels are ignored. Every value a format stores is exact in f32, so this inverts the read.
pub fn word_from_components(format: Format, components: &[u32]) -> u32 {
    format
        .channels()
        .iter()
        .zip(components)
        .fold(0, |word, (channel, &bits)| {
            let value = f32::from_bits(bits);
            let code = match channel.encoding {
                ChannelEncoding::Unorm => (value * channel.mask() as f32).round() as u32,
                ChannelEncoding::Half => small_float_bits(value, 10, true),
                ChannelEncoding::UnsignedFloat { mantissa_bits } => {
                    small_float_bits(value, mantissa_bits, false)
                }
                ChannelEncoding::Float32 | ChannelEncoding::Uint | ChannelEncoding::Sint => bits,
            };
            word | ((code & channel.mask()) << channel.offset)
        })
}

/// The bits of a float with a 5-bit exponent and `mantissa_bits` of mantissa (binary16 when
/// `signed`, the unsigned floats of `r11f_g11f_b10f` otherwise) that `value` was converted
/// from exactly. A NaN keeps the top of its payload (at least one bit of it).
fn small_float_bits(value: f32, mantissa_bits: u32, signed: bool) -> u32 {
    let bits = value.to_bits();
    let sign = if signed {
        (bits >> 31) << (5 + mantissa_bits)
    } else {
        0
    };
    let exponent = (bits >> 23) & 0xff;
    let mantissa = bits & 0x7f_ffff;
    let dropped = 23 - mantissa_bits;
    let magnitude = match exponent {
        0xff => {
            let payload = mantissa >> dropped;
            (0x1f << mantissa_bits) | payload | u32::from(mantissa != 0 && payload == 0)
        }
        113.. => ((exponent - 112) << mantissa_bits) | (mantissa >> dropped),
        0 => 0,
        // A subnormal of the small format: its code counts units of 2^(-14 - mantissa_bits).
        _ => (mantissa | 0x80_0000)
            .checked_shr(136 - mantissa_bits - exponent)
            .unwrap_or(0),
    };
    sign | magnitude
}
