//! What host code needs to know about an include, as data: the attachments it declares (with
//! their GL internal format and Vulkan format), the extensions its shader and its host need,
//! and the lowest GLSL ES version it compiles under. Host code reads these instead of
//! repeating them, and each include's header comment says the same.

use super::webgl::Plane;
use gbuffer_core::format::{PackedTarget, TargetFormat};
use gbuffer_core::Symbols;

/// An include of the GLSL family, by how the G-buffer reaches the shader.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Include {
    /// EXT_shader_framebuffer_fetch over the packed words: `inout highp uvec4` attachments in
    /// `RGBA32UI`, four words each. Fits layouts of up to 32 words in 8 attachments.
    FetchPacked,
    /// EXT_shader_framebuffer_fetch with one attachment per word: a whole-word field's in its
    /// own format (as Arm's deferred example does: the driver converts), a word of bit fields
    /// in `R32UI` (the include's code converts).
    FetchNative,
    /// Vulkan GLSL: the packed words as `usubpassInput`s.
    SubpassPacked,
    /// Vulkan GLSL: one input attachment per word, as [`Include::FetchNative`].
    SubpassNative,
    /// EXT_shader_pixel_local_storage: one block member per word (a whole-word field in its
    /// format, the hardware converting; a word of bit fields as `r32ui`, with the functions
    /// and accessors that convert them).
    PixelLocalStorage(super::PlsBlock),
    /// WebGL 2's pixel local storage (ANGLE's GLSL extension): one plane per word, `r32ui`
    /// with the packed bits, or `rgba8` for an rgba8 word under fast conversions.
    WebGlPixelLocalStorage,
}

impl Include {
    /// Every include, in the order the codegen writes them.
    pub const ALL: [Include; 8] = [
        Include::PixelLocalStorage(super::PlsBlock::InOut),
        Include::PixelLocalStorage(super::PlsBlock::In),
        Include::PixelLocalStorage(super::PlsBlock::Out),
        Include::WebGlPixelLocalStorage,
        Include::FetchPacked,
        Include::FetchNative,
        Include::SubpassPacked,
        Include::SubpassNative,
    ];

    /// Whether the attachments hold the packed words (`RGBA32UI`) rather than one field each.
    pub fn is_packed(self) -> bool {
        matches!(self, Include::FetchPacked | Include::SubpassPacked)
    }

    /// Whether the include is Vulkan GLSL (compiled for SPIR-V), not GLSL ES for GLES.
    pub fn is_vulkan(self) -> bool {
        matches!(self, Include::SubpassPacked | Include::SubpassNative)
    }

    /// The file name's suffix: `fetch`, `fetch_native`, `vulkan`, `vulkan_native`, `pls_inout`...
    pub fn file_suffix(self) -> String {
        match self {
            Include::FetchPacked => "fetch".into(),
            Include::FetchNative => "fetch_native".into(),
            Include::SubpassPacked => "vulkan".into(),
            Include::SubpassNative => "vulkan_native".into(),
            Include::PixelLocalStorage(block) => format!("pls_{}", block.suffix()),
            Include::WebGlPixelLocalStorage => "webgl_pls".into(),
        }
    }

    /// The file the include is written to for the layout of `symbols`, with `extension`: the
    /// GLSL's `glsl` (`mobile_metallic.fetch.glsl`), the WebGL host module's `js`.
    pub fn file_name(self, symbols: &Symbols, extension: &str) -> String {
        symbols.file(&format!("{}.{extension}", self.file_suffix()))
    }

    /// The `#extension` names the user's shader preamble must enable (`: require`).
    pub fn shader_extensions(self) -> &'static [&'static str] {
        match self {
            Include::FetchPacked | Include::FetchNative => &["GL_EXT_shader_framebuffer_fetch"],
            Include::PixelLocalStorage(_) => &["GL_EXT_shader_pixel_local_storage"],
            Include::WebGlPixelLocalStorage => &["GL_ANGLE_shader_pixel_local_storage"],
            Include::SubpassPacked | Include::SubpassNative => &[],
        }
    }

    /// The `#version` lines the include compiles under (the user writes one of them).
    pub fn versions(self) -> &'static [&'static str] {
        match self {
            Include::FetchPacked | Include::FetchNative => &["300 es", "310 es", "320 es"],
            // The extension is written against GLSL ES 3.00; its blocks need no more.
            Include::PixelLocalStorage(_) => &["300 es", "310 es", "320 es"],
            // WebGL 2's shading language.
            Include::WebGlPixelLocalStorage => &["300 es"],
            // Vulkan GLSL: GL_KHR_vulkan_glsl needs 310 es or desktop 450.
            Include::SubpassPacked | Include::SubpassNative => &["310 es", "320 es", "450"],
        }
    }
}

/// One colour or input attachment of an include.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Attachment {
    /// The GLSL variable that declares it.
    pub name: String,
    /// Its `location` (fetch) or `input_attachment_index` and `binding` (Vulkan).
    pub index: u32,
    /// Its format in GL and Vulkan terms: a row of the format table.
    pub format: &'static TargetFormat,
}

/// The GLSL type of a subpass input over an attachment of `format`: `subpassInput`,
/// `usubpassInput` or `isubpassInput`.
pub fn subpass_input_type(format: &TargetFormat) -> &'static str {
    match format.glsl_type.as_bytes()[0] {
        b'u' => "usubpassInput",
        b'i' => "isubpassInput",
        _ => "subpassInput",
    }
}

/// What an include asks of the host and the shader around it (its attachments here, its
/// `#extension`s and `#version`s from [`Include::shader_extensions`] and [`Include::versions`]),
/// and what it declares for them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Interface {
    /// The include this interface belongs to.
    pub include: Include,
    /// The attachments, in location order. Empty for pixel local storage, which has none.
    pub attachments: Vec<Attachment>,
    /// WebGL's pixel local storage planes, in binding order (empty for the other includes).
    pub planes: Vec<Plane>,
    /// Every declaration of the include's text, in its order: the attachments, planes or
    /// block, the translated types and functions, the accessors. Empty until the include is
    /// written ([`super::include`] fills it).
    pub declares: Vec<gbuffer_translate::printer::Item>,
}

impl Interface {
    /// The interface of `include` for a compiled layout, with the GLSL names its words and
    /// fields were given.
    pub fn new(compiled: &crate::CompiledLayout, include: Include) -> Interface {
        let symbols = compiled.lowered().symbols();
        let attachments: Vec<Attachment> = match include {
            Include::PixelLocalStorage(_) | Include::WebGlPixelLocalStorage => Vec::new(),
            Include::FetchPacked | Include::SubpassPacked => (0..compiled.lowered().targets())
                .map(|target| Attachment {
                    name: symbols.target(target),
                    index: target as u32,
                    format: PackedTarget::FourWords.target(),
                })
                .collect(),
            Include::FetchNative | Include::SubpassNative => {
                let words = compiled.lowered().words();
                // Joined without `__`, which GLSL ES reserves (naga's names may end in `_`).
                let attachment_names = super::unique(
                    compiled
                        .word_names()
                        .iter()
                        .map(|name| symbols.attachment(name))
                        .collect(),
                );
                words
                    .iter()
                    .zip(attachment_names)
                    .enumerate()
                    .map(|(index, (word, name))| Attachment {
                        name,
                        index: index as u32,
                        format: word.format.target(),
                    })
                    .collect()
            }
        };
        let planes = match include {
            Include::WebGlPixelLocalStorage => super::webgl::planes(compiled),
            _ => Vec::new(),
        };
        Interface {
            include,
            attachments,
            planes,
            declares: Vec::new(),
        }
    }

    /// The extensions a GLES host needs to render to the attachments' formats (none for the
    /// Vulkan includes), each once.
    pub fn host_extensions(&self) -> Vec<&'static str> {
        if self.include.is_vulkan() {
            return Vec::new();
        }
        let mut extensions: Vec<&'static str> = self
            .attachments
            .iter()
            .filter_map(|attachment| attachment.format.gl.host_extension)
            .collect();
        extensions.sort_unstable();
        extensions.dedup();
        extensions
    }
}
