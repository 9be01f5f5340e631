//! What the generated conversions cost once compiled, measured as the figures of the issue on
//! packing cost were: a compute shader that unpacks one texel and packs it again, through naga
//! to SPIR-V and `spirv-opt -O`, counting the instructions in function bodies and the
//! conditional branches. The exact conversions have no conditional branch (a fragment never
//! diverges on its data); the table printed beside it (`-- --nocapture`) compares them with
//! WGSL's pack builtins where the layout asks for those (`conversions = fast`).

use gbuffer::packing::{Field, FieldType, Format, Layout, ScalarKind};
use gbuffer_codegen::emit::wgsl::{emit_with, Conversions};
use gbuffer_testkit::tools::run;

/// SPIR-V opcodes counted.
const OP_FUNCTION: u32 = 54;
const OP_FUNCTION_END: u32 = 56;
const OP_BRANCH_CONDITIONAL: u32 = 250;
const OP_SWITCH: u32 = 251;

/// A layout of one field of `format`, as wide as the format.
fn one_field(format: Format) -> Layout {
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
            format,
            ty: FieldType::new(scalar, components),
        }],
    }
}

/// The shader measured: pack a texel read from one buffer, unpack words read from another.
fn harness(layout: &Layout, conversions: Conversions) -> String {
    let words = layout.words();
    format!(
        "{}\n\
         @group(0) @binding(0) var<storage, read> texel_in: Texel;\n\
         @group(0) @binding(1) var<storage, read_write> words_out: array<u32, {words}>;\n\
         @group(0) @binding(2) var<storage, read> words_in: array<u32, {words}>;\n\
         @group(0) @binding(3) var<storage, read_write> texel_out: Texel;\n\n\
         @compute @workgroup_size(1)\nfn main() {{\n    \
         words_out = pack_texel(texel_in);\n    \
         texel_out = unpack_texel(words_in);\n}}\n",
        emit_with(layout, conversions),
    )
}

/// Instructions in function bodies and conditional branches of the optimised SPIR-V.
fn cost(wgsl: &str) -> (usize, usize) {
    let (_, words) =
        gbuffer_validator::cost::compile_compacted(wgsl).expect("the harness is valid");
    let folder = tempfile::tempdir().unwrap();
    let input = folder.path().join("in.spv");
    let output = folder.path().join("out.spv");
    std::fs::write(&input, bytemuck::cast_slice::<u32, u8>(&words)).unwrap();
    let (ok, log) = run(
        "spirv-opt",
        &[
            "-O",
            input.to_str().unwrap(),
            "-o",
            output.to_str().unwrap(),
        ],
        "spirv-tools",
    );
    assert!(ok, "spirv-opt: {log}");
    if let Ok(folder) = std::env::var("GBUFFER_DUMP_SPIRV") {
        let name = format!("{folder}/{:016x}.spv", wgsl.len());
        std::fs::copy(&output, name).unwrap();
    }
    let optimised = std::fs::read(&output).unwrap();
    let words: Vec<u32> = optimised
        .chunks_exact(4)
        .map(|bytes| u32::from_le_bytes(bytes.try_into().unwrap()))
        .collect();
    let (mut in_function, mut instructions, mut branches) = (false, 0, 0);
    let mut at = 5;
    while at < words.len() {
        let (count, opcode) = ((words[at] >> 16) as usize, words[at] & 0xffff);
        match opcode {
            OP_FUNCTION => in_function = true,
            OP_FUNCTION_END => in_function = false,
            _ if in_function => {
                instructions += 1;
                branches += usize::from(opcode == OP_BRANCH_CONDITIONAL || opcode == OP_SWITCH);
            }
            _ => {}
        }
        at += count.max(1);
    }
    (instructions, branches)
}

#[test]
fn exact_conversions_have_no_conditional_branch() {
    let mut rows = Vec::new();
    let mut layouts: Vec<(String, Layout)> = Format::ALL
        .iter()
        .map(|&format| (format.name().to_string(), one_field(format)))
        .collect();
    let mut four_words = gbuffer::seed_layouts::all()[1].0.clone();
    four_words.name = "Texel".into();
    layouts.push(("Listing 2.2 (4 words)".into(), four_words));
    for (name, layout) in &layouts {
        let (exact, exact_branches) = cost(&harness(layout, Conversions::Exact));
        let (fast, fast_branches) = cost(&harness(layout, Conversions::Fast));
        rows.push(format!(
            "{name:<24} {exact:>6} {exact_branches:>9} {fast:>7} {fast_branches:>9}"
        ));
        assert_eq!(exact_branches, 0, "{name}: exact conversions branch");
    }
    println!(
        "{:<24} {:>6} {:>9} {:>7} {:>9}",
        "layout", "exact", "branches", "fast", "branches"
    );
    println!("{}", rows.join("\n"));
}
