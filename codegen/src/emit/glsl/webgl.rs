//! WebGL 2's pixel local storage: `WEBGL_shader_pixel_local_storage` on the host, ANGLE's
//! `GL_ANGLE_shader_pixel_local_storage` in GLSL ES 3.00. It is how the web reaches tile
//! memory: ANGLE implements it with framebuffer fetch, input attachments or images, on the tile
//! of Mali, Adreno and PowerVR GPUs where it can.
//!
//! Planes are opaque uniforms, one per word of the layout, in the few formats the extension
//! allows (`rgba8`, `rgba8i`, `rgba8ui`, `r32f`, `r32i`, `r32ui`: no `rgb10_a2`, no
//! `r11f_g11f_b10f`). So every word is an `r32ui` plane holding its packed bits, converted by
//! the layout's own functions (translated from its WGSL by naga), except an `rgba8` word under
//! fast conversions: that is an `rgba8` plane, converted by the GPU, as the fast contract
//! allows (one code at most from the mirror), which saves the packing arithmetic GLSL ES 3.00
//! lacks builtins for. An `r32f` word stays `r32ui`: its conversion is a free bit cast, and a
//! float plane may flush denormals or change a NaN, which the contract keeps.
//!
//! Beside the include, [`host_module`] writes the JavaScript (an ES module) that attaches the
//! planes, begins and ends the pass and checks what the browser offers.

use std::fmt::Write as _;

use super::unique;
use super::{bit_field_code, bit_word_value, declared_type};
use super::{declare, Include, Interface};
use crate::wgsl::mode_suffix;
use crate::CompiledLayout;
use crate::TranslationError;
use gbuffer_core::format::Format;
use gbuffer_core::layout::{Field, Storage};
use gbuffer_core::report::webgl_planes;
use gbuffer_core::{Direction, ScalarKind};
use gbuffer_files::json::string;
use gbuffer_translate::items::ItemKind;
use gbuffer_translate::printer::Item;

/// The format of a plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PlaneFormat {
    /// A word's packed bits, as the layout's functions convert them.
    R32ui,
    /// An `rgba8` word under fast conversions, converted by the GPU.
    Rgba8,
}

impl PlaneFormat {
    /// The layout qualifier: `r32ui` or `rgba8`.
    pub fn qualifier(self) -> &'static str {
        match self {
            PlaneFormat::R32ui => "r32ui",
            PlaneFormat::Rgba8 => "rgba8",
        }
    }

    /// The plane's opaque type in GLSL.
    pub fn glsl_type(self) -> &'static str {
        match self {
            PlaneFormat::R32ui => "upixelLocalANGLE",
            PlaneFormat::Rgba8 => "pixelLocalANGLE",
        }
    }

    /// The WebGL 2 sized internal format of the plane's texture, as JavaScript names it.
    pub fn internal_format(self) -> &'static str {
        match self {
            PlaneFormat::R32ui => "R32UI",
            PlaneFormat::Rgba8 => "RGBA8",
        }
    }
}

/// One plane of the include: a word of the layout.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plane {
    /// The GLSL uniform that declares it.
    pub name: String,
    /// The include's function that writes it whole from the fields it holds.
    pub store: String,
    /// Its binding: the plane index the host attaches a texture to (the word's index).
    pub binding: u32,
    /// Its format.
    pub format: PlaneFormat,
    /// The fields it holds, as the layout names them.
    pub fields: Vec<String>,
    /// What it holds and who converts it, for comments: `albedo (rgba8, converted by the GPU)`.
    pub contents: String,
}

/// What each field's load is called in the include: `load_pls_<layout>_<field>`, with the
/// field's GLSL name (a name naga gave a trailing `_` loses it).
pub fn field_loads(compiled: &CompiledLayout) -> Vec<String> {
    let symbols = compiled.lowered().symbols();
    unique(
        compiled
            .names()
            .fields
            .iter()
            .map(|field| symbols.load_pls(field))
            .collect(),
    )
}

/// The planes of a compiled layout, in binding order.
pub fn planes(compiled: &CompiledLayout) -> Vec<Plane> {
    let (layout, conversions) = (compiled.layout(), compiled.conversions());
    let symbols = compiled.lowered().symbols();
    let words = compiled.lowered().words();
    let word_names = compiled.word_names();
    let plane_names = unique(word_names.iter().map(|name| symbols.plane(name)).collect());
    let stores = unique(
        word_names
            .iter()
            .map(|name| symbols.store_pls(name))
            .collect(),
    );
    words
        .iter()
        .zip(plane_names.into_iter().zip(stores))
        .enumerate()
        .map(|(index, (word, (name, store)))| {
            let first = &layout.fields[word.members[0].field];
            let fields: Vec<String> = word
                .members
                .iter()
                .map(|member| layout.fields[member.field].name.clone())
                .collect();
            let native = !word.is_bit_fields
                && word.format == Format::Rgba8
                && !first
                    .conversions
                    .unwrap_or(conversions)
                    .is_exact_for(Format::Rgba8);
            Plane {
                name,
                store,
                binding: index as u32,
                format: if native {
                    PlaneFormat::Rgba8
                } else {
                    PlaneFormat::R32ui
                },
                contents: match (word.is_bit_fields, native) {
                    (true, _) => format!("{} (bit fields)", fields.join(", ")),
                    (false, true) => format!("{} (rgba8, converted by the GPU)", fields[0]),
                    (false, false) => format!("{} ({}, packed)", fields[0], word.format),
                },
                fields,
            }
        })
        .collect()
}

/// The include's text: the header, the planes, the translated functions and the accessors.
pub(super) fn include(
    compiled: &CompiledLayout,
    interface: &Interface,
    items: &mut Vec<Item>,
) -> Result<String, TranslationError> {
    let (layout, conversions) = (compiled.layout(), compiled.conversions());
    let (translation, names) = (compiled.glsl(), compiled.names());
    let symbols = compiled.lowered().symbols();
    let mut out = String::new();
    let native = interface
        .planes
        .iter()
        .filter(|plane| plane.format == PlaneFormat::Rgba8)
        .count();
    super::write_header(
        &mut out,
        &format!(
            "WebGL pixel local storage of G-buffer layout `{}`: {} planes ({} packed r32ui, {native} rgba8 converted by the GPU).",
            layout.name,
            interface.planes.len(),
            interface.planes.len() - native
        ),
        interface,
    );
    for plane in &interface.planes {
        let declaration = format!(
            "layout(binding = {}, {}) uniform highp {} {};\n",
            plane.binding,
            plane.format.qualifier(),
            plane.format.glsl_type(),
            plane.name
        );
        out.push_str(&declaration);
        declare(
            items,
            ItemKind::Attachment,
            plane.name.clone(),
            &declaration,
        );
    }
    out.push('\n');
    out.push_str(&translation.text);
    items.extend(translation.items.iter().cloned());

    let words = compiled.lowered().words();
    let locations = compiled.lowered().locations();
    // Each field's value from the plane it lives in, given as an expression: a `highp uint`
    // for an r32ui plane, a `highp vec4` for an rgba8 one.
    let field_value = |index: usize, plane: &str| -> Result<String, TranslationError> {
        let field = &layout.fields[index];
        let (word, member) = locations[index];
        let value = match (field.storage, interface.planes[word].format) {
            (Storage::Bits(_), _) => {
                let decode = symbols.bit_field(Direction::Decode, index);
                return Ok(format!("{decode}({})", bit_field_code(plane, member)));
            }
            (Storage::Word(_), PlaneFormat::Rgba8) => plane.to_string(),
            (Storage::Word(format), PlaneFormat::R32ui) => {
                let suffix = mode_suffix(field, conversions);
                let decode = symbols.format_word(Direction::Decode, format, suffix);
                translation.check_defines(&decode)?;
                format!("{decode}({plane})")
            }
        };
        Ok(narrowed(&value, field))
    };
    let load = |plane: &Plane| match plane.format {
        PlaneFormat::R32ui => format!("pixelLocalLoadANGLE({}).x", plane.name),
        PlaneFormat::Rgba8 => format!("pixelLocalLoadANGLE({})", plane.name),
    };

    let _ = writeln!(out, "\n// Each field, loaded from its plane alone.");
    for (index, (field, name)) in layout.fields.iter().zip(field_loads(compiled)).enumerate() {
        let plane = &interface.planes[locations[index].0];
        let text = format!(
            "{} {name}() {{\n    return {};\n}}\n",
            declared_type(field.ty),
            field_value(index, &load(plane))?
        );
        out.push_str(&text);
        declare(items, ItemKind::Function, name, &text);
    }

    let _ = writeln!(
        out,
        "\n// Each plane, written whole from the fields it holds."
    );
    for (word, plane) in words.iter().zip(&interface.planes) {
        let parameters: Vec<String> = word
            .members
            .iter()
            .map(|member| {
                let field = &layout.fields[member.field];
                format!("{} {}", declared_type(field.ty), names.fields[member.field])
            })
            .collect();
        let stored = if word.is_bit_fields {
            let value = bit_word_value(symbols, word, |field| names.fields[field].clone());
            format!("uvec4({value}, 0u, 0u, 0u)")
        } else {
            let index = word.members[0].field;
            let field = &layout.fields[index];
            let widened = widened(&names.fields[index], field, word.format);
            match plane.format {
                PlaneFormat::Rgba8 => widened,
                PlaneFormat::R32ui => {
                    let suffix = mode_suffix(field, conversions);
                    let encode = symbols.format_word(Direction::Encode, word.format, suffix);
                    translation.check_defines(&encode)?;
                    format!("uvec4({encode}({widened}), 0u, 0u, 0u)")
                }
            }
        };
        let text = format!(
            "void {}({}) {{\n    pixelLocalStoreANGLE({}, {stored});\n}}\n",
            plane.store,
            parameters.join(", "),
            plane.name
        );
        out.push_str(&text);
        declare(items, ItemKind::Function, plane.store.clone(), &text);
    }

    let texel = &names.layout;
    let start = out.len();
    let _ = writeln!(
        out,
        "\n// The texel in the planes, unpacked: each plane loaded once."
    );
    let _ = writeln!(out, "{texel} {}() {{", symbols.load());
    for (binding, plane) in interface.planes.iter().enumerate() {
        let ty = match plane.format {
            PlaneFormat::R32ui => "highp uint",
            PlaneFormat::Rgba8 => "highp vec4",
        };
        let _ = writeln!(out, "    {ty} plane{binding} = {};", load(plane));
    }
    let values: Vec<String> = (0..layout.fields.len())
        .map(|index| field_value(index, &format!("plane{}", locations[index].0)))
        .collect::<Result<_, _>>()?;
    let _ = writeln!(out, "    return {texel}({});\n}}", values.join(", "));
    declare(items, ItemKind::Function, symbols.load(), &out[start..]);
    let start = out.len();
    let _ = writeln!(out, "\n// Writes a texel into the planes.");
    let _ = writeln!(out, "void {}({texel} texel) {{", symbols.store());
    for (word, plane) in words.iter().zip(&interface.planes) {
        let arguments: Vec<String> = word
            .members
            .iter()
            .map(|member| format!("texel.{}", names.fields[member.field]))
            .collect();
        let _ = writeln!(out, "    {}({});", plane.store, arguments.join(", "));
    }
    out.push_str("}\n");
    declare(items, ItemKind::Function, symbols.store(), &out[start..]);
    Ok(out)
}

/// A whole word's value narrowed to the field's components (`.xyz` of a `vec4`).
fn narrowed(value: &str, field: &Field) -> String {
    let channels = match field.storage {
        Storage::Word(format) => format.channels().len(),
        Storage::Bits(_) => return value.to_string(),
    };
    if field.ty.components == channels {
        value.to_string()
    } else {
        format!("{value}.{}", &"xyzw"[..field.ty.components])
    }
}

/// A field's GLSL value `name` widened with zeros to its format's channels, as the format's
/// encode function (and an rgba8 plane) takes it.
fn widened(name: &str, field: &Field, format: Format) -> String {
    let channels = format.channels().len();
    if field.ty.components == channels {
        return name.to_string();
    }
    let (vector, zero) = match format.scalar_kind() {
        ScalarKind::Float => ("vec", "0.0"),
        ScalarKind::Uint | ScalarKind::Bool => ("uvec", "0u"),
        ScalarKind::Sint => ("ivec", "0"),
    };
    let zeros = vec![zero; channels - field.ty.components].join(", ");
    format!("{vector}{channels}({name}, {zeros})")
}

/// The JavaScript ES module beside the include: the planes as data, and the host calls a WebGL
/// 2 program makes around a pass that uses them, in the form Chromium ships.
pub fn host_module(compiled: &CompiledLayout, interface: &Interface) -> String {
    let include_file =
        Include::WebGlPixelLocalStorage.file_name(compiled.lowered().symbols(), "glsl");
    let mut out = String::new();
    let _ = writeln!(
        out,
        "// WebGL 2 host code for `{include_file}`, the pixel local storage of G-buffer layout\n\
         // `{}`. Generated by gbuffer's codegen: edit the layout, not this file.\n\
         //\n\
         // The extension is WEBGL_shader_pixel_local_storage, a draft: Chromium ships it behind\n\
         // --enable-webgl-draft-extensions (chrome://flags, \"WebGL Draft Extensions\"). Its calls\n\
         // here are Chromium's, which differ from the Khronos draft where marked; its token values\n\
         // differ too, so only the extension object's constants are used, never numbers.\n\
         //\n\
         // {}.",
        compiled.layout().name,
        webgl_planes(interface.planes.len())
    );
    out.push_str(
        "\n/** The planes in binding order: the uniform, the texture format, the fields held. */\n",
    );
    out.push_str("export const PLANES = Object.freeze([\n");
    for plane in &interface.planes {
        let fields: Vec<String> = plane.fields.iter().map(|field| string(field)).collect();
        let _ = writeln!(
            out,
            "  Object.freeze({{ name: {}, binding: {}, internalFormat: {}, fields: [{}] }}),",
            string(&plane.name),
            plane.binding,
            string(plane.format.internal_format()),
            fields.join(", ")
        );
    }
    out.push_str("]);\n");
    out.push_str(HOST_FUNCTIONS);
    out
}

/// The host functions, the same for every layout: they read [`PLANES`] (the JavaScript
/// constant) for what differs.
const HOST_FUNCTIONS: &str = r#"
/**
 * The extension, once `gl` is checked: a WebGL 2 context, the extension present, enough planes
 * for the layout and `colourOutputs` more (planes and colour outputs share one limit). Throws
 * an Error that names what is missing.
 */
export function enablePixelLocalStorage(gl, colourOutputs = 0) {
  if (typeof WebGL2RenderingContext === "undefined" || !(gl instanceof WebGL2RenderingContext)) {
    throw new Error("pixel local storage needs a WebGL 2 context");
  }
  const pls = gl.getExtension("WEBGL_shader_pixel_local_storage");
  if (pls === null) {
    throw new Error(
      "WEBGL_shader_pixel_local_storage is not offered (Chromium: --enable-webgl-draft-extensions)",
    );
  }
  const planes = gl.getParameter(pls.MAX_PIXEL_LOCAL_STORAGE_PLANES_WEBGL);
  const combined = gl.getParameter(
    pls.MAX_COMBINED_DRAW_BUFFERS_AND_PIXEL_LOCAL_STORAGE_PLANES_WEBGL,
  );
  if (planes < PLANES.length) {
    throw new Error(`the layout needs ${PLANES.length} planes; this context offers ${planes}`);
  }
  if (combined < PLANES.length + colourOutputs) {
    throw new Error(
      `${PLANES.length} planes and ${colourOutputs} colour outputs need ` +
        `${PLANES.length + colourOutputs}; this context offers ${combined} together`,
    );
  }
  return pls;
}

/** One texture per plane, `width` x `height`, in its format (immutable storage, one level). */
export function createPlaneTextures(gl, width, height) {
  return PLANES.map((plane) => {
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl[plane.internalFormat], width, height);
    return texture;
  });
}

/**
 * Attaches `textures` (one per plane, as createPlaneTextures makes them) as the planes of the
 * framebuffer bound to DRAW_FRAMEBUFFER. `noncoherent` asks for ANGLE's non-coherent path,
 * which needs barrier() between draws that overlap.
 */
export function attachPlanes(gl, pls, textures, noncoherent = false) {
  const usage = noncoherent ? pls.PIXEL_LOCAL_USAGE_ALWAYS_NONCOHERENT_BIT_WEBGL : 0;
  PLANES.forEach((plane, index) => {
    // Chromium takes a fifth argument, the usage; the draft's call has four
    // (plane, texture, level, layer).
    pls.framebufferTexturePixelLocalStorageWEBGL(plane.binding, textures[index], 0, 0, usage);
  });
}

/**
 * Begins pixel local storage on the bound draw framebuffer. `load` is "zero" (every plane
 * starts at zero), "clear" (at `clearValues[binding]`, four numbers each, unsigned integers for
 * an R32UI plane and floats for an RGBA8 one) or "load" (what the textures hold). DITHER is
 * disabled first: begin fails while it is enabled, as it is by default.
 */
export function beginPixelLocalStorage(gl, pls, load = "zero", clearValues = []) {
  gl.disable(gl.DITHER);
  const operation = {
    zero: pls.LOAD_OP_ZERO_WEBGL,
    clear: pls.LOAD_OP_CLEAR_WEBGL,
    load: pls.LOAD_OP_LOAD_WEBGL,
  }[load];
  if (operation === undefined) {
    throw new Error(`load is "zero", "clear" or "load", not ${JSON.stringify(load)}`);
  }
  if (load === "clear") {
    PLANES.forEach((plane) => {
      const value = clearValues[plane.binding] ?? [0, 0, 0, 0];
      if (plane.internalFormat === "R32UI") {
        pls.framebufferPixelLocalClearValueuivWEBGL(plane.binding, value);
      } else {
        pls.framebufferPixelLocalClearValuefvWEBGL(plane.binding, value);
      }
    });
  }
  pls.beginPixelLocalStorageWEBGL(PLANES.map(() => operation));
}

/**
 * Between two draws of one pass where the second reads what the first wrote at the same pixel:
 * a barrier where the storage is not coherent, nothing where it is.
 */
export function pixelLocalStorageBarrier(pls) {
  if (!pls.isCoherent()) {
    pls.pixelLocalStorageBarrierWEBGL();
  }
}

/**
 * Ends pixel local storage. `store` true writes the planes back to their textures; false
 * discards them, which is the point on a tiler: a G-buffer that is cleared on tile and never
 * stored costs no bandwidth at all.
 */
export function endPixelLocalStorage(gl, pls, store = false) {
  const operation = store ? pls.STORE_OP_STORE_WEBGL : gl.DONT_CARE;
  pls.endPixelLocalStorageWEBGL(PLANES.map(() => operation));
}
"#;
