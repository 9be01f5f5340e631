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
//! naga's module of the layout's WGSL and its IR printed as GLSL ES by gbuffer-translate's
//! printer (exact or fast conversions), and every include pastes that one translation, so WGSL
//! stays the one source of truth. Where GLSL reserves a name, the printer renames it as naga's
//! GLSL writer does (`sampler` -> `sampler_`, `main` -> `main_`, a name ending in a digit gets a
//! `_`), and the hand-written parts take those names from it ([`crate::GlslNames`]).
//!
//! Every function here reads a [`CompiledLayout`] (its lowered words, its names, its
//! translation) and calls nothing of the compile step but its accessors.

mod attachments;
mod interface;
pub mod local_read;
mod pixel_local_storage;
pub mod webgl;

use std::fmt::Write as _;

pub use attachments::store_statements;
pub use interface::{subpass_input_type, Attachment, Include, Interface};
pub use pixel_local_storage::{pls_member_type, PlsBlock};

use gbuffer_core::codecs::max_code;
use gbuffer_core::layout::{Member, Word};
use gbuffer_core::{Direction, FieldType, ScalarKind, Symbols};

use crate::{CompiledLayout, TranslationError};
use gbuffer_translate::items::ItemKind;
use gbuffer_translate::printer::Item;

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

/// A bit word's value in GLSL: each field's code from `value(field)`, shifted into place and
/// combined.
fn bit_word_value(symbols: &Symbols, word: &Word, value: impl Fn(usize) -> String) -> String {
    let codes: Vec<String> = word
        .members
        .iter()
        .map(|member| {
            let encode = symbols.bit_field(Direction::Encode, member.field);
            match member.offset {
                0 => format!("{encode}({})", value(member.field)),
                offset => format!("({encode}({}) << {offset}u)", value(member.field)),
            }
        })
        .collect();
    codes.join(" | ")
}

/// The include's text and its interface, around the compiled layout's translation. Vulkan
/// includes put their input attachments in descriptor set `set` (binding = input attachment
/// index). A tool that writes several includes of a layout compiles it once and asks for each.
pub fn include(
    compiled: &CompiledLayout,
    kind: Include,
    set: u32,
) -> Result<(String, Interface), TranslationError> {
    let mut interface = Interface::new(compiled, kind);
    let mut items = Vec::new();
    let text = match kind {
        Include::PixelLocalStorage(block) => {
            pixel_local_storage::pixel_local_storage(compiled, block, &interface, &mut items)
        }
        Include::WebGlPixelLocalStorage => webgl::include(compiled, &interface, &mut items)?,
        _ => attachments::attachments(compiled, &interface, set, &mut items),
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

/// `names` with each one that repeats an earlier one given its index (`_2`), so that every
/// identifier is declared once.
fn unique(names: Vec<String>) -> Vec<String> {
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
