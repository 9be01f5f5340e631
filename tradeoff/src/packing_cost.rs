//! What a layout's conversions cost and how far they stray from the exact ones, measured the
//! way the issue on packing cost measured them: a compute shader that packs one texel read
//! from a buffer and unpacks words read from another, through naga to SPIR-V and
//! `spirv-opt -O`, counting the instructions in function bodies (about 14 are the harness's)
//! and the conditional branches. The engines' idiom for each format ([`builtin_form`]) is
//! measured in the same harness, so the three columns compare like with like.

use gbuffer_core::Conversions;
use gbuffer_core::{Encoding, Field, FieldType, Format, Layout, ScalarKind, Storage};

use gbuffer_gpu::harness::field_code_errors;
use gbuffer_gpu::harness::{compute_harness, expected_words, run_in_batches, scalars_per_texel};
use gbuffer_gpu::tools::spirv_opt;
use gbuffer_gpu::values::{float_edges, Values};
use gbuffer_gpu::Gpu;

/// SPIR-V opcodes counted.
const OP_FUNCTION: u32 = 54;
const OP_FUNCTION_END: u32 = 56;
const OP_BRANCH_CONDITIONAL: u32 = 250;
const OP_SWITCH: u32 = 251;

/// The formats whose conversions differ between exact and fast (the integer formats and r32f
/// are exact either way), in the order the issue lists them.
pub const CONVERTED_FORMATS: [Format; 5] = [
    Format::Rgba8,
    Format::Rg16,
    Format::Rg16f,
    Format::Rgb10A2,
    Format::R11fG11fB10f,
];

/// Instructions in function bodies and conditional branches of the optimised SPIR-V.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cost {
    /// Instructions between `OpFunction` and `OpFunctionEnd`.
    pub instructions: usize,
    /// `OpBranchConditional` and `OpSwitch` among them.
    pub conditional_branches: usize,
}

/// A layout `Texel` of one field `value` of `format`, as wide as the format (three
/// components for r11f_g11f_b10f).
pub fn one_field(format: Format) -> Layout {
    let scalar = format.scalar_kind();
    let components = if scalar == ScalarKind::Float && format.channels().len() == 3 {
        3
    } else {
        format.channels().len()
    };
    Layout {
        name: "Texel".into(),
        budget: 32,
        fields: vec![Field {
            name: "value".into(),
            storage: Storage::Word(format),
            ty: FieldType::new(scalar, components),
            conversions: None,
        }],
    }
}

/// The shader measured, around WGSL that declares `Texel`, `pack_texel` and `unpack_texel`
/// for `words` words: pack a texel read from one buffer, unpack words read from another.
pub fn harness(texel_wgsl: &str, words: usize) -> String {
    format!(
        "{texel_wgsl}\n\
         @group(0) @binding(0) var<storage, read> texel_in: Texel;\n\
         @group(0) @binding(1) var<storage, read_write> words_out: array<u32, {words}>;\n\
         @group(0) @binding(2) var<storage, read> words_in: array<u32, {words}>;\n\
         @group(0) @binding(3) var<storage, read_write> texel_out: Texel;\n\n\
         @compute @workgroup_size(1)\nfn main() {{\n    \
         words_out = pack_texel(texel_in);\n    \
         texel_out = unpack_texel(words_in);\n}}\n"
    )
}

/// The compilers' form of [`harness`]: each invocation packs its own texel and unpacks its own
/// words. A GPU compiler hoists work on values that are the same for every invocation out of
/// the shader (ir3 into its once-a-draw preamble), and [`harness`]'s one texel is such a value.
pub fn invocation_harness(texel_wgsl: &str, words: usize) -> String {
    format!(
        "{texel_wgsl}\n\
         @group(0) @binding(0) var<storage, read> texels_in: array<Texel>;\n\
         @group(0) @binding(1) var<storage, read_write> words_out: array<array<u32, {words}>>;\n\
         @group(0) @binding(2) var<storage, read> words_in: array<array<u32, {words}>>;\n\
         @group(0) @binding(3) var<storage, read_write> texels_out: array<Texel>;\n\n\
         @compute @workgroup_size(64)\nfn main(@builtin(global_invocation_id) id: vec3<u32>) {{\n    \
         words_out[id.x] = pack_texel(texels_in[id.x]);\n    \
         texels_out[id.x] = unpack_texel(words_in[id.x]);\n}}\n"
    )
}

/// The cost of `layout` (named `Texel`) under `conversions`.
pub fn layout_cost(layout: &Layout, conversions: Conversions) -> Result<Cost, String> {
    let wgsl = gbuffer_codegen::wgsl::emit_with(layout, conversions);
    cost(&harness(&wgsl, layout.words()))
}

/// The engines' idiom for one field of `format` (see [`one_field`]), as `Texel`,
/// `pack_texel` and `unpack_texel`: WGSL's pack builtins where they exist, and for rgb10_a2 and
/// r11f_g11f_b10f what engines write instead (f32 rounding and shifts; halves with their
/// mantissas cut). None for the formats that need no conversion.
pub fn builtin_form(format: Format) -> Option<String> {
    let (value_type, pack, unpack) = match format {
        Format::Rgba8 => ("vec4<f32>", "return pack4x8unorm(v);", "return unpack4x8unorm(w);"),
        Format::Rg16 => ("vec2<f32>", "return pack2x16unorm(v);", "return unpack2x16unorm(w);"),
        Format::Rg16f => ("vec2<f32>", "return pack2x16float(v);", "return unpack2x16float(w);"),
        Format::Rgb10A2 => (
            "vec4<f32>",
            "let c = vec4<u32>(round(saturate(v) * vec4<f32>(1023.0, 1023.0, 1023.0, 3.0)));\n    \
             return c.x | (c.y << 10u) | (c.z << 20u) | (c.w << 30u);",
            "let c = (vec4<u32>(w) >> vec4<u32>(0u, 10u, 20u, 30u)) & vec4<u32>(1023u, 1023u, 1023u, 3u);\n    \
             return vec4<f32>(c) / vec4<f32>(1023.0, 1023.0, 1023.0, 3.0);",
        ),
        Format::R11fG11fB10f => (
            "vec3<f32>",
            "let red_green = pack2x16float(max(v.xy, vec2<f32>(0.0)));\n    \
             let blue = pack2x16float(vec2<f32>(max(v.z, 0.0), 0.0));\n    \
             return ((red_green >> 4u) & 0x7ffu) | ((red_green >> 9u) & 0x3ff800u) | ((blue & 0x7fe0u) << 17u);",
            "let red_green = unpack2x16float(((w & 0x7ffu) << 4u) | ((w & 0x3ff800u) << 9u));\n    \
             return vec3<f32>(red_green, unpack2x16float((w >> 17u) & 0x7fe0u).x);",
        ),
        _ => return None,
    };
    Some(format!(
        "struct Texel {{\n    value: {value_type},\n}}\n\n\
         fn encode(v: {value_type}) -> u32 {{\n    {pack}\n}}\n\n\
         fn decode(w: u32) -> {value_type} {{\n    {unpack}\n}}\n\n\
         fn pack_texel(texel: Texel) -> array<u32, 1> {{\n    return array<u32, 1>(encode(texel.value));\n}}\n\n\
         fn unpack_texel(words: array<u32, 1>) -> Texel {{\n    return Texel(decode(words[0]));\n}}\n"
    ))
}

/// Compiles `wgsl` (a whole shader) with naga, optimises it with `spirv-opt -O` (Debian's
/// `spirv-tools`) and counts.
pub fn cost(wgsl: &str) -> Result<Cost, String> {
    let (_, words) = gbuffer_validator::cost::compile_compacted(wgsl)?;
    let optimised = spirv_opt(bytemuck::cast_slice::<u32, u8>(&words))?;
    Ok(count(&optimised))
}

/// Counts a SPIR-V binary's instructions inside functions, and its conditional branches.
fn count(binary: &[u8]) -> Cost {
    let words: Vec<u32> = binary
        .chunks_exact(4)
        .map(|bytes| u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))
        .collect();
    let mut cost = Cost {
        instructions: 0,
        conditional_branches: 0,
    };
    let mut in_function = false;
    for opcode in gbuffer_validator::cost::spirv_opcodes(&words) {
        match opcode {
            OP_FUNCTION => in_function = true,
            OP_FUNCTION_END => in_function = false,
            _ if in_function => {
                cost.instructions += 1;
                cost.conditional_branches +=
                    usize::from(opcode == OP_BRANCH_CONDITIONAL || opcode == OP_SWITCH);
            }
            _ => {}
        }
    }
    cost
}

/// How far an adapter's codes stray from the exact mirror's.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Deviation {
    /// Channel codes that differ from the exact ones.
    pub differing: usize,
    /// Channel codes compared.
    pub channels: usize,
    /// The largest difference per field, in field order.
    pub largest_code_error_by_field: Vec<u32>,
}

impl Deviation {
    /// The largest difference between a channel's code and the exact one.
    pub fn largest_code_error(&self) -> u32 {
        self.largest_code_error_by_field
            .iter()
            .copied()
            .max()
            .unwrap_or(0)
    }

    /// The fraction of channel codes that differ from the exact ones.
    pub fn differing_fraction(&self) -> f64 {
        self.differing as f64 / self.channels.max(1) as f64
    }
}

/// The float inputs fast conversions are asked to handle: finite values within f16's range
/// (past it `pack2x16float`'s result is undefined, and engines keep G-buffer values there).
pub fn in_fast_domain(value: f32) -> bool {
    value.is_finite() && value.abs() <= 65504.0
}

/// Scalar bits for `count` texels of `scalars` float scalars each, in the domain fast
/// conversions promise to handle: the float edge cases in that domain first (once, from the
/// first call on), then random values from [`Values::float`] kept to it. A batch at a time.
pub fn fast_domain_inputs(seed: u64, scalars: usize) -> impl FnMut(usize) -> Vec<u32> {
    let edges = float_edges()
        .into_iter()
        .filter(|value| in_fast_domain(*value));
    let mut values = Values::new(seed);
    let random =
        std::iter::repeat_with(move || values.float()).filter(|value| in_fast_domain(*value));
    let mut stream = edges.chain(random).map(f32::to_bits);
    move |count| stream.by_ref().take(count * scalars).collect()
}

impl std::fmt::Display for Deviation {
    /// `N of M codes (P%) differ from the exact mirror, by at most [a, b, ...] per field`.
    fn fmt(&self, out: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            out,
            "{} of {} codes ({:.3}%) differ from the exact mirror, by at most {:?} per field",
            self.differing,
            self.channels,
            100.0 * self.differing_fraction(),
            self.largest_code_error_by_field
        )
    }
}

/// the layout contract's rule for a field's codes against the exact mirror's, given the layout's
/// conversions (a field's own override them): the same codes under exact conversions; under
/// fast ones within one code, or for octahedral and RGBM bit fields, measured on their decoded
/// values ([`field_code_errors`]), within two steps (each side is within one of the input).
pub fn allowed_code_error(field: &Field, layout_conversions: Conversions) -> u32 {
    match (
        field.conversions.unwrap_or(layout_conversions),
        field.bit_field(),
    ) {
        (Conversions::Exact, _) => 0,
        (Conversions::Fast, Some(bits))
            if matches!(bits.encoding, Encoding::Octahedral | Encoding::Rgbm(_)) =>
        {
            2
        }
        (Conversions::Fast, _) => 1,
    }
}

impl Deviation {
    /// A line for each field whose codes strayed further than [`allowed_code_error`] allows.
    pub fn beyond_contract(&self, layout: &Layout, layout_conversions: Conversions) -> Vec<String> {
        layout
            .fields
            .iter()
            .zip(&self.largest_code_error_by_field)
            .filter_map(|(field, &largest)| {
                let allowed = allowed_code_error(field, layout_conversions);
                (largest > allowed).then(|| {
                    format!(
                        "{}.{}: codes differ by {largest} from the exact mirror's (allowed {allowed})",
                        layout.name, field.name
                    )
                })
            })
            .collect()
    }

    /// No codes compared yet, for a layout of `fields` fields.
    pub fn new(fields: usize) -> Deviation {
        Deviation {
            largest_code_error_by_field: vec![0; fields],
            ..Deviation::default()
        }
    }

    /// Adds a batch: `packed` (the words a shader packed, per texel) against what the exact
    /// mirror packs from `inputs` (scalar bits, per texel).
    pub fn add(&mut self, layout: &Layout, inputs: &[u32], packed: &[u32]) {
        let (scalars, words) = (scalars_per_texel(layout), layout.words());
        for (texel, got) in packed.chunks_exact(words).enumerate() {
            let expected = expected_words(layout, &inputs[texel * scalars..][..scalars]);
            for (field, (word, member)) in layout.field_locations().into_iter().enumerate() {
                // Codes of one sign are ordered like their values (a sign bit is the top bit,
                // so a sign flip shows as a large difference).
                let errors = field_code_errors(layout, field, member, expected[word], got[word]);
                for error in errors {
                    let by_field = &mut self.largest_code_error_by_field[field];
                    *by_field = (*by_field).max(error);
                    self.differing += usize::from(error != 0);
                    self.channels += 1;
                }
            }
        }
    }
}

/// Packs `texels` texels of a layout of float fields on the adapter with `wgsl` (the layout's
/// WGSL, of either conversions) and compares every channel's code with the exact mirror's,
/// over [`fast_domain_inputs`]. The error is wgpu's, where it rejected the harness.
pub fn deviation(
    gpu: &Gpu,
    layout: &Layout,
    wgsl: &str,
    texels: usize,
    seed: u64,
) -> Result<Deviation, String> {
    let harness = compute_harness(layout, wgsl);
    let mut inputs = fast_domain_inputs(seed, scalars_per_texel(layout));
    let mut deviation = Deviation::new(layout.fields.len());
    run_in_batches(
        gpu,
        layout,
        &harness,
        texels,
        |_, count| inputs(count),
        |inputs, packed, _, _| deviation.add(layout, inputs, packed),
    )?;
    Ok(deviation)
}
