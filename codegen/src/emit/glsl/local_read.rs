//! What a Vulkan host sets to use a Vulkan include (`<snake>.vulkan.glsl`,
//! `.vulkan_native.glsl`) in one dynamic rendering, without render pass objects: Vulkan 1.3's
//! dynamic rendering with `VK_KHR_dynamic_rendering_local_read` (core in Vulkan 1.4), under
//! which the same `subpassInput` GLSL reads the attachments the earlier draws of the same
//! rendering wrote. Written beside the include as `<snake>.vulkan.local_read.json` (and
//! `.vulkan_native.local_read.json`), as the WebGL include ships its host module: data any
//! host reads, each Vulkan enumerant by its name and value.
//!
//! The host must (the extension's proposal, "Mapping to Subpasses"):
//!
//! - enable the `dynamicRendering` and `dynamicRenderingLocalRead` features;
//! - create the attachments with `COLOR_ATTACHMENT | INPUT_ATTACHMENT` usage (and
//!   `TRANSIENT_ATTACHMENT` on a tiler, so that they never reach memory), give them to
//!   `vkCmdBeginRendering` as colour attachments in `VK_IMAGE_LAYOUT_RENDERING_LOCAL_READ_KHR`,
//!   cleared and not stored, and bind them as `INPUT_ATTACHMENT` descriptors in that layout at
//!   the include's set and bindings;
//! - map each colour attachment to the fragment output `location` the G-buffer draw writes it
//!   at and to the `input_attachment_index` the include reads it at:
//!   `VkRenderingAttachmentLocationInfoKHR` and `VkRenderingInputAttachmentIndexInfoKHR`,
//!   chained to every pipeline's create info and set with
//!   `vkCmdSetRenderingAttachmentLocationsKHR` and
//!   `vkCmdSetRenderingInputAttachmentIndicesKHR` after `vkCmdBeginRendering` (a colour
//!   attachment no shader reads, such as the lit output, gets `VK_ATTACHMENT_UNUSED`);
//! - record, before each draw that reads what earlier draws wrote, a `BY_REGION` pipeline
//!   barrier from colour attachment writes to input attachment reads, or, where the device
//!   offers `rasterizationOrderColorAttachmentAccess`
//!   (`VK_EXT_rasterization_order_attachment_access`, or ARM's extension it was promoted
//!   from), create the pipelines with
//!   `VK_PIPELINE_COLOR_BLEND_STATE_CREATE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_BIT_EXT` and
//!   record no barrier between the draws. The shaders are the same in both: SPIR-V has no
//!   declaration for rasterization order, the pipeline carries it.
//!
//! The renderer's local-read paths (`gbuffer_render::vulkan`) take their mapping from
//! [`LocalRead::of`], and their tests hold the enumerants here to `ash`'s.

use std::fmt::Write as _;

use super::{Include, Interface};
use crate::CompiledLayout;
use gbuffer_core::Symbols;
use gbuffer_files::json::string;

/// A Vulkan enumerant or flag: its name in the C API and its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Enumerant {
    /// The C name, e.g. `VK_IMAGE_LAYOUT_RENDERING_LOCAL_READ_KHR`.
    pub name: &'static str,
    /// Its value.
    pub value: u32,
}

/// The layout of the attachments while the draws write and read them.
pub const IMAGE_LAYOUT: Enumerant = Enumerant {
    name: "VK_IMAGE_LAYOUT_RENDERING_LOCAL_READ_KHR",
    value: 1_000_232_000,
};

/// The descriptor type the include's subpass inputs are bound as.
pub const DESCRIPTOR_TYPE: Enumerant = Enumerant {
    name: "VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT",
    value: 10,
};

/// The value of a colour attachment no shader reads as an input attachment.
pub const ATTACHMENT_UNUSED: u32 = u32::MAX;

/// The barrier before a draw that reads what earlier draws wrote: (source stage, source
/// access, destination stage, destination access, dependency flags).
pub const BARRIER: [Enumerant; 5] = [
    Enumerant {
        name: "VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT",
        value: 0x400,
    },
    Enumerant {
        name: "VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT",
        value: 0x100,
    },
    Enumerant {
        name: "VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT",
        value: 0x80,
    },
    Enumerant {
        name: "VK_ACCESS_INPUT_ATTACHMENT_READ_BIT",
        value: 0x10,
    },
    Enumerant {
        name: "VK_DEPENDENCY_BY_REGION_BIT",
        value: 0x1,
    },
];

/// The colour blend state's flag under which the draws need no barrier.
pub const RASTERIZATION_ORDER_FLAG: Enumerant = Enumerant {
    name: "VK_PIPELINE_COLOR_BLEND_STATE_CREATE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_BIT_EXT",
    value: 0x1,
};

/// One attachment of the include, as the host maps it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LocalReadAttachment {
    /// The include's subpass input that reads it.
    pub name: String,
    /// Its Vulkan format.
    pub format: Enumerant,
    /// Its place in `VkRenderingInfo::pColorAttachments` and its fragment output `location`
    /// (the G-buffer draw writes it there).
    pub location: u32,
    /// Its `input_attachment_index` in the include.
    pub input_attachment_index: u32,
    /// Its descriptor's binding in the include's set.
    pub binding: u32,
}

/// What the host sets for one Vulkan include under dynamic rendering local read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LocalRead {
    /// The include's file name.
    pub include: String,
    /// The descriptor set its subpass inputs are declared in.
    pub set: u32,
    /// The G-buffer's attachments, in location order; a host puts its own colour attachments
    /// (the lit output) after them, with `ATTACHMENT_UNUSED` as their input index.
    pub attachments: Vec<LocalReadAttachment>,
}

impl LocalRead {
    /// The host's mapping for a Vulkan include's `interface`, declared in descriptor set `set`;
    /// `None` for the other includes.
    pub fn of(compiled: &CompiledLayout, interface: &Interface, set: u32) -> Option<LocalRead> {
        if !interface.include.is_vulkan() {
            return None;
        }
        Some(LocalRead {
            include: interface
                .include
                .file_name(compiled.lowered().symbols(), "glsl"),
            set,
            attachments: interface
                .attachments
                .iter()
                .map(|attachment| LocalReadAttachment {
                    name: attachment.name.clone(),
                    format: Enumerant {
                        name: attachment.format.vulkan.name,
                        value: attachment.format.vulkan.format as u32,
                    },
                    // The include's attachment `index` is both: its input attachment index and
                    // binding, and the location the G-buffer draw writes it at.
                    location: attachment.index,
                    input_attachment_index: attachment.index,
                    binding: attachment.index,
                })
                .collect(),
        })
    }

    /// The file the host data is written to: `<snake>.vulkan.local_read.json` or
    /// `<snake>.vulkan_native.local_read.json`.
    pub fn file_name(symbols: &Symbols, include: Include) -> String {
        include.file_name(symbols, "local_read.json")
    }

    /// The JSON document, with a trailing newline.
    pub fn to_json(&self) -> String {
        let enumerant =
            |e: &Enumerant| format!("{{ \"name\": {}, \"value\": {} }}", string(e.name), e.value);
        let mut out = String::from("{\n");
        let _ = writeln!(
            out,
            "  \"about\": {},",
            string(&format!(
                "What a Vulkan host sets to read the G-buffer of {} in one dynamic rendering \
                 (VK_KHR_dynamic_rendering_local_read). Generated by gbuffer's codegen: edit \
                 the layout, not this file.",
                self.include
            ))
        );
        let _ = writeln!(out, "  \"include\": {},", string(&self.include));
        let _ = writeln!(
            out,
            "  \"extensions\": [{}],",
            string("VK_KHR_dynamic_rendering_local_read")
        );
        let _ = writeln!(
            out,
            "  \"features\": [{}, {}],",
            string("dynamicRendering"),
            string("dynamicRenderingLocalRead")
        );
        let _ = writeln!(out, "  \"image_layout\": {},", enumerant(&IMAGE_LAYOUT));
        let _ = writeln!(
            out,
            "  \"descriptor_type\": {},",
            enumerant(&DESCRIPTOR_TYPE)
        );
        let _ = writeln!(out, "  \"descriptor_set\": {},", self.set);
        let _ = writeln!(out, "  \"attachment_unused\": {ATTACHMENT_UNUSED},");
        out.push_str("  \"colour_attachments\": [\n");
        for (index, attachment) in self.attachments.iter().enumerate() {
            let _ = write!(
                out,
                "    {{ \"name\": {}, \"format\": {}, \"location\": {}, \
                 \"input_attachment_index\": {}, \"binding\": {} }}",
                string(&attachment.name),
                enumerant(&attachment.format),
                attachment.location,
                attachment.input_attachment_index,
                attachment.binding
            );
            out.push_str(if index + 1 < self.attachments.len() {
                ",\n"
            } else {
                "\n"
            });
        }
        out.push_str("  ],\n");
        let [src_stage, src_access, dst_stage, dst_access, dependency] = &BARRIER;
        let _ = writeln!(
            out,
            "  \"barrier_between_draws\": {{ \"src_stage_mask\": {}, \"src_access_mask\": {}, \
             \"dst_stage_mask\": {}, \"dst_access_mask\": {}, \"dependency_flags\": {} }},",
            enumerant(src_stage),
            enumerant(src_access),
            enumerant(dst_stage),
            enumerant(dst_access),
            enumerant(dependency)
        );
        let _ = writeln!(
            out,
            "  \"rasterization_order\": {{ \"extensions\": [{}, {}], \"feature\": {}, \
             \"pipeline_color_blend_flags\": {}, \"barrier_between_draws\": null }}",
            string("VK_EXT_rasterization_order_attachment_access"),
            string("VK_ARM_rasterization_order_attachment_access"),
            string("rasterizationOrderColorAttachmentAccess"),
            enumerant(&RASTERIZATION_ORDER_FLAG)
        );
        out.push_str("}\n");
        out
    }
}
