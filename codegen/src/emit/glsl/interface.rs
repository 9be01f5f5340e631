//! What host code needs to know about an include, as data: the attachments it declares (with
//! their GL internal format and Vulkan format), the extensions its shader and its host need,
//! and the lowest GLSL ES version it compiles under. Host code reads these instead of
//! repeating them, and each include's header comment says the same.

use crate::format::Format;
use crate::layout::Layout;

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
}

impl Include {
    /// Every include, in the order the codegen writes them.
    pub const ALL: [Include; 7] = [
        Include::PixelLocalStorage(super::PlsBlock::InOut),
        Include::PixelLocalStorage(super::PlsBlock::In),
        Include::PixelLocalStorage(super::PlsBlock::Out),
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
        }
    }

    /// The `#extension` names the user's shader preamble must enable (`: require`).
    pub fn shader_extensions(self) -> &'static [&'static str] {
        match self {
            Include::FetchPacked | Include::FetchNative => &["GL_EXT_shader_framebuffer_fetch"],
            Include::PixelLocalStorage(_) => &["GL_EXT_shader_pixel_local_storage"],
            Include::SubpassPacked | Include::SubpassNative => &[],
        }
    }

    /// The `#version` lines the include compiles under (the user writes one of them).
    pub fn versions(self) -> &'static [&'static str] {
        match self {
            Include::FetchPacked | Include::FetchNative => &["300 es", "310 es", "320 es"],
            // The extension is written against GLSL ES 3.00; its blocks need no more.
            Include::PixelLocalStorage(_) => &["300 es", "310 es", "320 es"],
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
    /// Its format in GL and Vulkan terms.
    pub format: AttachmentFormat,
}

/// The format of an attachment in both APIs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AttachmentFormat {
    /// GL's sized internal format, e.g. `0x8059` (`GL_RGB10_A2`).
    pub gl_internal_format: u32,
    /// Its name, e.g. `GL_RGB10_A2`.
    pub gl_name: &'static str,
    /// The `VkFormat` value, e.g. `64` (`VK_FORMAT_A2B10G10R10_UNORM_PACK32`).
    pub vulkan_format: i32,
    /// Its name, e.g. `VK_FORMAT_A2B10G10R10_UNORM_PACK32`.
    pub vulkan_name: &'static str,
    /// The GLSL type the include declares it with: `vec4`, `uvec4` or `ivec4`, whatever the
    /// format's channel count (fetch and `subpassLoad` read four components; channels the
    /// format lacks read as 0, alpha as 1, and are dropped on write).
    pub glsl_type: &'static str,
    /// The extension a GLES 3.2 host needs to render to it, if any (`GL_EXT_texture_norm16`
    /// for the 16-bit unorm formats; the float formats are renderable in core GLES 3.2).
    pub gl_host_extension: Option<&'static str>,
}

impl AttachmentFormat {
    /// `RGBA32UI`: four packed words.
    pub const PACKED: AttachmentFormat = AttachmentFormat {
        gl_internal_format: 0x8D70,
        gl_name: "GL_RGBA32UI",
        vulkan_format: 107,
        vulkan_name: "VK_FORMAT_R32G32B32A32_UINT",
        glsl_type: "uvec4",
        gl_host_extension: None,
    };

    /// The attachment format that stores a pixel local storage format's channels in the same
    /// bits, so the driver's conversions are the extension's.
    pub const fn native(format: Format) -> AttachmentFormat {
        const fn of(
            gl_internal_format: u32,
            gl_name: &'static str,
            vulkan_format: i32,
            vulkan_name: &'static str,
            glsl_type: &'static str,
        ) -> AttachmentFormat {
            AttachmentFormat {
                gl_internal_format,
                gl_name,
                vulkan_format,
                vulkan_name,
                glsl_type,
                gl_host_extension: None,
            }
        }
        match format {
            Format::R11fG11fB10f => of(
                0x8C3A,
                "GL_R11F_G11F_B10F",
                122,
                "VK_FORMAT_B10G11R11_UFLOAT_PACK32",
                "vec4",
            ),
            Format::R32f => of(0x822E, "GL_R32F", 100, "VK_FORMAT_R32_SFLOAT", "vec4"),
            Format::Rg16f => of(0x822F, "GL_RG16F", 83, "VK_FORMAT_R16G16_SFLOAT", "vec4"),
            Format::Rgb10A2 => of(
                0x8059,
                "GL_RGB10_A2",
                64,
                "VK_FORMAT_A2B10G10R10_UNORM_PACK32",
                "vec4",
            ),
            Format::Rgba8 => of(0x8058, "GL_RGBA8", 37, "VK_FORMAT_R8G8B8A8_UNORM", "vec4"),
            Format::Rg16 => AttachmentFormat {
                gl_host_extension: Some("GL_EXT_texture_norm16"),
                ..of(0x822C, "GL_RG16_EXT", 77, "VK_FORMAT_R16G16_UNORM", "vec4")
            },
            Format::Rgba8i => of(0x8D8E, "GL_RGBA8I", 42, "VK_FORMAT_R8G8B8A8_SINT", "ivec4"),
            Format::Rg16i => of(0x8239, "GL_RG16I", 82, "VK_FORMAT_R16G16_SINT", "ivec4"),
            Format::Rgb10A2ui => of(
                0x906F,
                "GL_RGB10_A2UI",
                68,
                "VK_FORMAT_A2B10G10R10_UINT_PACK32",
                "uvec4",
            ),
            Format::Rgba8ui => of(0x8D7C, "GL_RGBA8UI", 41, "VK_FORMAT_R8G8B8A8_UINT", "uvec4"),
            Format::Rg16ui => of(0x823A, "GL_RG16UI", 81, "VK_FORMAT_R16G16_UINT", "uvec4"),
            Format::R32ui => of(0x8236, "GL_R32UI", 98, "VK_FORMAT_R32_UINT", "uvec4"),
        }
    }

    /// The GLSL type of a subpass input over this attachment: `subpassInput`, `usubpassInput`
    /// or `isubpassInput`.
    pub fn subpass_input_type(self) -> &'static str {
        match self.glsl_type.as_bytes()[0] {
            b'u' => "usubpassInput",
            b'i' => "isubpassInput",
            _ => "subpassInput",
        }
    }
}

/// What an include asks of the host and the shader around it: its attachments here, its
/// `#extension`s and `#version`s from [`Include::shader_extensions`] and [`Include::versions`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Interface {
    /// The include this interface belongs to.
    pub include: Include,
    /// The attachments, in location order. Empty for pixel local storage, which has none.
    pub attachments: Vec<Attachment>,
}

impl Interface {
    /// The interface of `include` for a checked layout, with the GLSL names naga gives its
    /// fields.
    pub fn new(layout: &Layout, include: Include, names: &super::GlslNames) -> Interface {
        let prefix = layout.snake_name();
        let attachments: Vec<Attachment> = match include {
            Include::PixelLocalStorage(_) => Vec::new(),
            Include::FetchPacked | Include::SubpassPacked => (0..layout.targets())
                .map(|target| Attachment {
                    name: format!("{prefix}_target{target}"),
                    index: target as u32,
                    format: AttachmentFormat::PACKED,
                })
                .collect(),
            Include::FetchNative | Include::SubpassNative => layout
                .word_contents()
                .iter()
                .enumerate()
                .map(|(index, word)| Attachment {
                    name: format!("{prefix}_{}_attachment", super::word_name(word, names)),
                    index: index as u32,
                    format: AttachmentFormat::native(word.format),
                })
                .collect(),
        };
        Interface {
            include,
            attachments,
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
            .filter_map(|attachment| attachment.format.gl_host_extension)
            .collect();
        extensions.sort_unstable();
        extensions.dedup();
        extensions
    }
}
