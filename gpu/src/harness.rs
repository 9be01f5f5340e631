//! WGSL harnesses around a layout's generated code, and the CPU expectations to compare their
//! results with. Both work from the layout model, so they serve derived layouts and random
//! ones alike.

use std::fmt::Write as _;

use gbuffer_core::{Encoding, Layout, Member, ScalarKind, Storage};

/// Scalars per texel: the components of all fields.
pub fn scalars_per_texel(layout: &Layout) -> usize {
    layout.fields.iter().map(|field| field.ty.components).sum()
}

/// A texel's scalar bits (field by field, component by component) as the lanes of each
/// field, as [`Layout::encode_lanes`] takes them.
pub fn lanes_of_scalars(layout: &Layout, scalars: &[u32]) -> Vec<[u32; 4]> {
    let mut scalars = scalars.iter().copied();
    layout
        .fields
        .iter()
        .map(|field| {
            let mut lanes = [0u32; 4];
            for lane in lanes.iter_mut().take(field.ty.components) {
                *lane = scalars.next().expect("one scalar per component");
            }
            lanes
        })
        .collect()
}

/// What the Rust mirror packs for one texel given as scalar bits (field by field, component
/// by component): the conversions the derive's `pack` calls.
pub fn expected_words(layout: &Layout, scalars: &[u32]) -> Vec<u32> {
    layout.encode_lanes(&lanes_of_scalars(layout, scalars))
}

/// What the Rust mirror unpacks from one texel's words, as scalar bits.
pub fn expected_scalars(layout: &Layout, words: &[u32]) -> Vec<u32> {
    layout
        .decode_lanes(words)
        .iter()
        .zip(&layout.fields)
        .flat_map(|(lanes, field)| lanes[..field.ty.components].to_vec())
        .collect()
}

/// WGSL statements that declare `var texel: <Name>` and fill it from the scalar bits
/// `harness_inputs[base..]` (a `base: u32` in scope).
pub fn texel_from_inputs(layout: &Layout) -> String {
    let mut out = format!("    var texel: {};\n", layout.name);
    let mut first = 0;
    for field in &layout.fields {
        let _ = writeln!(
            out,
            "    texel.{} = {};",
            field.name,
            field_from_scalars(&field.ty, first)
        );
        first += field.ty.components;
    }
    out
}

/// WGSL statements that write the scalars of the texel `texel` as bits into
/// `output[base + slot]`, in slot order.
pub fn scalars_to_output(layout: &Layout, texel: &str, output: &str, base: &str) -> String {
    let mut out = String::new();
    let mut slot = 0;
    for field in &layout.fields {
        for component in 0..field.ty.components {
            let access = if field.ty.components == 1 {
                String::new()
            } else {
                format!(".{}", &"xyzw"[component..=component])
            };
            let value = format!("{texel}.{}{access}", field.name);
            let bits = match field.ty.scalar {
                ScalarKind::Bool => format!("u32({value})"),
                _ => format!("bitcast<u32>({value})"),
            };
            let _ = writeln!(out, "    {output}[{base} + {slot}u] = {bits};");
            slot += 1;
        }
    }
    out
}

/// The WGSL expression that builds field `field` from scalars `inputs[base + first..]`.
fn field_from_scalars(ty: &gbuffer_core::FieldType, first: usize) -> String {
    let components: Vec<String> = (0..ty.components)
        .map(|component| {
            let load = format!("harness_inputs[base + {}u]", first + component);
            match ty.scalar {
                ScalarKind::Uint => load,
                ScalarKind::Bool => format!("({load} != 0u)"),
                kind => format!("bitcast<{}>({load})", kind.wgsl()),
            }
        })
        .collect();
    format!("{}({})", ty.wgsl(), components.join(", "))
}

/// A compute shader that reads texels as scalar bits, packs them with the generated
/// `pack_<snake>`, writes the words, unpacks them again with `unpack_<snake>` and writes the
/// scalars' bits, then reads each field alone with `load_<snake>_<field>` and writes those
/// scalars' bits too. Bindings: 0 inputs, 1 packed words, 2 unpacked scalars, 3 loaded
/// scalars, 4 texel count (in `x`); workgroups of 64.
pub fn compute_harness(layout: &Layout, wgsl: &str) -> String {
    let symbols = layout.symbols();
    let scalars = scalars_per_texel(layout);
    let words = layout.words();
    let mut out = String::from(wgsl);
    out.push_str("\n\n// ---- test harness ----\n");
    out.push_str("@group(0) @binding(0) var<storage, read> harness_inputs: array<u32>;\n");
    out.push_str("@group(0) @binding(1) var<storage, read_write> harness_packed: array<u32>;\n");
    out.push_str("@group(0) @binding(2) var<storage, read_write> harness_unpacked: array<u32>;\n");
    out.push_str("@group(0) @binding(3) var<storage, read_write> harness_loaded: array<u32>;\n");
    out.push_str("@group(0) @binding(4) var<uniform> harness_count: vec4<u32>;\n\n");
    out.push_str("@compute @workgroup_size(64)\n");
    out.push_str("fn harness_main(@builtin(global_invocation_id) id: vec3<u32>) {\n");
    out.push_str("    let index = id.x;\n");
    out.push_str("    if index >= harness_count.x {\n        return;\n    }\n");
    let _ = writeln!(out, "    let base = index * {scalars}u;");
    out.push_str(&texel_from_inputs(layout));
    let _ = writeln!(out, "    let words = {}(texel);", symbols.pack());
    for word in 0..words {
        let _ = writeln!(
            out,
            "    harness_packed[index * {words}u + {word}u] = words[{word}];"
        );
    }
    let _ = writeln!(out, "    let back = {}(words);", symbols.unpack());
    out.push_str(&scalars_to_output(
        layout,
        "back",
        "harness_unpacked",
        "base",
    ));
    let _ = writeln!(out, "    var loaded: {};", layout.name);
    for field in &layout.fields {
        let _ = writeln!(
            out,
            "    loaded.{} = {}(words);",
            field.name,
            symbols.load_field(&field.name)
        );
    }
    out.push_str(&scalars_to_output(
        layout,
        "loaded",
        "harness_loaded",
        "base",
    ));
    out.push_str("}\n");
    out
}

/// Runs a [`compute_harness`] of `layout` over `texels` texels on the adapter, in batches small
/// enough for the default storage binding size. `inputs(first, count)` gives a batch's scalar
/// bits; `results(inputs, packed words, unpacked scalar bits, loaded scalar bits)` receives
/// each batch's. The error is wgpu's, where it rejected the harness.
pub fn run_in_batches(
    gpu: &crate::Gpu,
    layout: &Layout,
    harness: &str,
    texels: usize,
    mut inputs: impl FnMut(usize, usize) -> Vec<u32>,
    mut results: impl FnMut(&[u32], &[u32], &[u32], &[u32]),
) -> Result<(), String> {
    const BATCH: usize = 1 << 18;
    let (scalars, words) = (scalars_per_texel(layout), layout.words());
    for first in (0..texels).step_by(BATCH) {
        let count = BATCH.min(texels - first);
        let batch = inputs(first, count);
        let outputs = gpu.run_compute(
            harness,
            "harness_main",
            &batch,
            &[count * words, count * scalars, count * scalars],
            count as u32,
        )?;
        results(&batch, &outputs[0], &outputs[1], &outputs[2]);
    }
    Ok(())
}

/// A fragment shader that uses every generated function (pack, unpack, each `load_`, the
/// target helpers) on values made from the fragment position: what the backend translation
/// tests compile. GLSL ES 3.00 (WebGL2) has fragment shaders but no compute ones.
pub fn fragment_harness(layout: &Layout, wgsl: &str) -> String {
    let symbols = layout.symbols();
    let name = symbols.texel();
    let mut out = String::from(wgsl);
    out.push_str("\n\n// ---- test harness ----\n@fragment\n");
    let _ = writeln!(
        out,
        "fn harness_fragment(@builtin(position) position: vec4<f32>) -> {} {{",
        symbols.targets()
    );
    let _ = writeln!(out, "    var texel: {name};");
    for field in &layout.fields {
        let scalar = match field.ty.scalar {
            ScalarKind::Float => "position.x".to_string(),
            ScalarKind::Bool => "position.y > 0.5".to_string(),
            kind => format!("{}(position.y)", kind.wgsl()),
        };
        let _ = writeln!(
            out,
            "    texel.{} = {}({scalar});",
            field.name,
            field.ty.wgsl()
        );
    }
    let _ = writeln!(out, "    let words = {}(texel);", symbols.pack());
    let _ = writeln!(out, "    var back = {}(words);", symbols.unpack());
    for field in &layout.fields {
        let load = symbols.load_field(&field.name);
        let _ = writeln!(out, "    back.{} = {load}(words);", field.name);
    }
    let (pack_targets, unpack_targets) = (symbols.pack_targets(), symbols.unpack_targets());
    let _ = writeln!(
        out,
        "    let again = {unpack_targets}({pack_targets}(back));\n    return {pack_targets}(again);\n}}"
    );
    out
}

/// How far a field in word `have` is from the same field in word `want`, per component, in
/// codes: the difference of each channel's or component's code, for a whole word and the
/// per-component encodings; for rgb9e5 and bool, of the whole code. Octahedral and RGBM
/// fields name some values by two codes (the map's folded border, a multiplier and a channel
/// that trade a step), so theirs is measured on the decoded values: the angle in units of the
/// octahedral bound (sqrt(18) half-steps), or each channel's difference in steps of the
/// coarser multiplier, rounded up.
pub fn field_code_errors(
    layout: &Layout,
    field: usize,
    member: Member,
    want: u32,
    have: u32,
) -> Vec<u32> {
    let field = &layout.fields[field];
    let bit_field = match field.storage {
        Storage::Word(format) => {
            return format.channels()[..field.ty.components]
                .iter()
                .map(|channel| {
                    let code = |word: u32| (word >> channel.offset) & channel.mask();
                    code(want).abs_diff(code(have))
                })
                .collect()
        }
        Storage::Bits(bit_field) => bit_field,
    };
    let code = |word: u32| (word >> member.offset) & mask(member.bits);
    let (want, have) = (code(want), code(have));
    let components = field.ty.components;
    let decoded = |code: u32| {
        bit_field
            .decode(code, components)
            .map(|lane| f64::from(f32::from_bits(lane)))
    };
    match bit_field.encoding {
        Encoding::Rgb9e5 | Encoding::Bool => vec![want.abs_diff(have)],
        _ if want == have => vec![0],
        Encoding::Octahedral => {
            let (a, b) = (decoded(want), decoded(have));
            let cross = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            let angle = cross
                .iter()
                .map(|c| c * c)
                .sum::<f64>()
                .sqrt()
                .atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
            let bound = 18f64.sqrt() / f64::from(mask(bit_field.bits / 2));
            vec![(angle / bound - 1e-9).ceil().max(0.0) as u32]
        }
        Encoding::Rgbm(range) => {
            let multiplier = (want >> 24).max(have >> 24);
            let step = f64::from(multiplier) / 255.0 * f64::from(range.get()) / 255.0;
            let (a, b) = (decoded(want), decoded(have));
            (0..3)
                .map(|channel| {
                    ((a[channel] - b[channel]).abs() / step - 1e-9)
                        .ceil()
                        .max(0.0) as u32
                })
                .collect()
        }
        _ => {
            let each = bit_field.component_bits(components);
            (0..components)
                .map(|index| {
                    let part = |code: u32| (code >> (each * index as u32)) & mask(each);
                    part(want).abs_diff(part(have))
                })
                .collect()
        }
    }
}

/// The low `bits` bits set.
fn mask(bits: u32) -> u32 {
    u32::MAX >> (32 - bits)
}
