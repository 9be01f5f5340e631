//! The Vulkan objects the plans are made of: render passes, framebuffers, descriptor sets,
//! pipeline layouts and pipelines (vertex stages as naga's SPIR-V, fragment stages as naga's or
//! hand-written GLSL 450 compiled by glslang).

use ash::vk;
use gbuffer_gpu::tools::glslang;
use gbuffer_gpu::vulkan::{DrawsIn, GraphicsPipeline, Resource};

use super::VulkanRenderer;
use crate::glsl::{self, Dialect};
use crate::mesh::Vertex;
use crate::shaders::{
    used_bindings, CLAMPED_SAMPLER_BINDING, ENVIRONMENT_BINDING, ENVIRONMENT_SAMPLER_BINDING,
};

impl VulkanRenderer {
    /// A descriptor set (and its layout) of combined image samplers at `bindings`: the inputs
    /// (trilinear: the environment's wrapping in u, the others' clamped) and `frame_textures`
    /// (nearest), for the fragment stage.
    pub(super) fn sampled_set(
        &self,
        bindings: &[u32],
        frame_textures: &[(u32, vk::ImageView)],
    ) -> Result<(vk::DescriptorSetLayout, vk::DescriptorSet), String> {
        let mut resources = Vec::new();
        for binding in combined_image_bindings(bindings) {
            if let Some((_, view)) = self.inputs.iter().find(|(input, _)| *input == binding) {
                let sampler = if binding == ENVIRONMENT_BINDING {
                    self.environment_sampler
                } else {
                    self.clamped_sampler
                };
                resources.push((binding, *view, sampler));
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
        let resources: Vec<(u32, Resource)> = resources
            .iter()
            .map(|&(binding, view, sampler)| (binding, Resource::SampledImage(view, sampler)))
            .collect();
        self.descriptor_set(&resources)
    }

    /// A descriptor set (and its layout) of the input attachments `views` at bindings 0, 1...,
    /// each also written by the draws that read it, in `layout` (`GENERAL` in a subpass,
    /// `RENDERING_LOCAL_READ_KHR` in a dynamic rendering).
    pub(super) fn input_attachment_set(
        &self,
        views: &[vk::ImageView],
        layout: vk::ImageLayout,
    ) -> Result<(vk::DescriptorSetLayout, vk::DescriptorSet), String> {
        let resources: Vec<(u32, Resource)> = (0..)
            .zip(
                views
                    .iter()
                    .map(|&view| Resource::FeedbackAttachment(view, layout)),
            )
            .collect();
        self.descriptor_set(&resources)
    }

    /// A descriptor set and its layout holding `resources` at their bindings.
    fn descriptor_set(
        &self,
        resources: &[(u32, Resource)],
    ) -> Result<(vk::DescriptorSetLayout, vk::DescriptorSet), String> {
        let types: Vec<(u32, vk::DescriptorType)> = resources
            .iter()
            .map(|(binding, resource)| (*binding, resource.descriptor_type()))
            .collect();
        let layout = self.vulkan.descriptor_set_layout_at(&types)?;
        Ok((layout, self.vulkan.descriptor_set_at(layout, resources)?))
    }

    /// A pass's pipeline over sampled resources: the WGSL's `fragment` entry point translated,
    /// the descriptor set of what it samples (the inputs, and `frame_textures` at their
    /// bindings) and its pipeline layout; the pipeline, the layout and the set.
    pub(super) fn sampling_pipeline(
        &self,
        wgsl: &str,
        (vertex, fragment): (&str, &str),
        frame_textures: &[(u32, vk::ImageView)],
        draws_in: DrawsIn<'_>,
        writes: (Depth, &[bool]),
        size: (u32, u32),
    ) -> Result<(vk::Pipeline, vk::PipelineLayout, vk::DescriptorSet), String> {
        let bindings = used_bindings(wgsl, fragment);
        let (set_layout, set) = self.sampled_set(&bindings, frame_textures)?;
        let layout = self.vulkan.pipeline_layout(&[set_layout], None)?;
        let glsl = glsl::write_stage(wgsl, naga::ShaderStage::Fragment, fragment, Dialect::Vulkan)?;
        let pipeline = self.pipeline(wgsl, vertex, &glsl.text, draws_in, layout, writes, size)?;
        Ok((pipeline, layout, set))
    }

    /// A pipeline: `vertex` of the WGSL as naga's SPIR-V and `fragment` (GLSL 450) compiled
    /// by glslang, with the vertex input its vertex stage takes, a depth test, and colour writes
    /// to the attachments `writes` marks.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn pipeline(
        &self,
        wgsl: &str,
        vertex: &str,
        fragment: &str,
        draws_in: DrawsIn<'_>,
        layout: vk::PipelineLayout,
        writes: (Depth, &[bool]),
        size: (u32, u32),
    ) -> Result<vk::Pipeline, String> {
        let shaders = (
            vertex_spirv(wgsl, vertex)?,
            glslang(fragment, "frag", true)?,
        );
        self.pipeline_of_spirv(vertex, shaders, draws_in, layout, writes, size)
    }

    /// A pipeline of compiled shaders: `vertex` names the vertex stage's entry point (its
    /// SPIR-V the first of `spirv`), whose [`vertex_input`] it takes.
    pub(super) fn pipeline_of_spirv(
        &self,
        vertex: &str,
        (vertex_spirv, fragment_spirv): (Vec<u8>, Vec<u8>),
        draws_in: DrawsIn<'_>,
        layout: vk::PipelineLayout,
        (depth, writes): (Depth, &[bool]),
        (width, height): (u32, u32),
    ) -> Result<vk::Pipeline, String> {
        let vertex_module = self.vulkan.shader_module(&vertex_spirv)?;
        let vertex_entry = std::ffi::CString::new(vertex)
            .map_err(|_| format!("`{vertex}` is no entry point name"))?;
        let fragment_module = self.vulkan.shader_module(&fragment_spirv)?;
        let (bindings, attributes) = vertex_input(vertex);
        let depth = match depth {
            Depth::None => None,
            Depth::Write => Some((true, vk::CompareOp::LESS)),
            Depth::Surfaces => Some((false, vk::CompareOp::GREATER)),
            Depth::Sky => Some((false, vk::CompareOp::EQUAL)),
        };
        self.vulkan.graphics_pipeline(&GraphicsPipeline {
            draws_in,
            layout,
            shaders: (vertex_module, fragment_module),
            vertex_entry: &vertex_entry,
            vertex_input: (&bindings, &attributes),
            depth,
            colour_writes: writes,
            size: (width, height),
        })
    }
}

/// The bindings of `bindings` that are combined image samplers in Vulkan's GLSL: GLSL combines
/// each texture with its sampler, so the samplers' own bindings are not bound.
pub(super) fn combined_image_bindings(bindings: &[u32]) -> Vec<u32> {
    let samplers = [ENVIRONMENT_SAMPLER_BINDING, CLAMPED_SAMPLER_BINDING];
    (bindings.iter().copied())
        .filter(|binding| !samplers.contains(binding))
        .collect()
}

/// The vertex input of the renderer's vertex entry point `vertex`: the mesh's interleaved
/// vertices (position, normal, material), a volume's index per instance, or nothing (the
/// fullscreen triangle).
pub(super) fn vertex_input(
    vertex: &str,
) -> (
    Vec<vk::VertexInputBindingDescription>,
    Vec<vk::VertexInputAttributeDescription>,
) {
    let attribute = |location, format, offset| vk::VertexInputAttributeDescription {
        location,
        binding: 0,
        format,
        offset,
    };
    match vertex {
        "geometry_vertex" => (
            vec![vk::VertexInputBindingDescription {
                binding: 0,
                stride: std::mem::size_of::<Vertex>() as u32,
                input_rate: vk::VertexInputRate::VERTEX,
            }],
            vec![
                attribute(0, vk::Format::R32G32B32_SFLOAT, 0),
                attribute(1, vk::Format::R32G32B32_SFLOAT, 12),
                attribute(2, vk::Format::R32_UINT, 24),
            ],
        ),
        "volume_vertex" => (
            vec![vk::VertexInputBindingDescription {
                binding: 0,
                stride: 4,
                input_rate: vk::VertexInputRate::INSTANCE,
            }],
            vec![attribute(0, vk::Format::R32_UINT, 0)],
        ),
        _ => (Vec::new(), Vec::new()),
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

/// Vertex stage `entry` of the WGSL as naga's SPIR-V, clip space as the WGSL writes it (no
/// coordinate adjustment, as the GLSL translations): the vertex and instance indices are
/// SPIR-V's builtins, which GLSL would name differently for Vulkan than naga's GL names.
pub(super) fn vertex_spirv(wgsl: &str, entry: &str) -> Result<Vec<u8>, String> {
    use naga::back::spv;
    let (module, info) = glsl::module(wgsl)?;
    let options = spv::Options {
        flags: spv::WriterFlags::LABEL_VARYINGS,
        // As the GLSL translations: loops run as written.
        force_loop_bounding: false,
        ..spv::Options::default()
    };
    let pipeline = spv::PipelineOptions {
        shader_stage: naga::ShaderStage::Vertex,
        entry_point: entry.to_string(),
    };
    let words = spv::write_vec(&module, &info, &options, Some(&pipeline))
        .map_err(|error| format!("naga cannot write `{entry}` as SPIR-V: {error}"))?;
    Ok(words.iter().flat_map(|word| word.to_le_bytes()).collect())
}
