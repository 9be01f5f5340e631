//! The framebuffer-fetch and Vulkan subpass-input includes: one declaration per attachment
//! (the packed words in `RGBA32UI`, or one per word in its own format), the layout's translated
//! functions, and the accessors that read (and for fetch write) the texel.

use std::fmt::Write as _;

use gbuffer_core::{Direction, ScalarKind};

use super::{bit_field_code, bit_word_value, declare, write_header};
use super::{subpass_input_type, Attachment, Include, Interface};
use crate::CompiledLayout;
use gbuffer_translate::items::ItemKind;
use gbuffer_translate::printer::Item;

/// A framebuffer-fetch or subpass-input include: the header, one declaration per attachment,
/// the translated functions, and `load_<snake>()` (and for fetch `store_<snake>()`).
pub(super) fn attachments(
    compiled: &CompiledLayout,
    interface: &Interface,
    set: u32,
    items: &mut Vec<Item>,
) -> String {
    let (layout, translation) = (compiled.layout(), compiled.glsl());
    let include = interface.include;
    let what = match include {
        Include::FetchPacked | Include::FetchNative => "Framebuffer-fetch",
        _ => "Vulkan subpass-input",
    };
    let storage = if include.is_packed() {
        format!(
            "{} packed words in {} RGBA32UI attachment(s)",
            compiled.lowered().words().len(),
            compiled.lowered().targets()
        )
    } else if layout.has_bit_fields() {
        format!(
            "one attachment per word, a field's own format or R32UI for bit fields ({})",
            interface.attachments.len()
        )
    } else {
        format!(
            "one attachment per field in its own format ({})",
            interface.attachments.len()
        )
    };
    let mut out = String::new();
    write_header(
        &mut out,
        &format!("{what} G-buffer of layout `{}`: {storage}.", layout.name),
        interface,
    );
    for attachment in &interface.attachments {
        let declaration = if include.is_vulkan() {
            format!(
                "layout(input_attachment_index = {index}, set = {set}, binding = {index}) uniform highp {} {};",
                subpass_input_type(attachment.format),
                attachment.name,
                index = attachment.index
            )
        } else {
            format!(
                "layout(location = {}) inout highp {} {};",
                attachment.index, attachment.format.glsl_type, attachment.name
            )
        };
        let _ = writeln!(out, "{declaration}");
        declare(
            items,
            ItemKind::Attachment,
            attachment.name.clone(),
            &format!("{declaration}\n"),
        );
    }
    out.push('\n');
    out.push_str(&translation.text);
    items.extend(translation.items.iter().cloned());
    write_accessors((&mut out, items), compiled, interface);
    out
}

/// What reading an attachment yields in the shader (four components): the fetched variable,
/// or `subpassLoad` of the input attachment.
fn read_attachment(attachment: &Attachment, vulkan: bool) -> String {
    if vulkan {
        format!("subpassLoad({})", attachment.name)
    } else {
        attachment.name.clone()
    }
}

/// `load_<snake>()` reading every attachment, and for fetch `store_<snake>()` writing them.
fn write_accessors(
    (out, items): (&mut String, &mut Vec<Item>),
    compiled: &CompiledLayout,
    interface: &Interface,
) {
    let (layout, names) = (compiled.layout(), compiled.names());
    let symbols = compiled.lowered().symbols();
    let texel = &names.layout;
    let vulkan = interface.include.is_vulkan();
    let reads: Vec<String> = interface
        .attachments
        .iter()
        .map(|attachment| read_attachment(attachment, vulkan))
        .collect();
    let start = out.len();
    let _ = writeln!(out, "\n// The texel in the attachments, unpacked.");
    if interface.include.is_packed() {
        let _ = writeln!(
            out,
            "{texel} {}() {{\n    return {}({}({}));\n}}",
            symbols.load(),
            symbols.unpack_targets(),
            names.targets,
            reads.join(", ")
        );
    } else {
        // Native attachments hold the values: take each field's components, or decode its
        // bits from the word's.
        let fields: Vec<String> = layout
            .fields
            .iter()
            .zip(compiled.lowered().locations())
            .enumerate()
            .map(|(index, (field, &(word, member)))| {
                let read = &reads[word];
                if field.bit_field().is_some() {
                    let decode = symbols.bit_field(Direction::Decode, index);
                    return format!("{decode}({})", bit_field_code(&format!("{read}.x"), member));
                }
                match field.ty.components {
                    4 => read.clone(),
                    n => format!("{read}.{}", &"xyzw"[..n]),
                }
            })
            .collect();
        let _ = writeln!(
            out,
            "{texel} {}() {{\n    return {texel}({});\n}}",
            symbols.load(),
            fields.join(", ")
        );
    }
    declare(items, ItemKind::Function, symbols.load(), &out[start..]);
    if vulkan {
        return;
    }
    let start = out.len();
    let _ = writeln!(out, "\n// Writes a texel into the attachments.");
    let _ = writeln!(out, "void {}({texel} texel) {{", symbols.store());
    out.push_str(&store_statements(compiled, interface, |attachment| {
        attachment.name.clone()
    }));
    out.push_str("}\n");
    declare(items, ItemKind::Function, symbols.store(), &out[start..]);
}

/// The statements that write the GLSL variable `texel` into the attachments of `interface`:
/// the packed targets through `pack_<snake>_targets`, or each field widened with zeros to its
/// attachment's four components. `output` names the variable written for each attachment: the
/// `inout` itself for fetch, the user's own `out` for a Vulkan G-buffer subpass.
pub fn store_statements(
    compiled: &CompiledLayout,
    interface: &Interface,
    output: impl Fn(&Attachment) -> String,
) -> String {
    let (layout, lowered, names) = (compiled.layout(), compiled.lowered(), compiled.names());
    let mut out = String::new();
    if interface.include.is_packed() {
        let _ = writeln!(
            out,
            "    {} targets = {}(texel);",
            names.targets,
            lowered.symbols().pack_targets()
        );
        for (attachment, member) in interface.attachments.iter().zip(&names.target_members) {
            let _ = writeln!(out, "    {} = targets.{member};", output(attachment));
        }
        return out;
    }
    for (word, attachment) in lowered.words().iter().zip(&interface.attachments) {
        if word.is_bit_fields {
            let value = bit_word_value(lowered.symbols(), word, |field| {
                format!("texel.{}", names.fields[field])
            });
            let _ = writeln!(
                out,
                "    {} = uvec4({value}, 0u, 0u, 0u);",
                output(attachment)
            );
            continue;
        }
        let field = &layout.fields[word.members[0].field];
        let name = &names.fields[word.members[0].field];
        let zero = match field.ty.scalar {
            ScalarKind::Float => ", 0.0",
            ScalarKind::Uint | ScalarKind::Bool => ", 0u",
            ScalarKind::Sint => ", 0",
        };
        let value = match 4 - field.ty.components {
            0 => format!("texel.{name}"),
            padding => format!(
                "{}(texel.{name}{})",
                attachment.format.glsl_type,
                zero.repeat(padding)
            ),
        };
        let _ = writeln!(out, "    {} = {value};", output(attachment));
    }
    out
}
