//! GLSL ES includes for engines that render with OpenGL ES or Vulkan GLSL:
//!
//! - pixel local storage blocks (EXT_shader_pixel_local_storage), where the hardware does the
//!   conversions, as the seeds write them;
//! - framebuffer fetch (EXT_shader_framebuffer_fetch), over the packed words in `RGBA32UI`
//!   attachments or over one attachment per word: a whole-word field's in its own format, a
//!   word of bit fields in `R32UI`;
//! - Vulkan GLSL subpass inputs, packed or one per word likewise, with what a host sets to read
//!   them in one dynamic rendering ([`local_read`]);
//! - WebGL 2's pixel local storage (ANGLE's `GL_ANGLE_shader_pixel_local_storage`), one plane
//!   per word, with the JavaScript that drives it ([`webgl`]).
//!
//! Every include is pasted (or `#include`d) after the user's own preamble: it carries no
//! `#version`, no `#extension` and no default precision statement, and gives each of its
//! declarations an explicit `highp`, so it compiles under any preamble its header comment
//! lists and leaves the user's defaults alone. What it needs from the preamble and the host is
//! data too: [`Interface`].
//!
//! The functions are not written twice: the compiled layout ([`crate::CompiledLayout`]) holds
//! naga's module of the layout's WGSL and its IR printed as GLSL ES by [`printer`] (exact or
//! fast conversions), and every include pastes that one translation, so WGSL stays the one
//! source of truth. Where GLSL reserves a name, the printer renames it as naga's GLSL writer
//! does (`sampler` -> `sampler_`, `main` -> `main_`, a name ending in a digit gets a `_`), and
//! the hand-written parts take those names from it ([`GlslNames`]).

mod interface;
pub mod local_read;
pub mod printer;
pub(crate) mod translate;
pub mod webgl;

use std::fmt::Write as _;

pub use interface::{subpass_input_type, Attachment, Include, Interface};
pub use translate::{GlslNames, Translation};

use gbuffer_core::Named;

use gbuffer_core::codecs::max_code;
use gbuffer_core::format::Format;
use gbuffer_core::layout::{Layout, Member, Word};
use gbuffer_core::Conversions;
use gbuffer_core::{FieldType, ScalarKind, Symbols};

use crate::emit::items::ItemKind;
use crate::CompiledLayout;
use printer::Item;

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

/// A field type's GLSL declaration type, with `highp` for floats and integers.
fn declared_type(ty: FieldType) -> String {
    let base = match ty.scalar {
        ScalarKind::Float => "vec",
        ScalarKind::Uint => "uvec",
        ScalarKind::Sint => "ivec",
        ScalarKind::Bool => return "bool".to_string(),
    };
    match (ty.scalar, ty.components) {
        (ScalarKind::Float, 1) => "highp float".to_string(),
        (ScalarKind::Uint, 1) => "highp uint".to_string(),
        (ScalarKind::Sint, 1) => "highp int".to_string(),
        (_, components) => format!("highp {base}{components}"),
    }
}

/// What each word is called in GLSL (its PLS member, its native attachment): a whole word its
/// field's name, a word of bit fields its fields' names joined, ending in `_bits`. Joined names
/// can meet another word's (fields `a_1` and `a_`, trimmed, both give `a_1_bits`; a field may be
/// called `a_bits`): such a word is called `<joined>_word<index>_bits` instead, so every name is
/// declared once.
pub(crate) fn word_names(words: &[Word], names: &GlslNames) -> Vec<String> {
    let whole: Vec<&str> = words
        .iter()
        .filter(|word| !word.is_bit_fields)
        .map(|word| names.fields[word.members[0].field].as_str())
        .collect();
    let mut taken: Vec<String> = Vec::new();
    for (index, word) in words.iter().enumerate() {
        if !word.is_bit_fields {
            taken.push(names.fields[word.members[0].field].clone());
            continue;
        }
        // naga's names may end in `_` (`field_0_`): trimmed, so that no `__` appears.
        let fields: Vec<&str> = word
            .members
            .iter()
            .map(|member| names.fields[member.field].trim_end_matches('_'))
            .collect();
        let joined = fields.join("_");
        let name = format!("{joined}_bits");
        let clashes = whole.contains(&name.as_str()) || taken.contains(&name);
        taken.push(if clashes {
            format!("{joined}_word{index}_bits")
        } else {
            name
        });
    }
    taken
}

/// `names` with each one that repeats an earlier one given its index (`_2`), so that every
/// identifier is declared once.
pub(crate) fn unique(names: Vec<String>) -> Vec<String> {
    let mut taken: Vec<String> = Vec::new();
    for (index, name) in names.into_iter().enumerate() {
        let name = match taken.contains(&name) {
            true => gbuffer_core::naming::glsl_identifier(&[&name, &index.to_string()]),
            false => name,
        };
        taken.push(name);
    }
    taken
}

/// `(word >> offset) & mask` in GLSL: a bit field's code out of its word.
fn bit_field_code(word: &str, member: Member) -> String {
    let shifted = match member.offset {
        0 => word.to_string(),
        offset => format!("({word} >> {offset}u)"),
    };
    match member.bits {
        32 => shifted,
        bits => format!("({shifted} & {:#x}u)", max_code(bits)),
    }
}

/// The GLSL name of bit field `field`'s encode or decode function: its WGSL name, which naga
/// keeps (the translation checks it).
fn bit_field_function(layout: &Layout, verb: &str, field: usize) -> String {
    crate::emit::wgsl::bit_field_function_name(&layout.snake_name(), verb, field)
}

/// A bit word's value in GLSL: each field's code from `value(field)`, shifted into place and
/// combined.
fn bit_word_value(layout: &Layout, word: &Word, value: impl Fn(usize) -> String) -> String {
    let codes: Vec<String> = word
        .members
        .iter()
        .map(|member| {
            let encode = bit_field_function(layout, "encode", member.field);
            match member.offset {
                0 => format!("{encode}({})", value(member.field)),
                offset => format!("({encode}({}) << {offset}u)", value(member.field)),
            }
        })
        .collect();
    codes.join(" | ")
}

/// Why a layout's WGSL did not become GLSL: naga refused it, or the printer met a construct
/// it has no form for (a bug either way, since the WGSL is generated valid).
#[derive(Debug)]
pub struct TranslationError(pub String);

impl std::fmt::Display for TranslationError {
    fn fmt(&self, out: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            out,
            "the generated WGSL could not be translated to GLSL: {}",
            self.0
        )
    }
}

impl std::error::Error for TranslationError {}

/// The include's text and its interface, for a checked layout, with exact conversions.
/// Vulkan includes put their input attachments in descriptor set `set` (binding = input
/// attachment index). It compiles the layout for this one include: a caller that writes
/// several compiles it once ([`CompiledLayout::include`]).
pub fn include(
    layout: &Layout,
    include: Include,
    set: u32,
) -> Result<(String, Interface), TranslationError> {
    include_with(layout, Conversions::Exact, include, set)
}

/// [`include`] with the chosen conversions (pixel local storage blocks have none: the hardware
/// converts).
pub fn include_with(
    layout: &Layout,
    conversions: Conversions,
    include: Include,
    set: u32,
) -> Result<(String, Interface), TranslationError> {
    CompiledLayout::new(layout, conversions)?.include(include, set)
}

/// The include's text and its interface, around the compiled layout's translation
/// ([`CompiledLayout::include`]).
pub(crate) fn write_include(
    compiled: &CompiledLayout,
    include: Include,
    set: u32,
) -> Result<(String, Interface), TranslationError> {
    let mut interface = Interface::new(compiled, include);
    let mut items = Vec::new();
    let text = match include {
        Include::PixelLocalStorage(block) => {
            pixel_local_storage(compiled, block, &interface, &mut items)
        }
        Include::WebGlPixelLocalStorage => webgl::include(compiled, &interface, &mut items)?,
        _ => attachments(compiled, &interface, set, &mut items),
    };
    interface.declares = items;
    Ok((text, interface))
}

/// The header every include starts with: what it is, and the preamble it needs.
fn write_header(out: &mut String, title: &str, interface: &Interface) {
    let _ = writeln!(out, "// {title}");
    let source = match interface.include {
        Include::PixelLocalStorage(_) => "from the layout",
        _ => "from the layout's WGSL (functions translated by naga)",
    };
    let _ = writeln!(
        out,
        "// Generated by gbuffer's codegen {source}:\n// edit the layout, not this file."
    );
    let _ = writeln!(out, "//");
    let kind = match interface.include {
        Include::SubpassPacked | Include::SubpassNative => {
            "a Vulkan GLSL fragment shader (compiled to SPIR-V)"
        }
        Include::WebGlPixelLocalStorage => "a WebGL 2 fragment shader",
        _ => "a GLSL ES fragment shader",
    };
    let _ = writeln!(
        out,
        "// Paste or #include it after the preamble of {kind}, which must have:"
    );
    let include = interface.include;
    let _ = writeln!(out, "//     #version {}", include.versions().join(" | "));
    for extension in include.shader_extensions() {
        let _ = writeln!(out, "//     #extension {extension} : require");
    }
    let _ = writeln!(
        out,
        "// It declares its own precision (highp) and leaves the shader's defaults alone."
    );
    if !interface.attachments.is_empty() {
        let _ = writeln!(out, "//\n// Attachments:");
        for attachment in &interface.attachments {
            let _ = writeln!(
                out,
                "//     {} {}: {} ({} / {})",
                if interface.include.is_vulkan() {
                    "input attachment"
                } else {
                    "location"
                },
                attachment.index,
                attachment.name,
                attachment.format.gl.name,
                attachment.format.vulkan.name
            );
        }
    }
    if !interface.planes.is_empty() {
        let _ = writeln!(
            out,
            "//\n// Planes (a texture of each format at its binding; the `.webgl_pls.js` module beside this\n// file attaches them):"
        );
        for plane in &interface.planes {
            let _ = writeln!(
                out,
                "//     binding {}: {}, {}: {}",
                plane.binding,
                plane.name,
                plane.format.internal_format(),
                plane.contents
            );
        }
        let _ = writeln!(
            out,
            "// {}.\n// The shader may not `discard`, `return` from main, or write gl_FragDepth or gl_SampleMask.",
            gbuffer_core::report::webgl_planes(interface.planes.len())
        );
    }
    let host_extensions = interface.host_extensions();
    if !host_extensions.is_empty() {
        let _ = writeln!(
            out,
            "// The host needs {} to render to them.",
            host_extensions.join(" and ")
        );
    }
    out.push('\n');
}

/// The pixel local storage block: one member per field, named as the field is in GLSL, with
/// the format's layout qualifier and type. Channels the field does not use are noted.
fn pixel_local_storage(
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
            layout.bits(),
            layout.used_bits()
        ),
        interface,
    );
    let block_start = out.len();
    let block_name = Symbols::pixel_local_storage_block(&names.layout);
    let _ = writeln!(out, "{} {block_name} {{", block.qualifier());
    let words = layout.word_contents();
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
        write_pls_bit_field_accessors((&mut out, items), compiled, block, functions, &words);
    }
    out
}

/// Records an item the include writes by hand (no WGSL twin): its kind, name and text, from
/// its comment to its end.
fn declare(items: &mut Vec<Item>, kind: ItemKind, glsl: String, text: &str) {
    items.push(Item {
        kind,
        wgsl: None,
        glsl,
        text: text.trim_start_matches('\n').to_string(),
    });
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
    let symbols = layout.symbols();
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
                let decode = bit_field_function(layout, "decode", member.field);
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
            let value = bit_word_value(layout, word, |field| names.fields[field].clone());
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

/// A framebuffer-fetch or subpass-input include: the header, one declaration per attachment,
/// the translated functions, and `load_<snake>()` (and for fetch `store_<snake>()`).
fn attachments(
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
            layout.words(),
            layout.targets()
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
    let symbols = layout.symbols();
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
            .zip(layout.field_locations())
            .enumerate()
            .map(|(index, (field, (word, member)))| {
                let read = &reads[word];
                if field.bit_field().is_some() {
                    let decode = bit_field_function(layout, "decode", index);
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
    let (layout, names) = (compiled.layout(), compiled.names());
    let mut out = String::new();
    if interface.include.is_packed() {
        let _ = writeln!(
            out,
            "    {} targets = {}(texel);",
            names.targets,
            layout.symbols().pack_targets()
        );
        for (attachment, member) in interface.attachments.iter().zip(&names.target_members) {
            let _ = writeln!(out, "    {} = targets.{member};", output(attachment));
        }
        return out;
    }
    for (word, attachment) in layout.word_contents().iter().zip(&interface.attachments) {
        if word.is_bit_fields {
            let value = bit_word_value(layout, word, |field| {
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
