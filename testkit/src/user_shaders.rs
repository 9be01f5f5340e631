//! Small user shaders around the generated GLSL includes, written as a user would: a preamble
//! of their own (a `#version`, the `#extension` lines the include's header asks for, perhaps
//! default precision statements and other extensions), the include pasted unedited, then the
//! user's code. The GLES and Vulkan tests draw with them.

use std::fmt::Write as _;

use gbuffer_codegen::emit::glsl::{self, Include};
use gbuffer_codegen::CompiledLayout;
use gbuffer_codegen::GlslNames;
use gbuffer_core::Conversions;
use gbuffer_core::{Layout, ScalarKind};
use gbuffer_gpu::harness::scalars_per_texel;

/// The preambles a user may write before an include: every `#version` it supports, each
/// without default precision, with `mediump` defaults, and with `highp` float plus an extra
/// extension line of the user's own.
pub fn preambles(include: Include) -> Vec<String> {
    let mut preambles = Vec::new();
    for version in include.versions() {
        let mut required = String::new();
        for extension in include.shader_extensions() {
            let _ = writeln!(required, "#extension {extension} : require");
        }
        let version_line = format!("#version {version}\n");
        let extra = if include.is_vulkan() {
            "#extension GL_EXT_samplerless_texture_functions : enable\n"
        } else {
            "#extension GL_OES_sample_variables : enable\n"
        };
        preambles.push(format!("{version_line}{required}"));
        preambles.push(format!(
            "{version_line}{required}precision mediump float;\nprecision mediump int;\n"
        ));
        preambles.push(format!(
            "{version_line}{extra}{required}precision highp float;\n"
        ));
    }
    preambles
}

/// Whether a preamble's GLSL has shader storage buffers (GLSL ES 3.10 and up, or desktop).
pub fn has_storage_buffers(preamble: &str) -> bool {
    !preamble.starts_with("#version 300 es")
}

/// The GLSL expression that builds the layout's texel from scalar bits; `scalar(i)` is the
/// expression of scalar `i` (a `highp uint`).
pub fn texel_from_scalars(
    layout: &Layout,
    names: &GlslNames,
    scalar: impl Fn(usize) -> String,
) -> String {
    let mut next = 0;
    let fields: Vec<String> = layout
        .fields
        .iter()
        .map(|field| {
            let components: Vec<String> = (0..field.ty.components)
                .map(|_| {
                    let bits = scalar(next);
                    next += 1;
                    match field.ty.scalar {
                        ScalarKind::Float => format!("uintBitsToFloat({bits})"),
                        ScalarKind::Uint => bits,
                        ScalarKind::Sint => format!("int({bits})"),
                        ScalarKind::Bool => format!("({bits} != 0u)"),
                    }
                })
                .collect();
            match field.ty.components {
                1 => components[0].clone(),
                n => {
                    let prefix = match field.ty.scalar {
                        ScalarKind::Float => "",
                        ScalarKind::Uint => "u",
                        ScalarKind::Sint => "i",
                        ScalarKind::Bool => "b",
                    };
                    format!("{prefix}vec{n}({})", components.join(", "))
                }
            }
        })
        .collect();
    format!("{}({})", names.layout, fields.join(", "))
}

/// The GLSL expressions of a texel variable's scalars as `uint` bits, in slot order.
pub fn scalars_of_texel(layout: &Layout, names: &GlslNames, texel: &str) -> Vec<String> {
    let mut scalars = Vec::new();
    for (field, name) in layout.fields.iter().zip(&names.fields) {
        for component in 0..field.ty.components {
            let value = if field.ty.components == 1 {
                format!("{texel}.{name}")
            } else {
                format!("{texel}.{name}.{}", &"xyzw"[component..component + 1])
            };
            scalars.push(match field.ty.scalar {
                ScalarKind::Float => format!("floatBitsToUint({value})"),
                ScalarKind::Uint => value,
                ScalarKind::Sint | ScalarKind::Bool => format!("uint({value})"),
            });
        }
    }
    scalars
}

/// The two passes of a user's shader around a framebuffer-fetch `include` under `preamble`:
/// the first builds texels from scalars read from `harness_inputs` (a texture of
/// `scalars_per_texel` words per pixel) and stores them; the second loads them, stores them
/// again and (where the GLSL has storage buffers) writes each decoded field's bits to
/// `harness_decoded`, `width` pixels a row.
pub fn fetch_user_shaders(
    layout: &Layout,
    conversions: Conversions,
    include: Include,
    preamble: &str,
    width: i32,
) -> (String, String) {
    let compiled = CompiledLayout::new(layout, conversions).unwrap();
    let (text, _) = glsl::include(&compiled, include, 0).unwrap();
    let names = compiled.names();
    let symbols = layout.symbols();
    let (load, store_texel) = (symbols.load(), symbols.store());
    let scalars = scalars_per_texel(layout);
    let texel = texel_from_scalars(layout, names, |index| format!("harness_scalar({index})"));
    let store = format!(
        "{preamble}{text}\n// The user's code.\nuniform highp usampler2D harness_inputs;\n\n\
         highp uint harness_scalar(highp int index) {{\n    highp ivec2 pixel = ivec2(gl_FragCoord.xy);\n    \
         return texelFetch(harness_inputs, ivec2(pixel.x * {scalars} + index, pixel.y), 0).x;\n}}\n\n\
         void main() {{\n    {store_texel}({texel});\n}}\n"
    );
    let mut reload = format!("{preamble}{text}\n// The user's code.\n");
    let decode = has_storage_buffers(preamble);
    if decode {
        reload.push_str(
            "layout(std430, binding = 0) buffer HarnessDecoded {\n    highp uint harness_decoded[];\n};\n\n",
        );
    }
    reload.push_str(&format!(
        "void main() {{\n    {} texel = {load}();\n    {store_texel}(texel);\n",
        names.layout
    ));
    if decode {
        reload.push_str(&format!(
            "    highp int base = (int(gl_FragCoord.y) * {width} + int(gl_FragCoord.x)) * {scalars};\n"
        ));
        for (index, scalar) in scalars_of_texel(layout, names, "texel").iter().enumerate() {
            reload.push_str(&format!(
                "    harness_decoded[base + {index}] = {scalar};\n"
            ));
        }
    }
    reload.push_str("}\n");
    (store, reload)
}
