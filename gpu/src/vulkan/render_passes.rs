//! Render passes of subpasses over attachments, and their framebuffers.

use ash::vk;
use ash::Device;

use super::barriers::FEEDBACK;
use super::Vulkan;

/// One subpass of a render pass: the attachments it reads as input attachments and those it
/// writes as colour attachments, as indices into the render pass's attachments.
pub struct Subpass {
    /// Attachments read as input attachments, in input attachment index order.
    pub inputs: Vec<u32>,
    /// Attachments written as colour attachments, in location order.
    pub colours: Vec<u32>,
}

impl Vulkan {
    /// A render pass over `formats` whose subpasses run in order, each reading its inputs
    /// after the previous ones wrote them (by region, as a tiler keeps them). No attachment is
    /// loaded or stored: they live and die inside the pass.
    pub fn render_pass(
        &self,
        formats: &[vk::Format],
        subpasses: &[Subpass],
    ) -> Result<vk::RenderPass, String> {
        let attachments: Vec<vk::AttachmentDescription> = formats
            .iter()
            .map(|&format| {
                vk::AttachmentDescription::default()
                    .format(format)
                    .samples(vk::SampleCountFlags::TYPE_1)
                    .load_op(vk::AttachmentLoadOp::DONT_CARE)
                    .store_op(vk::AttachmentStoreOp::DONT_CARE)
                    .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
                    .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
                    .initial_layout(vk::ImageLayout::UNDEFINED)
                    .final_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)
            })
            .collect();
        let references = |indices: &[u32], layout| -> Vec<vk::AttachmentReference> {
            indices
                .iter()
                .map(|&attachment| vk::AttachmentReference { attachment, layout })
                .collect()
        };
        let inputs: Vec<_> = subpasses
            .iter()
            .map(|subpass| references(&subpass.inputs, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL))
            .collect();
        let colours: Vec<_> = subpasses
            .iter()
            .map(|subpass| references(&subpass.colours, vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL))
            .collect();
        let descriptions: Vec<vk::SubpassDescription> = inputs
            .iter()
            .zip(&colours)
            .map(|(inputs, colours)| {
                vk::SubpassDescription::default()
                    .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
                    .input_attachments(inputs)
                    .color_attachments(colours)
            })
            .collect();
        let dependencies: Vec<vk::SubpassDependency> = (1..subpasses.len() as u32)
            .map(|next| {
                vk::SubpassDependency::default()
                    .src_subpass(next - 1)
                    .dst_subpass(next)
                    .src_stage_mask(FEEDBACK.0 .1)
                    .dst_stage_mask(FEEDBACK.1 .1)
                    .src_access_mask(FEEDBACK.0 .0)
                    .dst_access_mask(FEEDBACK.1 .0)
                    .dependency_flags(vk::DependencyFlags::BY_REGION)
            })
            .collect();
        self.render_pass_of(&attachments, &descriptions, &dependencies)
    }

    /// A render pass of these attachments, subpasses and dependencies, as they are written.
    pub fn render_pass_of(
        &self,
        attachments: &[vk::AttachmentDescription],
        subpasses: &[vk::SubpassDescription],
        dependencies: &[vk::SubpassDependency],
    ) -> Result<vk::RenderPass, String> {
        let info = vk::RenderPassCreateInfo::default()
            .attachments(attachments)
            .subpasses(subpasses)
            .dependencies(dependencies);
        // SAFETY: the caller's descriptions reference only `attachments`.
        let made = unsafe { self.device.create_render_pass(&info, None) };
        self.created("vkCreateRenderPass", made, Device::destroy_render_pass)
    }

    /// A framebuffer of `views` for `render_pass`.
    pub fn framebuffer(
        &self,
        render_pass: vk::RenderPass,
        views: &[vk::ImageView],
        width: u32,
        height: u32,
    ) -> Result<vk::Framebuffer, String> {
        let info = vk::FramebufferCreateInfo::default()
            .render_pass(render_pass)
            .attachments(views)
            .width(width)
            .height(height)
            .layers(1);
        // SAFETY: the views match the render pass's attachments.
        let made = unsafe { self.device.create_framebuffer(&info, None) };
        self.created("vkCreateFramebuffer", made, Device::destroy_framebuffer)
    }
}
