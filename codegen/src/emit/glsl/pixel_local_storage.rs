//! The EXT pixel local storage includes (`EXT_shader_pixel_local_storage`), where the hardware
//! does the conversions, as the seeds write them: one block of the three forms a pass needs,
//! a member per word in its format's qualifier, and for bit fields the translated functions
//! with a load per field and a store per word beside the block.

use std::fmt::Write as _;

use gbuffer_core::format::Format;
use gbuffer_core::layout::Word;
use gbuffer_core::{Direction, Named, ScalarKind, Symbols};

use super::{bit_field_code, bit_word_value, declare, declared_type};
use super::{write_header, Interface};
use crate::CompiledLayout;
use gbuffer_translate::items::ItemKind;
use gbuffer_translate::printer::Item;

/// Which of the three pixel local storage block forms to declare.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PlsBlock {
    /// `__pixel_localEXT`: read and written (the lighting pass of a fused renderer).
    InOut,
    /// `__pixel_local_inEXT`: read only (the resolve pass).
    In,
    /// `__pixel_local_outEXT`: written only (the G-buffer pass).
    Out,
}

impl PlsBlock {
    /// The three forms, in the order the codegen writes them.
    pub const ALL: [PlsBlock; 3] = [PlsBlock::InOut, PlsBlock::In, PlsBlock::Out];

    /// The block qualifier.
    pub fn qualifier(self) -> &'static str {
        match self {
            PlsBlock::InOut => "__pixel_localEXT",
            PlsBlock::In => "__pixel_local_inEXT",
            PlsBlock::Out => "__pixel_local_outEXT",
        }
    }

    /// A short name for file names: `inout`, `in`, `out`.
    pub fn suffix(self) -> &'static str {
        match self {
            PlsBlock::InOut => "inout",
            PlsBlock::In => "in",
            PlsBlock::Out => "out",
        }
    }
}

/// The GLSL type a pixel local storage member of this format has: one component per channel
/// (the extension ties each format to one type).
pub fn pls_member_type(format: Format) -> &'static str {
    let channels = format.channels().len();
    match (format.scalar_kind(), channels) {
        (ScalarKind::Float, 1) => "float",
        (ScalarKind::Float, 2) => "vec2",
        (ScalarKind::Float, 3) => "vec3",
        (ScalarKind::Float, _) => "vec4",
        (ScalarKind::Sint, 2) => "ivec2",
        (ScalarKind::Sint, _) => "ivec4",
        (ScalarKind::Uint, 1) => "uint",
        (ScalarKind::Uint, 2) => "uvec2",
        (ScalarKind::Uint, _) => "uvec4",
        (ScalarKind::Bool, _) => "bool",
    }
}

/// The pixel local storage block: one member per field, named as the field is in GLSL, with
/// the format's layout qualifier and type. Channels the field does not use are noted.
pub(super) fn pixel_local_storage(
    compiled: &CompiledLayout,
    block: PlsBlock,
    interface: &Interface,
    items: &mut Vec<Item>,
) -> String {
    let (layout, names) = (compiled.layout(), compiled.names());
    let mut out = String::new();
    write_header(
        &mut out,
        &format!(
            "Pixel local storage of G-buffer layout `{}`: {} bits ({} used).",
            layout.name,
            compiled.lowered().bits(),
            layout.used_bits()
        ),
        interface,
    );
    let block_start = out.len();
    let block_name = Symbols::pixel_local_storage_block(&names.layout);
    let _ = writeln!(out, "{} {block_name} {{", block.qualifier());
    let words = compiled.lowered().words();
    for (word, name) in words.iter().zip(compiled.word_names()) {
        if word.is_bit_fields {
            let fields: Vec<String> = word
                .members
                .iter()
                .map(|member| format!("{} {}", names.fields[member.field], member.bit_range()))
                .collect();
            let _ = writeln!(
                out,
                "    layout(r32ui) highp uint {name}; // bit fields: {}",
                fields.join(", ")
            );
            continue;
        }
        let field = &layout.fields[word.members[0].field];
        let unused: Vec<String> = word.format.channels()[field.ty.components..]
            .iter()
            .map(|channel| channel.name.to_string())
            .collect();
        let note = match unused.len() {
            0 => String::new(),
            1 => format!(" // channel {} unused", unused[0]),
            _ => format!(" // channels {} unused", unused.join(", ")),
        };
        let _ = writeln!(
            out,
            "    layout({}) highp {} {name};{note}",
            word.format.name(),
            pls_member_type(word.format),
        );
    }
    out.push_str("};\n");
    declare(items, ItemKind::Block, block_name, &out[block_start..]);
    if let Some(functions) = compiled.bit_field_glsl() {
        write_pls_bit_field_accessors((&mut out, items), compiled, block, functions, words);
    }
    out
}

/// For a layout with bit fields, after its pixel local storage block: the translated
/// functions, `load_pls_<snake>_<field>()` per bit field where the block is readable and
/// `store_pls_<snake>_<word>(...)` per bit word where it is writable (a word is written
/// whole).
fn write_pls_bit_field_accessors(
    (out, items): (&mut String, &mut Vec<Item>),
    compiled: &CompiledLayout,
    block: PlsBlock,
    (functions, function_items): &(String, Vec<Item>),
    words: &[Word],
) {
    let (layout, names) = (compiled.layout(), compiled.names());
    let symbols = compiled.lowered().symbols();
    let _ = writeln!(
        out,
        "\n// The bit fields' conversions, translated by naga from the layout's WGSL.\n"
    );
    out.push_str(functions);
    items.extend(function_items.iter().cloned());
    for (word, name) in words
        .iter()
        .zip(compiled.word_names())
        .filter(|(word, _)| word.is_bit_fields)
    {
        if block != PlsBlock::Out {
            for member in &word.members {
                let field = &layout.fields[member.field];
                let decode = symbols.bit_field(Direction::Decode, member.field);
                let load = symbols.load_pls(&names.fields[member.field]);
                let start = out.len();
                let _ = writeln!(
                    out,
                    "\n// `{}` from bits {} of `{name}`.\n{} {load}() {{\n    return {decode}({});\n}}",
                    field.name,
                    member.bit_range(),
                    declared_type(field.ty),
                    bit_field_code(name, *member)
                );
                declare(items, ItemKind::Function, load, &out[start..]);
            }
        }
        if block != PlsBlock::In {
            let parameters: Vec<String> = word
                .members
                .iter()
                .map(|member| {
                    format!(
                        "{} {}",
                        declared_type(layout.fields[member.field].ty),
                        names.fields[member.field]
                    )
                })
                .collect();
            let value = bit_word_value(symbols, word, |field| names.fields[field].clone());
            let store = symbols.store_pls(name);
            let start = out.len();
            let _ = writeln!(
                out,
                "\n// Writes `{name}` whole: every bit field it holds.\nvoid {store}({}) {{\n    {name} = {value};\n}}",
                parameters.join(", ")
            );
            declare(items, ItemKind::Function, store, &out[start..]);
        }
    }
}
