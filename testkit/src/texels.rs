//! Texels for the packing tests on real drivers: inputs that walk the edge sets before random
//! values, and the comparison of what a driver produced with the Rust mirror. The wgpu, Dawn,
//! GLES and Vulkan tests share them, so every path is held to the same contract.

use gbuffer_core::codecs::unsigned_float::EXPONENT_BITS;
use gbuffer_core::{Channel, Encoding, Format, Layout, ScalarKind, Storage};

use gbuffer_gpu::harness::{
    compute_harness, expected_scalars, expected_words, field_code_errors, run_in_batches,
    scalars_per_texel,
};
use gbuffer_gpu::values::{float_edges, sint_edges, uint_edges, Values};
use gbuffer_gpu::Gpu;

/// How far a decoded scalar may be from the mirror's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// Bit for bit.
    Exact,
    /// Within this many ulp: shaders multiply by a correctly rounded reciprocal where the
    /// mirror divides (unorm, snorm), and chain such products (RGBM).
    Ulps(u32),
    /// Within this distance: `normalize` in a shader against the mirror's square root and
    /// divisions (octahedral normals).
    Absolute(f32),
}

impl Tolerance {
    /// Whether `have` (bits) is close enough to `want` (bits).
    pub fn accepts(self, want: u32, have: u32) -> bool {
        match self {
            Tolerance::Exact => want == have,
            Tolerance::Ulps(ulps) => want.abs_diff(have) <= ulps,
            Tolerance::Absolute(distance) => {
                (f32::from_bits(want) - f32::from_bits(have)).abs() <= distance
            }
        }
    }
}

/// One scalar slot of a texel: `field.channel` (or `field.x` for a bit field), its scalar
/// kind and how close a decode must come to the mirror's.
pub struct Slot {
    /// `field.channel`.
    pub name: String,
    /// Float, unsigned, signed or bool.
    pub kind: ScalarKind,
    /// How close a shader's decode must be.
    pub tolerance: Tolerance,
    /// Whether it is a small float (half or unsigned float) channel, whose NaN codes a driver
    /// may decode to any NaN.
    pub small_float: bool,
}

/// The slots of a texel, field by field, component by component.
pub fn slots(layout: &Layout) -> Vec<Slot> {
    let mut slots = Vec::new();
    for field in &layout.fields {
        match field.storage {
            Storage::Word(format) => {
                slots.extend(
                    format.channels()[..field.ty.components]
                        .iter()
                        .map(|channel| Slot {
                            name: format!("{}.{}", field.name, channel.name),
                            kind: field.ty.scalar,
                            tolerance: match channel.encoding {
                                Encoding::Unorm => Tolerance::Ulps(2),
                                _ => Tolerance::Exact,
                            },
                            small_float: matches!(
                                channel.encoding,
                                Encoding::Half | Encoding::UnsignedFloat
                            ),
                        }),
                );
            }
            Storage::Bits(bit_field) => {
                let tolerance = match bit_field.encoding {
                    Encoding::Unorm | Encoding::Snorm => Tolerance::Ulps(2),
                    Encoding::Rgbm(_) => Tolerance::Ulps(4),
                    Encoding::Octahedral => Tolerance::Absolute(1e-6),
                    _ => Tolerance::Exact,
                };
                slots.extend((0..field.ty.components).map(|component| Slot {
                    name: format!("{}.{}", field.name, &"xyzw"[component..=component]),
                    kind: field.ty.scalar,
                    tolerance,
                    small_float: false,
                }));
            }
        }
    }
    slots
}

/// The low `bits` bits set.
fn mask(bits: u32) -> u32 {
    u32::MAX >> (32 - bits)
}

/// What word `word` holds, for messages: `normal (rgb10_a2)` or `reflectance, metallic
/// (bit fields)`.
pub fn describe_word(layout: &Layout, word: usize) -> String {
    let contents = &layout.word_contents()[word];
    let names = layout.field_names(contents);
    if contents.is_bit_fields {
        format!("{} (bit fields)", names.join(", "))
    } else {
        format!("{} ({})", names[0], contents.format)
    }
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
                    ScalarKind::Bool => (pick & 1) as u32,
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
            ScalarKind::Uint | ScalarKind::Bool => format!("{}={bits}", slot.name),
            ScalarKind::Sint => format!("{}={}", slot.name, bits as i32),
        })
        .collect()
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
                let input = &inputs[texel * slots.len()..][..slots.len()];
                failures.push(format!(
                    "{what}: {}: word {word} ({}): mirror {want:#010x}, driver {have:#010x}; inputs {:?}",
                    layout.name,
                    describe_word(layout, word),
                    describe(input, &slots)
                ));
            }
        }
    }
    if let Some(decoded) = decoded {
        compare_decoded(what, layout, &expected, decoded, failures, limit);
    }
}

/// Compares what a layout's compute harness (`gbuffer_gpu::harness::compute_harness`) wrote for
/// `inputs` on a path named `what` with the Rust mirror: the packed words bit for bit, the
/// unpacked and the per-field loaded values within their tolerance. Pushes a line per mismatch
/// onto `failures`, at most `limit` in all.
pub fn compare_harness(
    what: &str,
    layout: &Layout,
    inputs: &[u32],
    [packed, unpacked, loaded]: [&[u32]; 3],
    failures: &mut Vec<String>,
    limit: usize,
) {
    let (words, decoded) = (Some(packed), Some(unpacked));
    compare(what, layout, inputs, words, decoded, failures, limit);
    let loads = format!("{what}, per-field loads");
    compare(&loads, layout, inputs, None, Some(loaded), failures, limit);
}

/// Runs the compute harness of `layout` (its WGSL `wgsl`) over `texels` texels on the adapter,
/// `inputs(first, count)` giving each batch's scalar bits, and compares what it wrote with the
/// mirror ([`compare_harness`]): a line per mismatch, at most `limit`.
pub fn check_on_adapter(
    gpu: &Gpu,
    layout: &Layout,
    wgsl: &str,
    texels: usize,
    inputs: impl FnMut(usize, usize) -> Vec<u32>,
    limit: usize,
) -> Vec<String> {
    let mut failures = Vec::new();
    run_in_batches(
        gpu,
        layout,
        &compute_harness(layout, wgsl),
        texels,
        inputs,
        |batch, packed, unpacked, loaded| {
            let outputs = [packed, unpacked, loaded];
            compare_harness("wgpu", layout, batch, outputs, &mut failures, limit);
        },
    )
    .expect("the adapter runs the harness");
    failures
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
            let both_nan = f32::from_bits(*want).is_nan() && f32::from_bits(*have).is_nan();
            if slot.small_float && both_nan {
                continue;
            }
            if !slot.tolerance.accepts(*want, *have) && failures.len() < limit {
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
fn defined_input(value: f32, channel: Channel) -> bool {
    match channel.encoding {
        Encoding::Unorm => (0.0..=1.0).contains(&value),
        Encoding::Half => value.is_finite() && value.abs() <= 65504.0,
        Encoding::UnsignedFloat => {
            let mantissa_bits = channel.bits - EXPONENT_BITS;
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
    let words = layout.word_contents();
    for (texel, input) in inputs.chunks_exact(scalars).enumerate() {
        let expected = expected_words(layout, input);
        let lanes = gbuffer_gpu::harness::lanes_of_scalars(layout, input);
        for (word, contents) in words.iter().enumerate() {
            let got = stored[texel * words.len() + word];
            if contents.is_bit_fields {
                // Shader code packs bit fields: the word is the mirror's, bit for bit.
                if got != expected[word] && failures.len() < 24 {
                    failures.push(format!(
                        "{what}: {}: word {word} ({}): driver {got:#010x}, mirror {:#010x}",
                        layout.name,
                        describe_word(layout, word),
                        expected[word]
                    ));
                }
                continue;
            }
            let field = &layout.fields[contents.members[0].field];
            let values = lanes[contents.members[0].field];
            let float = field.ty.scalar == ScalarKind::Float;
            for (index, channel) in contents.format.channels().iter().enumerate() {
                // Channels past the field's components are padding: zero on both sides.
                let value = (index < field.ty.components).then(|| f32::from_bits(values[index]));
                let defined = !float || value.is_none_or(|value| defined_input(value, *channel));
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
                Encoding::Unorm => (value * channel.mask() as f32).round() as u32,
                Encoding::Half => small_float_bits(value, 10, true),
                Encoding::UnsignedFloat => {
                    small_float_bits(value, channel.bits - EXPONENT_BITS, false)
                }
                _ => bits,
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

/// What `store(load())` did to the words of `stored` (words per texel, as the layout packs
/// them): `(unexpected, twins)`. A field must come back with the same bits, but for an
/// octahedral or RGBM bit field, which may come back as another code of (nearly) the same
/// value: those encodings name some values by two codes (the octahedral map's folded border,
/// where a code and its mirror image are one vector; an RGBM multiplier and a channel that
/// trade a step), and a decode a few ulp from the mirror's can re-encode to the other. Such a
/// field must decode within one step (see [`field_code_errors`]) of what it held; the words
/// where one changed so are counted in `twins`.
pub fn restore_changes(layout: &Layout, stored: &[u32], reloaded: &[u32]) -> (usize, usize) {
    let locations = layout.field_locations();
    let word_count = layout.words();
    // The bits no field covers (left over at the top of a word of bit fields): kept too.
    let mut uncovered = vec![u32::MAX; word_count];
    for &(word, member) in &locations {
        uncovered[word] &= !(mask(member.bits) << member.offset);
    }
    let (mut unexpected, mut twins) = (0, 0);
    for (before, after) in stored
        .chunks_exact(word_count)
        .zip(reloaded.chunks_exact(word_count))
    {
        // Per word: (changed unexpectedly, changed as a twin).
        let mut changed: Vec<(bool, bool)> = (0..word_count)
            .map(|word| ((before[word] ^ after[word]) & uncovered[word] != 0, false))
            .collect();
        for (field, &(word, member)) in locations.iter().enumerate() {
            let (was, is) = (before[word], after[word]);
            let bits = mask(member.bits) << member.offset;
            if was & bits == is & bits {
                continue;
            }
            let twin_codes = matches!(
                layout.fields[field]
                    .bit_field()
                    .map(|bit_field| bit_field.encoding),
                Some(Encoding::Octahedral | Encoding::Rgbm(_))
            );
            if twin_codes
                && field_code_errors(layout, field, member, was, is)
                    .iter()
                    .all(|&steps| steps <= 1)
            {
                changed[word].1 = true;
            } else {
                changed[word].0 = true;
            }
        }
        unexpected += changed.iter().filter(|(wrong, _)| *wrong).count();
        twins += changed
            .iter()
            .filter(|(wrong, twin)| *twin && !*wrong)
            .count();
    }
    (unexpected, twins)
}
