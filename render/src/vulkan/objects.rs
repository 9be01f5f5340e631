//! The Vulkan objects the plans are made of: render passes, framebuffers, descriptor sets,
//! pipeline layouts and pipelines (naga's GLSL 450 compiled by glslang).

use ash::vk;
use gbuffer_gpu::tools::glslang;
use gbuffer_gpu::vulkan::{GraphicsPipeline, Object};

use super::VulkanRenderer;
use crate::glsl::{self, Dialect};
use crate::mesh::Vertex;
use crate::shaders::SAMPLER_BINDING;

impl VulkanRenderer {
    /// A descriptor set (and its layout) of combined image samplers at `bindings`: the inputs
    /// (linear sampler) and `frame_textures` (nearest), for the fragment stage.
    pub(super) fn sampled_set(
        &self,
        bindings: &[u32],
        frame_textures: &[(u32, vk::ImageView)],
    ) -> Result<(vk::DescriptorSetLayout, vk::DescriptorSet), String> {
        let mut resources = Vec::new();
        // GLSL combines the sampler with each texture.
        for &binding in bindings
            .iter()
            .filter(|&&binding| binding != SAMPLER_BINDING)
        {
            if let Some((_, view)) = self.inputs.iter().find(|(input, _)| *input == binding) {
                resources.push((binding, *view, self.linear));
            } else if let Some((_, view)) = frame_textures
                .iter()
                .find(|(texture, _)| *texture == binding)
            {
                resources.push((binding, *view, self.nearest));
            } else {
                return Err(format!(
                    "the shader samples binding {binding}, which this renderer does not bind"
                ));
            }
        }
        self.descriptor_set(
            &resources
                .iter()
                .map(|&(binding, view, sampler)| {
                    (
                        binding,
                        vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                        view,
                        sampler,
                        vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                    )
                })
                .collect::<Vec<_>>(),
        )
    }

    /// A descriptor set (and its layout) of the input attachments `views` at bindings 0, 1...
    pub(super) fn input_attachment_set(
        &self,
        views: &[vk::ImageView],
    ) -> Result<(vk::DescriptorSetLayout, vk::DescriptorSet), String> {
        self.descriptor_set(
            &views
                .iter()
                .enumerate()
                .map(|(index, &view)| {
                    (
                        index as u32,
                        vk::DescriptorType::INPUT_ATTACHMENT,
                        view,
                        vk::Sampler::null(),
                        vk::ImageLayout::GENERAL,
                    )
                })
                .collect::<Vec<_>>(),
        )
    }

    #[allow(clippy::type_complexity)]
    pub(super) fn descriptor_set(
        &self,
        resources: &[(
            u32,
            vk::DescriptorType,
            vk::ImageView,
            vk::Sampler,
            vk::ImageLayout,
        )],
    ) -> Result<(vk::DescriptorSetLayout, vk::DescriptorSet), String> {
        let device = &self.vulkan.device;
        let bindings: Vec<vk::DescriptorSetLayoutBinding> = resources
            .iter()
            .map(|&(binding, kind, ..)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(binding)
                    .descriptor_type(kind)
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::FRAGMENT)
            })
            .collect();
        let sizes: Vec<vk::DescriptorPoolSize> = resources
            .iter()
            .map(|&(_, kind, ..)| vk::DescriptorPoolSize {
                ty: kind,
                descriptor_count: 1,
            })
            .collect();
        // SAFETY: the layout, pool and set are created, written and tracked here.
        unsafe {
            let layout = device
                .create_descriptor_set_layout(
                    &vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings),
                    None,
                )
                .map_err(|error| format!("vkCreateDescriptorSetLayout: {error}"))?;
            self.vulkan.track(Object::DescriptorSetLayout(layout));
            let mut pool_info = vk::DescriptorPoolCreateInfo::default().max_sets(1);
            if !sizes.is_empty() {
                pool_info = pool_info.pool_sizes(&sizes);
            }
            let pool = device
                .create_descriptor_pool(&pool_info, None)
                .map_err(|error| format!("vkCreateDescriptorPool: {error}"))?;
            self.vulkan.track(Object::DescriptorPool(pool));
            let layouts = [layout];
            let set = device
                .allocate_descriptor_sets(
                    &vk::DescriptorSetAllocateInfo::default()
                        .descriptor_pool(pool)
                        .set_layouts(&layouts),
                )
                .map_err(|error| format!("vkAllocateDescriptorSets: {error}"))?[0];
            let images: Vec<[vk::DescriptorImageInfo; 1]> = resources
                .iter()
                .map(|&(_, _, view, sampler, layout)| {
                    [vk::DescriptorImageInfo {
                        sampler,
                        image_view: view,
                        image_layout: layout,
                    }]
                })
                .collect();
            let writes: Vec<vk::WriteDescriptorSet> = resources
                .iter()
                .zip(&images)
                .map(|(&(binding, kind, ..), image)| {
                    vk::WriteDescriptorSet::default()
                        .dst_set(set)
                        .dst_binding(binding)
                        .descriptor_type(kind)
                        .image_info(image)
                })
                .collect();
            device.update_descriptor_sets(&writes, &[]);
            Ok((layout, set))
        }
    }

    /// A pipeline: `vertex` of the WGSL translated and `fragment` (GLSL 450), compiled by
    /// glslang, with the vertex input its vertex stage takes, a depth test, and colour writes
    /// to the attachments `writes` marks.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn pipeline(
        &self,
        wgsl: &str,
        vertex: &str,
        fragment: &str,
        render_pass: vk::RenderPass,
        layout: vk::PipelineLayout,
        (depth, writes): (Depth, &[bool]),
        (width, height): (u32, u32),
    ) -> Result<vk::Pipeline, String> {
        let vertex_glsl =
            glsl::translate(wgsl, naga::ShaderStage::Vertex, vertex, Dialect::Vulkan)?;
        let vertex_module =
            self.vulkan
                .shader_module(&glslang(&vertex_glsl.text, "vert", true)?)?;
        let fragment_module = self
            .vulkan
            .shader_module(&glslang(fragment, "frag", true)?)?;
        let (bindings, attributes): (Vec<_>, Vec<_>) = match vertex {
            "geometry_vertex" => (
                vec![vk::VertexInputBindingDescription {
                    binding: 0,
                    stride: std::mem::size_of::<Vertex>() as u32,
                    input_rate: vk::VertexInputRate::VERTEX,
                }],
                vec![
                    vk::VertexInputAttributeDescription {
                        location: 0,
                        binding: 0,
                        format: vk::Format::R32G32B32_SFLOAT,
                        offset: 0,
                    },
                    vk::VertexInputAttributeDescription {
                        location: 1,
                        binding: 0,
                        format: vk::Format::R32G32B32_SFLOAT,
                        offset: 12,
                    },
                    vk::VertexInputAttributeDescription {
                        location: 2,
                        binding: 0,
                        format: vk::Format::R32_UINT,
                        offset: 24,
                    },
                ],
            ),
            "volume_vertex" => (
                vec![vk::VertexInputBindingDescription {
                    binding: 0,
                    stride: 4,
                    input_rate: vk::VertexInputRate::INSTANCE,
                }],
                vec![vk::VertexInputAttributeDescription {
                    location: 0,
                    binding: 0,
                    format: vk::Format::R32_UINT,
                    offset: 0,
                }],
            ),
            _ => (Vec::new(), Vec::new()),
        };
        let depth = match depth {
            Depth::None => None,
            Depth::Write => Some((true, vk::CompareOp::LESS)),
            Depth::Surfaces => Some((false, vk::CompareOp::GREATER)),
            Depth::Sky => Some((false, vk::CompareOp::EQUAL)),
        };
        self.vulkan.graphics_pipeline(&GraphicsPipeline {
            render_pass,
            subpass: 0,
            layout,
            shaders: (vertex_module, fragment_module),
            vertex_input: (&bindings, &attributes),
            depth,
            colour_writes: writes,
            size: (width, height),
        })
    }
}

/// How a pipeline tests depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Depth {
    /// No depth attachment.
    None,
    /// The mesh: LESS, written.
    Write,
    /// Fullscreen and volume draws over the surfaces: GREATER than their depth.
    Surfaces,
    /// The sky: EQUAL to the cleared far plane.
    Sky,
}
