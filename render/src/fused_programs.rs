//! A fused path's programs, assembled in one place for every dialect: the GLES backend's
//! framebuffer fetch, WebGL's pixel local storage and the Vulkan backend's subpass inputs
//! (its subpass and local-read paths share the shaders). What differs between them is data
//! ([`FusedDialect`]): which include the fragment shaders paste, what they declare around it
//! (the output, the volume drawn, Vulkan's G-buffer outputs), how a stage writes its texel and
//! whether the vertex stage is GLSL.
//!
//! Every fragment shader is the dialect's preamble (its `#version`, the include's extensions,
//! the early depth test, the ES dialects' highp defaults), the layout's include as generated,
//! the declarations the stages' functions reach ([`glsl::fragment_declarations`], less what
//! the include declares), the dialect's declarations and the stage's `main`.

use gbuffer_codegen::emit::glsl::local_read::LocalRead;
use gbuffer_codegen::emit::glsl::{self as includes, Include, Interface};
use gbuffer_codegen::CompiledLayout;
use gbuffer_core::{Conversions, Named};

use crate::glsl::{self, Dialect};
use crate::on_tile::{fused_wgsl, tile_layout, Path, Stage, TRANSLATION_ENTRY};
use crate::options::Options;

/// How a fused path's fragment shaders reach the G-buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FusedDialect {
    /// GLES 3.2: framebuffer fetch, over `Include::FetchPacked` or `Include::FetchNative`.
    Fetch(Include),
    /// WebGL 2: ANGLE's pixel local storage.
    WebGlPixelLocalStorage,
    /// Vulkan: the packed words as subpass inputs in descriptor set 1, written through colour
    /// outputs (the same shaders for a render pass's subpass and for dynamic rendering local
    /// read).
    VulkanSubpass,
}

impl FusedDialect {
    /// The dialect of a fused path (none for the two-pass path).
    pub fn of(path: Path) -> Option<FusedDialect> {
        match path {
            Path::FetchPacked => Some(FusedDialect::Fetch(Include::FetchPacked)),
            Path::FetchNative => Some(FusedDialect::Fetch(Include::FetchNative)),
            Path::Subpass | Path::LocalRead | Path::LocalReadOrdered => {
                Some(FusedDialect::VulkanSubpass)
            }
            Path::TwoPass => None,
        }
    }

    /// The GLSL its shaders are written in.
    pub fn glsl(self) -> Dialect {
        match self {
            FusedDialect::Fetch(_) => Dialect::Gles,
            FusedDialect::WebGlPixelLocalStorage => Dialect::WebGl,
            FusedDialect::VulkanSubpass => Dialect::Vulkan,
        }
    }

    /// The layout's include its fragment shaders paste.
    pub fn include(self) -> Include {
        match self {
            FusedDialect::Fetch(include) => include,
            FusedDialect::WebGlPixelLocalStorage => Include::WebGlPixelLocalStorage,
            FusedDialect::VulkanSubpass => Include::SubpassPacked,
        }
    }

    /// The descriptor set of the include's input attachments (set 0 holds the renderer's
    /// textures on Vulkan; the GL includes have no sets).
    fn set(self) -> u32 {
        match self {
            FusedDialect::VulkanSubpass => 1,
            _ => 0,
        }
    }

    /// Whether its vertex stages are GLSL translated from the WGSL (GL's dialects) or left to
    /// the backend (Vulkan takes naga's SPIR-V: naga's GLSL names GL's vertex and instance
    /// indices, which Vulkan's GLSL renames).
    fn translates_vertex(self) -> bool {
        self != FusedDialect::VulkanSubpass
    }

    /// What the fragment shaders declare beside the include: the output `frame_colour` after
    /// the G-buffer's attachments (framebuffer fetch reads and writes it in place; WebGL's
    /// only colour output; Vulkan's after a `uvec4` output per packed attachment) and the
    /// volume drawn, `volume_index` (a uniform on GL, a push constant on Vulkan). Each draw
    /// writes only what it changes.
    fn declarations(self, interface: &Interface) -> String {
        let attachments = interface.attachments.len();
        match self {
            FusedDialect::Fetch(_) => format!(
                "layout(location = {attachments}) inout highp vec4 frame_colour;\nuniform highp uint volume_index;\n"
            ),
            FusedDialect::WebGlPixelLocalStorage => {
                "layout(location = 0) out highp vec4 frame_colour;\nuniform highp uint volume_index;\n"
                    .to_string()
            }
            FusedDialect::VulkanSubpass => {
                let outputs: String = (0..attachments)
                    .map(|index| {
                        format!("layout(location = {index}) out highp uvec4 {};\n", gbuffer_output(index))
                    })
                    .collect();
                format!(
                    "{outputs}layout(location = {attachments}) out highp vec4 frame_colour;\n\
                     layout(push_constant) uniform Volume {{\n    uint volume_index;\n}};\n"
                )
            }
        }
    }

    /// The highp defaults of the ES dialects (Vulkan's GLSL is always highp).
    fn precision(self) -> &'static str {
        match self {
            FusedDialect::VulkanSubpass => "",
            _ => "precision highp float;\nprecision highp int;\n",
        }
    }
}

/// The Vulkan fragment output of packed G-buffer attachment `index`.
fn gbuffer_output(index: usize) -> String {
    format!("gbuffer_out{index}")
}

/// One stage's program.
#[derive(Clone, Debug)]
pub struct FusedProgram {
    /// What it draws.
    pub stage: Stage,
    /// The vertex shader, GLSL of the WGSL's [`Stage::vertex_entry`], in GL's dialects; none
    /// on Vulkan, whose backend writes that entry point as SPIR-V from [`FusedPrograms::wgsl`].
    pub vertex: Option<String>,
    /// The fragment shader.
    pub fragment: String,
    /// Each sampler uniform either shader declares, with the binding (texture unit) of the
    /// texture it samples, which a host without binding qualifiers (WebGL) sets by name.
    pub samplers: Vec<(String, u32)>,
}

impl FusedProgram {
    /// The GLSL vertex shader a GL host links the program with: an error naming the stage for
    /// a Vulkan program, whose vertex stage its backend writes as SPIR-V.
    pub fn glsl_vertex(&self) -> Result<&str, String> {
        self.vertex.as_deref().ok_or_else(|| {
            format!(
                "the {} program has no GLSL vertex shader: its dialect leaves the vertex stage to the Vulkan backend",
                self.stage.name()
            )
        })
    }
}

/// A fused path's programs and what its host needs to draw them.
#[derive(Clone, Debug)]
pub struct FusedPrograms {
    /// The include the fragment shaders paste.
    pub include: Include,
    /// Its interface: the G-buffer's attachments (the output follows them) or planes.
    pub interface: Interface,
    /// The renderer's WGSL the programs were translated from.
    pub wgsl: String,
    /// One program per stage, in [`Stage::ALL`]'s order.
    pub programs: Vec<FusedProgram>,
    /// Vulkan's: where a dynamic rendering host puts each attachment and its input index (the
    /// include's `.local_read.json`); `None` for the GL dialects.
    pub local_read: Option<LocalRead>,
    /// WebGL's: the JavaScript module that attaches the planes (the include's `.webgl_pls.js`);
    /// `None` for the other dialects.
    pub webgl_host: Option<String>,
}

/// The programs of the fused path of `dialect` for `options`.
pub fn fused_programs(options: &Options, dialect: FusedDialect) -> Result<FusedPrograms, String> {
    let layout = tile_layout(options)?;
    let model = layout.layout();
    // Compiled once: the include and the texel's GLSL name come from the same value.
    let compiled =
        CompiledLayout::new(&model, Conversions::Exact).map_err(|error| error.to_string())?;
    let include = dialect.include();
    let (include_text, interface) =
        includes::include(&compiled, include, dialect.set()).map_err(|error| error.to_string())?;
    let local_read = LocalRead::of(&compiled, &interface, dialect.set());
    let webgl_host = (dialect == FusedDialect::WebGlPixelLocalStorage)
        .then(|| includes::webgl::host_module(&compiled, &interface));
    let wgsl = fused_wgsl(options, layout, -1.0);
    let stages = glsl::fragment_declarations(&wgsl, TRANSLATION_ENTRY, dialect.glsl(), &interface)?;
    let store = match dialect {
        // The include's own store writes the attachments or planes.
        FusedDialect::Fetch(_) | FusedDialect::WebGlPixelLocalStorage => {
            format!("    {}(texel);\n", model.symbols().store())
        }
        FusedDialect::VulkanSubpass => {
            includes::store_statements(&compiled, &interface, |attachment| {
                gbuffer_output(attachment.index as usize)
            })
        }
    };
    let (texel, load) = (&compiled.names().layout, model.symbols().load());
    let extensions: String = include
        .shader_extensions()
        .iter()
        .map(|extension| format!("#extension {extension} : require\n"))
        .collect();
    // The depth test runs before the fragment shader where the dialect allows: a shader that
    // reads the attachments it writes (a subpass input, framebuffer fetch) is otherwise shaded
    // before its test, and lavapipe then ran the whole lighting draw's arithmetic for the sky's
    // pixels too, a third of that draw's time at 1280x720. No fused stage writes depth from its
    // shader, so testing first changes no pixel (`discard` after an early test is allowed).
    let preamble = format!(
        "{}\n{extensions}{}{}",
        dialect.glsl().version_line(),
        dialect.glsl().early_fragment_tests(),
        dialect.precision()
    );
    let declarations = dialect.declarations(&interface);
    let programs = Stage::ALL
        .iter()
        .map(|&stage| {
            let main = match dialect {
                // Pixel local storage forbids `discard`.
                FusedDialect::WebGlPixelLocalStorage => {
                    stage.pixel_local_storage_main(texel, &load, &store)
                }
                _ => stage.fragment_main(texel, &load, &store),
            };
            let fragment = format!(
                "{preamble}\n{include_text}\n{}\n{declarations}{main}",
                stages.text
            );
            let mut samplers = stages.samplers.clone();
            let vertex = match dialect.translates_vertex() {
                true => {
                    let vertex = glsl::write_stage(
                        &wgsl,
                        naga::ShaderStage::Vertex,
                        stage.vertex_entry(),
                        dialect.glsl(),
                    )
                    .map_err(|error| format!("the {} program: {error}", stage.name()))?;
                    samplers.extend(vertex.samplers);
                    Some(vertex.text)
                }
                false => None,
            };
            samplers.sort();
            samplers.dedup();
            Ok(FusedProgram {
                stage,
                vertex,
                fragment,
                samplers,
            })
        })
        .collect::<Result<_, String>>()?;
    Ok(FusedPrograms {
        include,
        interface,
        wgsl,
        programs,
        local_read,
        webgl_host,
    })
}
