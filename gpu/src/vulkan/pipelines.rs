//! Shader modules, pipeline layouts and graphics pipelines.

use ash::vk;
use ash::Device;

use super::Vulkan;

/// Where a pipeline draws.
#[derive(Clone, Copy)]
pub enum DrawsIn<'a> {
    /// A subpass (its index) of a render pass object.
    Subpass(vk::RenderPass, u32),
    /// A dynamic rendering over these attachments, without a render pass object.
    Rendering(&'a RenderingAttachments),
}

/// The attachments of a dynamic rendering, as a pipeline that draws in it must know them, and
/// how its shaders address them: what `VkPipelineRenderingCreateInfo`,
/// `VkRenderingAttachmentLocationInfoKHR` and `VkRenderingInputAttachmentIndexInfoKHR` say
/// at pipeline creation, and the host sets again while drawing
/// (`vkCmdSetRenderingAttachmentLocationsKHR`, `vkCmdSetRenderingInputAttachmentIndicesKHR`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RenderingAttachments {
    /// The colour attachments' formats, in `VkRenderingInfo::pColorAttachments` order.
    pub colour_formats: Vec<vk::Format>,
    /// The depth attachment's format.
    pub depth_format: vk::Format,
    /// Each colour attachment's fragment output `location`.
    pub locations: Vec<u32>,
    /// Each colour attachment's `input_attachment_index`, or `vk::ATTACHMENT_UNUSED` for one
    /// no shader reads.
    pub input_indices: Vec<u32>,
    /// Whether pipelines read the attachments in rasterization order
    /// (`RASTERIZATION_ORDER_ATTACHMENT_ACCESS_EXT`): draws that read what earlier draws wrote
    /// need no barrier between them.
    pub rasterization_order: bool,
}

/// What a graphics pipeline is made of, for [`Vulkan::graphics_pipeline`].
pub struct GraphicsPipeline<'a> {
    /// Where it draws.
    pub draws_in: DrawsIn<'a>,
    /// Its layout.
    pub layout: vk::PipelineLayout,
    /// The vertex and fragment modules.
    pub shaders: (vk::ShaderModule, vk::ShaderModule),
    /// The vertex module's entry point: `main` in glslang's SPIR-V, the WGSL function's name
    /// in naga's (the fragment module's is `main`).
    pub vertex_entry: &'a std::ffi::CStr,
    /// The vertex buffers' bindings and attributes (none for a fullscreen triangle).
    pub vertex_input: (
        &'a [vk::VertexInputBindingDescription],
        &'a [vk::VertexInputAttributeDescription],
    ),
    /// The depth test, if the render pass has a depth attachment: whether it writes, and its
    /// comparison.
    pub depth: Option<(bool, vk::CompareOp)>,
    /// Per colour attachment, whether the pipeline writes it.
    pub colour_writes: &'a [bool],
    /// The viewport's width and height.
    pub size: (u32, u32),
}

impl Vulkan {
    /// A shader module from SPIR-V bytes.
    pub fn shader_module(&self, spirv: &[u8]) -> Result<vk::ShaderModule, String> {
        let code = ash::util::read_spv(&mut std::io::Cursor::new(spirv))
            .map_err(|error| format!("not SPIR-V: {error}"))?;
        // SAFETY: the code is whole SPIR-V words.
        let module = unsafe {
            self.device
                .create_shader_module(&vk::ShaderModuleCreateInfo::default().code(&code), None)
        };
        self.created(
            "vkCreateShaderModule",
            module,
            Device::destroy_shader_module,
        )
    }

    /// A pipeline layout of `set_layouts` (set i is `set_layouts[i]`) and, where given, a
    /// push-constant range of that many bytes for the fragment stage.
    pub fn pipeline_layout(
        &self,
        set_layouts: &[vk::DescriptorSetLayout],
        fragment_push_constant_bytes: Option<u32>,
    ) -> Result<vk::PipelineLayout, String> {
        let ranges: Vec<vk::PushConstantRange> = fragment_push_constant_bytes
            .into_iter()
            .map(|size| vk::PushConstantRange {
                stage_flags: vk::ShaderStageFlags::FRAGMENT,
                offset: 0,
                size,
            })
            .collect();
        let info = vk::PipelineLayoutCreateInfo::default()
            .set_layouts(set_layouts)
            .push_constant_ranges(&ranges);
        // SAFETY: valid set layouts.
        let layout = unsafe { self.device.create_pipeline_layout(&info, None) };
        self.created(
            "vkCreatePipelineLayout",
            layout,
            Device::destroy_pipeline_layout,
        )
    }

    /// A pipeline for `subpass` of `render_pass` that draws a fullscreen triangle (`vertex`
    /// makes it from the vertex index) and runs `fragment` on a `width` x `height` viewport,
    /// writing `colour_attachments` attachments without blending.
    #[allow(clippy::too_many_arguments)]
    pub fn fullscreen_pipeline(
        &self,
        render_pass: vk::RenderPass,
        subpass: u32,
        layout: vk::PipelineLayout,
        vertex: vk::ShaderModule,
        fragment: vk::ShaderModule,
        colour_attachments: usize,
        size: (u32, u32),
    ) -> Result<vk::Pipeline, String> {
        self.graphics_pipeline(&GraphicsPipeline {
            draws_in: DrawsIn::Subpass(render_pass, subpass),
            layout,
            shaders: (vertex, fragment),
            vertex_entry: c"main",
            vertex_input: (&[], &[]),
            depth: None,
            colour_writes: &vec![true; colour_attachments],
            size,
        })
    }

    /// A graphics pipeline as `description` says: triangle lists, no culling, no blending, one
    /// sample, a viewport and scissor of its size; in a dynamic rendering, with its attachments'
    /// formats, locations and input attachment indices chained to the create info.
    pub fn graphics_pipeline(
        &self,
        description: &GraphicsPipeline,
    ) -> Result<vk::Pipeline, String> {
        let (vertex, fragment) = description.shaders;
        let stages = [
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::VERTEX)
                .module(vertex)
                .name(description.vertex_entry),
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::FRAGMENT)
                .module(fragment)
                .name(c"main"),
        ];
        let (bindings, attributes) = description.vertex_input;
        let vertex_input = vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(bindings)
            .vertex_attribute_descriptions(attributes);
        let input_assembly = vk::PipelineInputAssemblyStateCreateInfo::default()
            .topology(vk::PrimitiveTopology::TRIANGLE_LIST);
        let (width, height) = description.size;
        let viewports = [vk::Viewport {
            x: 0.0,
            y: 0.0,
            width: width as f32,
            height: height as f32,
            min_depth: 0.0,
            max_depth: 1.0,
        }];
        let scissors = [vk::Rect2D {
            offset: vk::Offset2D { x: 0, y: 0 },
            extent: vk::Extent2D { width, height },
        }];
        let viewport = vk::PipelineViewportStateCreateInfo::default()
            .viewports(&viewports)
            .scissors(&scissors);
        let rasterization = vk::PipelineRasterizationStateCreateInfo::default()
            .polygon_mode(vk::PolygonMode::FILL)
            .cull_mode(vk::CullModeFlags::NONE)
            .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
            .line_width(1.0);
        let multisample = vk::PipelineMultisampleStateCreateInfo::default()
            .rasterization_samples(vk::SampleCountFlags::TYPE_1);
        let blend_attachments: Vec<vk::PipelineColorBlendAttachmentState> = description
            .colour_writes
            .iter()
            .map(|&writes| {
                vk::PipelineColorBlendAttachmentState::default().color_write_mask(if writes {
                    vk::ColorComponentFlags::RGBA
                } else {
                    vk::ColorComponentFlags::empty()
                })
            })
            .collect();
        let mut blend =
            vk::PipelineColorBlendStateCreateInfo::default().attachments(&blend_attachments);
        let rendering = match description.draws_in {
            DrawsIn::Subpass(..) => None,
            DrawsIn::Rendering(attachments) => Some(attachments),
        };
        if rendering.is_some_and(|attachments| attachments.rasterization_order) {
            blend = blend.flags(
                vk::PipelineColorBlendStateCreateFlags::RASTERIZATION_ORDER_ATTACHMENT_ACCESS_EXT,
            );
        }
        // What a pipeline for a dynamic rendering is told of its attachments.
        let mut rendering_infos = rendering.map(|attachments| {
            (
                vk::PipelineRenderingCreateInfo::default()
                    .color_attachment_formats(&attachments.colour_formats)
                    .depth_attachment_format(attachments.depth_format),
                vk::RenderingAttachmentLocationInfoKHR::default()
                    .color_attachment_locations(&attachments.locations),
                vk::RenderingInputAttachmentIndexInfoKHR::default()
                    .color_attachment_input_indices(&attachments.input_indices),
            )
        });
        let depth_state = description.depth.map(|(write, compare)| {
            vk::PipelineDepthStencilStateCreateInfo::default()
                .depth_test_enable(true)
                .depth_write_enable(write)
                .depth_compare_op(compare)
        });
        let mut info = vk::GraphicsPipelineCreateInfo::default()
            .stages(&stages)
            .vertex_input_state(&vertex_input)
            .input_assembly_state(&input_assembly)
            .viewport_state(&viewport)
            .rasterization_state(&rasterization)
            .multisample_state(&multisample)
            .color_blend_state(&blend)
            .layout(description.layout);
        if let DrawsIn::Subpass(render_pass, subpass) = description.draws_in {
            info = info.render_pass(render_pass).subpass(subpass);
        }
        if let Some((formats, locations, input_indices)) = &mut rendering_infos {
            info = info
                .push_next(formats)
                .push_next(locations)
                .push_next(input_indices);
        }
        if let Some(depth_state) = &depth_state {
            info = info.depth_stencil_state(depth_state);
        }
        // SAFETY: the stages, layout and render pass (or rendering attachments) are alive and
        // agree with each other.
        let pipelines = unsafe {
            self.device
                .create_graphics_pipelines(vk::PipelineCache::null(), &[info], None)
        }
        .map_err(|(_, error)| error)
        .map(|pipelines| pipelines[0]);
        self.created(
            "vkCreateGraphicsPipelines",
            pipelines,
            Device::destroy_pipeline,
        )
    }
}
