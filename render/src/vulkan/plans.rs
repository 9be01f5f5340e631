//! The plans of the Vulkan backend: the fused paths' one pass (the subpass path's render pass
//! object, the local-read paths' dynamic rendering), and the two-pass path's two render passes.

use ash::vk;
use gbuffer_codegen::emit::glsl::local_read::ATTACHMENT_UNUSED;
use gbuffer_core::Named;

use gbuffer_gpu::vulkan::{DrawsIn, RenderingAttachments};

use super::fused_pipelines::{self, PUSH_CONSTANT_BYTES};
use super::objects::Depth;
use super::{
    clear_depth, clear_float, clear_uint, named, Begin, Draw, Pass, Plan, Rendering, StagePipeline,
    VulkanRenderer, DEPTH_FORMAT, OUTPUT_FORMAT, PACKED_FORMAT,
};
use crate::fused_programs::{fused_programs, FusedDialect};
use crate::on_tile::{Path, Stage};
use crate::options::Options;
use crate::recording::Attachment;
use crate::scene::{DECALS, POINT_LIGHT_COUNT};
use crate::shaders::Positions;

/// How a fused plan keeps the G-buffer in its one pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Fused {
    /// A render pass object of one subpass reading its own attachments (a feedback loop);
    /// `store_gbuffer` (the debug view) stores the G-buffer and draws only the geometry.
    Subpass { store_gbuffer: bool },
    /// A dynamic rendering reading its own attachments (`VK_KHR_dynamic_rendering_local_read`):
    /// a by-region barrier before each draw that reads earlier draws' writes, or none where the
    /// pipelines read in rasterization order.
    LocalRead { rasterization_order: bool },
}

impl VulkanRenderer {
    /// Why the device cannot draw `path` (a local-read path without the extensions it needs),
    /// or `None` where it can.
    pub fn cannot_draw(&self, path: Path) -> Option<String> {
        match path {
            Path::LocalRead => self.local_read_commands(false).err(),
            Path::LocalReadOrdered => self.local_read_commands(true).err(),
            _ => None,
        }
    }

    /// The local-read commands, or why the device cannot draw the local-read path (in
    /// rasterization order where `rasterization_order`).
    fn local_read_commands(
        &self,
        rasterization_order: bool,
    ) -> Result<ash::khr::dynamic_rendering_local_read::Device, String> {
        let path = if rasterization_order {
            Path::LocalReadOrdered
        } else {
            Path::LocalRead
        };
        let local_read = self.vulkan.local_read().map_err(|why| {
            format!(
                "--path {} needs dynamic rendering with local read: {why}",
                path.name()
            )
        })?;
        if let (true, Err(why)) = (rasterization_order, &local_read.rasterization_order) {
            return Err(format!(
                "--path {} needs rasterization-order attachment access: {why} (--path \
                 local-read draws with barriers instead)",
                path.name()
            ));
        }
        Ok(local_read.commands.clone())
    }

    /// A fused path: one render pass (a render pass object's one subpass, or one dynamic
    /// rendering), five pipelines, the G-buffer in transient attachments read back as input
    /// attachments by the later draws.
    pub(super) fn fused_plan(
        &self,
        options: &Options,
        layout: crate::gbuffers::PackedLayout,
        fused: Fused,
    ) -> Result<Plan, String> {
        let store_gbuffer = fused
            == Fused::Subpass {
                store_gbuffer: true,
            };
        let rasterization_order = fused
            == Fused::LocalRead {
                rasterization_order: true,
            };
        // The local-read paths' commands, checked before anything is made for them.
        let local_read = match fused {
            Fused::Subpass { .. } => None,
            Fused::LocalRead { .. } => Some(self.local_read_commands(rasterization_order)?),
        };
        // The same shaders for the subpass and the local-read paths: what differs is the
        // pipeline and the pass.
        let shaders = fused_programs(options, FusedDialect::VulkanSubpass)?;
        let interface = &shaders.interface;
        let targets = interface.attachments.len() as u32;
        let limits = &self.vulkan.limits;
        if targets + 1 > limits.max_color_attachments
            || targets + 1 > limits.max_fragment_output_attachments
            || targets > limits.max_per_stage_descriptor_input_attachments
        {
            return Err(format!(
                "layout `{}` on the fused paths needs {} colour attachments and {targets} input \
                 attachments, but the device offers maxColorAttachments = {}, \
                 maxFragmentOutputAttachments = {} and maxPerStageDescriptorInputAttachments = {}",
                layout.name(),
                targets + 1,
                limits.max_color_attachments,
                limits.max_fragment_output_attachments,
                limits.max_per_stage_descriptor_input_attachments
            ));
        }
        let (width, height) = (options.width, options.height);
        let transient = vk::ImageUsageFlags::TRANSIENT_ATTACHMENT;
        // The debug view stores the G-buffer to copy it out; otherwise it is transient.
        let kept = if store_gbuffer {
            vk::ImageUsageFlags::TRANSFER_SRC
        } else {
            transient
        };
        let mut images = Vec::new();
        let mut views = Vec::new();
        let mut gbuffer = Vec::new();
        for _ in 0..targets {
            let usage = vk::ImageUsageFlags::COLOR_ATTACHMENT
                | vk::ImageUsageFlags::INPUT_ATTACHMENT
                | kept;
            let (image, view, _) = self
                .vulkan
                .image(PACKED_FORMAT, (width, height, 1), usage)?;
            images.push(image);
            views.push(view);
            if store_gbuffer {
                let words = (width * height * 4) as usize;
                let buffer = self
                    .vulkan
                    .host_buffer(words, vk::BufferUsageFlags::TRANSFER_DST)?;
                gbuffer.push((image, buffer));
            }
        }
        let (output, output_view, _) = self.vulkan.image(
            OUTPUT_FORMAT,
            (width, height, 1),
            vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC,
        )?;
        images.push(output);
        views.push(output_view);
        let (depth_image, depth_view, _) = self.vulkan.image(
            DEPTH_FORMAT,
            (width, height, 1),
            vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | transient,
        )?;
        images.push(depth_image);
        views.push(depth_view);

        // The G-buffer attachments at the locations and input attachment indices the include's
        // host data gives (the codegen's `.local_read.json`); the output, at the next location,
        // is read by no shader.
        let host = shaders
            .local_read
            .as_ref()
            .ok_or("the Vulkan programs have no local-read host data")?;
        let rendering = RenderingAttachments {
            colour_formats: host
                .attachments
                .iter()
                .map(|attachment| vk::Format::from_raw(attachment.format.value as i32))
                .chain([OUTPUT_FORMAT])
                .collect(),
            depth_format: DEPTH_FORMAT,
            locations: host
                .attachments
                .iter()
                .map(|attachment| attachment.location)
                .chain([targets])
                .collect(),
            input_indices: host
                .attachments
                .iter()
                .map(|attachment| attachment.input_attachment_index)
                .chain([ATTACHMENT_UNUSED])
                .collect(),
            rasterization_order,
        };
        let begin = match local_read {
            None => self.feedback_render_pass(targets, store_gbuffer, &views, (width, height))?,
            Some(commands) => Begin::Rendering(Rendering {
                images,
                views: views.clone(),
                attachments: rendering.clone(),
                commands,
            }),
        };

        // Descriptors: the inputs the stages sample in set 0, the G-buffer inputs in set 1,
        // the volume index as a push constant.
        let pipelines = fused_pipelines::of_programs(&shaders)?;
        let (set0_layout, set0) = self.sampled_set(&pipelines[0].sampled, &[])?;
        let input_views: Vec<vk::ImageView> = views[..targets as usize].to_vec();
        let input_layout = match fused {
            Fused::Subpass { .. } => vk::ImageLayout::GENERAL,
            Fused::LocalRead { .. } => vk::ImageLayout::RENDERING_LOCAL_READ_KHR,
        };
        let (set1_layout, set1) = self.input_attachment_set(&input_views, input_layout)?;
        let layout_handle = self
            .vulkan
            .pipeline_layout(&[set0_layout, set1_layout], Some(PUSH_CONSTANT_BYTES))?;

        let draws_in = match &begin {
            Begin::RenderPass { render_pass, .. } => DrawsIn::Subpass(*render_pass, 0),
            Begin::Rendering(_) => DrawsIn::Rendering(&rendering),
        };
        let mut pipeline_stages = Vec::new();
        for compiled in pipelines {
            let stage = compiled.stage;
            let depth = match stage {
                Stage::Geometry => Depth::Write,
                Stage::Sky => Depth::Sky,
                _ => Depth::Surfaces,
            };
            let writes = stage.writes(layout, targets as usize, 4);
            let pipeline = self
                .pipeline_of_spirv(
                    stage.vertex_entry(),
                    (compiled.vertex, compiled.fragment),
                    draws_in,
                    layout_handle,
                    (depth, &writes),
                    (width, height),
                )
                .map_err(|error| format!("the {} pipeline: {error}", stage.name()))?;
            pipeline_stages.push(StagePipeline {
                name: stage.name(),
                pipeline,
                // In rasterization order a draw sees what the draws before it wrote unasked.
                reads_earlier_draws: stage.reads_gbuffer() && !rasterization_order,
            });
        }
        // Each draw names its stage by its place in `Stage::ALL`, as `pipeline_stages` holds them.
        let at = |stage: Stage| {
            Stage::ALL
                .iter()
                .position(|s| *s == stage)
                .expect("a stage")
        };
        let mut draws = vec![(at(Stage::Geometry), Draw::Mesh)];
        if !store_gbuffer {
            draws.extend((0..DECALS.len()).map(|decal| {
                (
                    at(Stage::Decal),
                    Draw::Volume((POINT_LIGHT_COUNT + decal) as u32),
                )
            }));
            draws.extend(
                [Stage::Lighting, Stage::Resolve, Stage::Sky]
                    .map(|stage| (at(stage), Draw::Fullscreen)),
            );
        }

        let mut attachments: Vec<(Attachment, bool)> = (0..targets)
            .map(|index| (named(&format!("gbuffer{index}"), 16), store_gbuffer))
            .collect();
        attachments.push((named("output", 4), true));
        attachments.push((named("depth", 4), false));
        let mut clears = vec![clear_uint(0); targets as usize];
        clears.push(clear_float(0.0));
        clears.push(clear_depth());
        Ok(Plan {
            passes: vec![Pass {
                begin,
                attachments,
                clears,
                layout: layout_handle,
                sets: vec![set0, set1],
                stages: pipeline_stages,
                draws,
                samples: Vec::new(),
            }],
            output,
            read_back: self.vulkan.host_buffer(
                (width * height) as usize,
                vk::BufferUsageFlags::TRANSFER_DST,
            )?,
            gbuffer,
            width,
            height,
        })
    }

    /// The subpass path's render pass of one subpass over `views` (the G-buffer's `targets`
    /// attachments, cleared, never stored but for the debug view, `GENERAL`: read and written in
    /// the same subpass; the output, stored; depth, never stored) and its framebuffer.
    fn feedback_render_pass(
        &self,
        targets: u32,
        store_gbuffer: bool,
        views: &[vk::ImageView],
        (width, height): (u32, u32),
    ) -> Result<Begin, String> {
        let gbuffer_layout = if store_gbuffer {
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL
        } else {
            vk::ImageLayout::GENERAL
        };
        let mut descriptions: Vec<vk::AttachmentDescription> = (0..targets)
            .map(|_| attachment_description(PACKED_FORMAT, store_gbuffer, gbuffer_layout))
            .collect();
        descriptions.push(attachment_description(
            OUTPUT_FORMAT,
            true,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
        ));
        descriptions.push(attachment_description(
            DEPTH_FORMAT,
            false,
            vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
        ));
        let reference = |attachment, layout| vk::AttachmentReference { attachment, layout };
        let mut colours: Vec<_> = (0..targets)
            .map(|index| reference(index, vk::ImageLayout::GENERAL))
            .collect();
        colours.push(reference(
            targets,
            vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
        ));
        let inputs: Vec<_> = (0..targets)
            .map(|index| reference(index, vk::ImageLayout::GENERAL))
            .collect();
        let depth = reference(
            targets + 1,
            vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
        );
        let subpass = [vk::SubpassDescription::default()
            .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
            .color_attachments(&colours)
            .input_attachments(&inputs)
            .depth_stencil_attachment(&depth)];
        let dependencies = [
            // Within the subpass: a draw reads, by region, what the draws before it wrote.
            vk::SubpassDependency::default()
                .src_subpass(0)
                .dst_subpass(0)
                .src_stage_mask(vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT)
                .dst_stage_mask(vk::PipelineStageFlags::FRAGMENT_SHADER)
                .src_access_mask(vk::AccessFlags::COLOR_ATTACHMENT_WRITE)
                .dst_access_mask(vk::AccessFlags::INPUT_ATTACHMENT_READ)
                .dependency_flags(vk::DependencyFlags::BY_REGION),
            output_to_transfer(),
        ];
        let render_pass = self
            .vulkan
            .render_pass_of(&descriptions, &subpass, &dependencies)?;
        let framebuffer = self.vulkan.framebuffer(render_pass, views, width, height)?;
        Ok(Begin::RenderPass {
            render_pass,
            framebuffer,
        })
    }

    /// The two-pass path: wgpu's G-buffer pass into stored images, then its lighting pass
    /// (with the tone mapping) sampling them.
    pub(super) fn two_pass_plan(&self, options: &Options) -> Result<Plan, String> {
        let (width, height) = (options.width, options.height);
        let formats: Vec<(vk::Format, u32)> = options
            .gbuffer
            .packed_targets()?
            .into_iter()
            .map(|target| {
                let target = target.target();
                let format = vk::Format::from_raw(target.vulkan.format);
                (format, target.webgpu.byte_cost)
            })
            .collect();
        let mut gbuffer_views = Vec::new();
        for &(format, _) in &formats {
            let usage = vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::SAMPLED;
            gbuffer_views.push(self.vulkan.image(format, (width, height, 1), usage)?.1);
        }
        let (_, depth_view, _) = self.vulkan.image(
            DEPTH_FORMAT,
            (width, height, 1),
            vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT
                | vk::ImageUsageFlags::TRANSIENT_ATTACHMENT,
        )?;
        let (output, output_view, _) = self.vulkan.image(
            OUTPUT_FORMAT,
            (width, height, 1),
            vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC,
        )?;

        // Pass 1: the G-buffer, stored for the second pass to sample.
        let mut descriptions: Vec<_> = formats
            .iter()
            .map(|&(format, _)| {
                attachment_description(format, true, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)
            })
            .collect();
        descriptions.push(attachment_description(
            DEPTH_FORMAT,
            false,
            vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
        ));
        let count = formats.len() as u32;
        let colours: Vec<_> = (0..count)
            .map(|attachment| vk::AttachmentReference {
                attachment,
                layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            })
            .collect();
        let depth = vk::AttachmentReference {
            attachment: count,
            layout: vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
        };
        let subpass = [vk::SubpassDescription::default()
            .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
            .color_attachments(&colours)
            .depth_stencil_attachment(&depth)];
        let to_sampling = [vk::SubpassDependency::default()
            .src_subpass(0)
            .dst_subpass(vk::SUBPASS_EXTERNAL)
            .src_stage_mask(vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT)
            .dst_stage_mask(vk::PipelineStageFlags::FRAGMENT_SHADER)
            .src_access_mask(vk::AccessFlags::COLOR_ATTACHMENT_WRITE)
            .dst_access_mask(vk::AccessFlags::SHADER_READ)];
        let first_pass = self
            .vulkan
            .render_pass_of(&descriptions, &subpass, &to_sampling)?;
        let mut views = gbuffer_views.clone();
        views.push(depth_view);
        let first_framebuffer = self.vulkan.framebuffer(first_pass, &views, width, height)?;
        let gbuffer_wgsl = crate::shaders::gbuffer_wgsl(options, -1.0);
        let (gbuffer, first_layout, set) = self.sampling_pipeline(
            &gbuffer_wgsl,
            ("geometry_vertex", "gbuffer_main"),
            &[],
            DrawsIn::Subpass(first_pass, 0),
            (Depth::Write, &vec![true; formats.len()]),
            (width, height),
        )?;

        // Pass 2: lighting and tone mapping into the output.
        let output_description = [attachment_description(
            OUTPUT_FORMAT,
            true,
            vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
        )];
        let output_reference = [vk::AttachmentReference {
            attachment: 0,
            layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
        }];
        let subpass = [vk::SubpassDescription::default()
            .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
            .color_attachments(&output_reference)];
        let second_pass =
            self.vulkan
                .render_pass_of(&output_description, &subpass, &[output_to_transfer()])?;
        let second_framebuffer =
            self.vulkan
                .framebuffer(second_pass, &[output_view], width, height)?;
        let lighting_wgsl = crate::shaders::lighting_pass_wgsl(options, Positions::Texel)?;
        let gbuffer_bindings: Vec<(u32, vk::ImageView)> = gbuffer_views
            .iter()
            .enumerate()
            .map(|(index, view)| (10 + index as u32, *view))
            .collect();
        let (lighting, second_layout, lighting_set) = self.sampling_pipeline(
            &lighting_wgsl,
            ("full_screen", "lighting_resolve_main"),
            &gbuffer_bindings,
            DrawsIn::Subpass(second_pass, 0),
            (Depth::None, &[true]),
            (width, height),
        )?;

        let mut first_attachments: Vec<(Attachment, bool)> = formats
            .iter()
            .enumerate()
            .map(|(index, &(_, bytes))| (named(&format!("gbuffer{index}"), bytes), true))
            .collect();
        first_attachments.push((named("depth", 4), false));
        let samples = first_attachments[..formats.len()]
            .iter()
            .map(|(attachment, _)| attachment.clone())
            .collect();
        let mut clears = vec![clear_uint(u32::MAX); formats.len()];
        clears.push(clear_depth());
        Ok(Plan {
            passes: vec![
                Pass {
                    begin: Begin::RenderPass {
                        render_pass: first_pass,
                        framebuffer: first_framebuffer,
                    },
                    attachments: first_attachments,
                    clears,
                    layout: first_layout,
                    sets: vec![set],
                    stages: vec![StagePipeline::named("gbuffer", gbuffer)],
                    draws: vec![(0, Draw::Mesh)],
                    samples: Vec::new(),
                },
                Pass {
                    begin: Begin::RenderPass {
                        render_pass: second_pass,
                        framebuffer: second_framebuffer,
                    },
                    attachments: vec![(named("output", 4), true)],
                    clears: vec![clear_float(0.0)],
                    layout: second_layout,
                    sets: vec![lighting_set],
                    stages: vec![StagePipeline::named("lighting and resolve", lighting)],
                    draws: vec![(0, Draw::Fullscreen)],
                    samples,
                },
            ],
            output,
            read_back: self.vulkan.host_buffer(
                (width * height) as usize,
                vk::BufferUsageFlags::TRANSFER_DST,
            )?,
            gbuffer: Vec::new(),
            width,
            height,
        })
    }
}

/// An attachment cleared at the start of the render pass, stored at its end or not.
fn attachment_description(
    format: vk::Format,
    stored: bool,
    final_layout: vk::ImageLayout,
) -> vk::AttachmentDescription {
    vk::AttachmentDescription::default()
        .format(format)
        .samples(vk::SampleCountFlags::TYPE_1)
        .load_op(vk::AttachmentLoadOp::CLEAR)
        .store_op(if stored {
            vk::AttachmentStoreOp::STORE
        } else {
            vk::AttachmentStoreOp::DONT_CARE
        })
        .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
        .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
        .initial_layout(vk::ImageLayout::UNDEFINED)
        .final_layout(final_layout)
}

/// The output, written in the pass, then copied out.
fn output_to_transfer() -> vk::SubpassDependency {
    vk::SubpassDependency::default()
        .src_subpass(0)
        .dst_subpass(vk::SUBPASS_EXTERNAL)
        .src_stage_mask(vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT)
        .dst_stage_mask(vk::PipelineStageFlags::TRANSFER)
        .src_access_mask(vk::AccessFlags::COLOR_ATTACHMENT_WRITE)
        .dst_access_mask(vk::AccessFlags::TRANSFER_READ)
}

#[cfg(test)]
mod tests {
    use ash::vk;
    use gbuffer_codegen::emit::glsl::local_read::{
        ATTACHMENT_UNUSED, BARRIER, DESCRIPTOR_TYPE, IMAGE_LAYOUT, RASTERIZATION_ORDER_FLAG,
    };

    /// The codegen's host data spells each enumerant by hand; `ash`'s, generated from the
    /// Vulkan registry, are the independent reference, and the barrier is the one the renderer
    /// records.
    #[test]
    fn the_local_read_host_data_has_the_vulkan_registry_values() {
        assert_eq!(
            IMAGE_LAYOUT.value as i32,
            vk::ImageLayout::RENDERING_LOCAL_READ_KHR.as_raw()
        );
        assert_eq!(
            DESCRIPTOR_TYPE.value as i32,
            vk::DescriptorType::INPUT_ATTACHMENT.as_raw()
        );
        assert_eq!(ATTACHMENT_UNUSED, vk::ATTACHMENT_UNUSED);
        assert_eq!(
            RASTERIZATION_ORDER_FLAG.value,
            vk::PipelineColorBlendStateCreateFlags::RASTERIZATION_ORDER_ATTACHMENT_ACCESS_EXT
                .as_raw()
        );
        let ((src_access, src_stage), (dst_access, dst_stage)) = gbuffer_gpu::vulkan::FEEDBACK;
        assert_eq!(
            BARRIER.map(|flag| flag.value),
            [
                src_stage.as_raw(),
                src_access.as_raw(),
                dst_stage.as_raw(),
                dst_access.as_raw(),
                vk::DependencyFlags::BY_REGION.as_raw(),
            ]
        );
    }
}
