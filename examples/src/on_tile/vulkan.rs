//! The on-tile renderer on Vulkan (`ash`): the subpass path draws the frame in one render pass
//! whose G-buffer attachments are `TRANSIENT` (in lazily allocated memory where the device
//! offers it), read back as input attachments by the later draws of the same subpass (a
//! feedback loop: `GENERAL` layout, a by-region self-dependency and a barrier between draws)
//! and never stored (`DONT_CARE`); only the output is stored. The two-pass path stores the
//! G-buffer to images and samples them in a second render pass, as wgpu does.
//!
//! Shaders are naga's GLSL 450 of the renderer's WGSL compiled by glslang; the fragment stages
//! that read the G-buffer wrap the translation around the layout's generated Vulkan include.
//! Clip space is y-down in Vulkan: the scene renders with `CLIP_Y_SIGN` -1.

use std::time::Instant;

use ash::vk;
use gbuffer_codegen::emit::glsl::{self as includes, Include};
use gbuffer_testkit::tools::glslang;
use gbuffer_testkit::vulkan::{Object, StorageBuffer, Vulkan};

use super::glsl::{self, Dialect};
use super::recording::{Attachment, Call, Load, Recording};
use super::{fused_wgsl, tile_layout, Path, Stage, TileOptions};
use crate::inputs::{Inputs, Texels};
use crate::mesh::{Mesh, Vertex};
use crate::renderer::{Frame, Options, Positions};
use crate::scene::{DECALS, POINT_LIGHT_COUNT};
use crate::shaders::{used_bindings, SAMPLER_BINDING};

const OUTPUT_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;
const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;
const PACKED_FORMAT: vk::Format = vk::Format::R32G32B32A32_UINT;

/// A Vulkan device with the inputs and the mesh uploaded.
pub struct VulkanRenderer {
    vulkan: Vulkan,
    /// The inputs by binding: environment (1), LUT (2), light map (5).
    inputs: Vec<(u32, vk::ImageView)>,
    linear: vk::Sampler,
    nearest: vk::Sampler,
    vertices: StorageBuffer,
    indices: StorageBuffer,
    index_count: u32,
    volume_indices: StorageBuffer,
}

/// One draw of a pipeline.
#[derive(Clone, Copy)]
enum Draw {
    Mesh,
    Fullscreen,
    /// A volume's screen rectangle: point light `n` below POINT_LIGHT_COUNT, then the decals.
    Volume(u32),
}

/// A pipeline of a plan and what it is called in the recording.
struct StagePipeline {
    name: &'static str,
    pipeline: vk::Pipeline,
}

/// A render pass of a plan: its framebuffer, attachments (for the recording), clear values,
/// the descriptor sets its pipelines bind and its draws.
struct Pass {
    render_pass: vk::RenderPass,
    framebuffer: vk::Framebuffer,
    attachments: Vec<(Attachment, bool)>,
    clears: Vec<vk::ClearValue>,
    layout: vk::PipelineLayout,
    sets: Vec<vk::DescriptorSet>,
    stages: Vec<StagePipeline>,
    draws: Vec<(usize, Draw)>,
    /// Frame textures this pass samples (the two-pass G-buffer), for the recording.
    samples: Vec<Attachment>,
}

/// The passes of one configuration, made once and drawn every frame.
struct Plan {
    passes: Vec<Pass>,
    output: vk::Image,
    read_back: StorageBuffer,
    /// The stored G-buffer images of the debug view, and the buffers they are copied to.
    gbuffer: Vec<(vk::Image, StorageBuffer)>,
    width: u32,
    height: u32,
}

impl VulkanRenderer {
    /// A device (lavapipe here), with the inputs and the mesh uploaded. The error says what is
    /// missing (the loader, a device).
    pub fn new(progress: &dyn Fn(&str)) -> Result<VulkanRenderer, String> {
        let vulkan = Vulkan::new()?;
        progress(&format!("Vulkan: {}", vulkan.describe()));
        progress(if vulkan.has_lazily_allocated_memory() {
            "transient attachments take lazily allocated memory"
        } else {
            "the device offers no lazily allocated memory: transient attachments take device-local memory"
        });
        progress("baking the split-sum LUT, the light map and the prefiltered sky...");
        let inputs = Inputs::bake();
        let mesh = Mesh::scene();
        let sampler = |filter: vk::Filter, mipmap: vk::SamplerMipmapMode, u| {
            let info = vk::SamplerCreateInfo::default()
                .mag_filter(filter)
                .min_filter(filter)
                .mipmap_mode(mipmap)
                .address_mode_u(u)
                .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_EDGE)
                .address_mode_w(vk::SamplerAddressMode::CLAMP_TO_EDGE)
                .max_lod(vk::LOD_CLAMP_NONE);
            // SAFETY: a valid sampler of the device, destroyed with it.
            let sampler = unsafe { vulkan.device.create_sampler(&info, None) }
                .map_err(|error| format!("vkCreateSampler: {error}"))?;
            vulkan.track(Object::Sampler(sampler));
            Ok::<vk::Sampler, String>(sampler)
        };
        // As wgpu's sampler: trilinear, u repeating (around the sky).
        let linear = sampler(
            vk::Filter::LINEAR,
            vk::SamplerMipmapMode::LINEAR,
            vk::SamplerAddressMode::REPEAT,
        )?;
        let nearest = sampler(
            vk::Filter::NEAREST,
            vk::SamplerMipmapMode::NEAREST,
            vk::SamplerAddressMode::CLAMP_TO_EDGE,
        )?;
        let mut renderer = VulkanRenderer {
            vertices: buffer_of(
                &vulkan,
                bytemuck::cast_slice(&mesh.vertices),
                vk::BufferUsageFlags::VERTEX_BUFFER,
            )?,
            indices: buffer_of(
                &vulkan,
                bytemuck::cast_slice(&mesh.indices),
                vk::BufferUsageFlags::INDEX_BUFFER,
            )?,
            index_count: mesh.indices.len() as u32,
            volume_indices: {
                let indices: Vec<u32> = (0..(POINT_LIGHT_COUNT + DECALS.len()) as u32).collect();
                buffer_of(
                    &vulkan,
                    bytemuck::cast_slice(&indices),
                    vk::BufferUsageFlags::VERTEX_BUFFER,
                )?
            },
            vulkan,
            inputs: Vec::new(),
            linear,
            nearest,
        };
        renderer.inputs = vec![
            (
                1,
                renderer.upload(vk::Format::R8G8B8A8_UNORM, &inputs.environment)?,
            ),
            (
                2,
                renderer.upload(vk::Format::R16G16B16A16_SFLOAT, &[inputs.lut])?,
            ),
            (
                5,
                renderer.upload(vk::Format::R8G8B8A8_UNORM, &[inputs.light_map])?,
            ),
        ];
        Ok(renderer)
    }

    /// Renders a frame and reads it back, with the calls it made.
    pub fn render(&self, tile: &TileOptions) -> Result<(Frame, Recording), String> {
        let plan = self.plan(tile)?;
        let mut recording = Recording::default();
        self.submit_frame(&plan, &mut recording)?;
        recording.push(Call::ReadBack("output".into()));
        let words = self.vulkan.read_buffer(&plan.read_back)?;
        let pixels = words
            .iter()
            .take((plan.width * plan.height) as usize)
            .map(|word| word.to_le_bytes())
            .collect();
        Ok((
            Frame {
                width: plan.width,
                height: plan.height,
                pixels,
            },
            recording,
        ))
    }

    /// Times `frames` frames (after one that warms up): seconds each, by the wall clock around
    /// a submit and its wait.
    pub fn time_frames(&self, tile: &TileOptions, frames: usize) -> Result<Vec<f64>, String> {
        let plan = self.plan(tile)?;
        let mut times = Vec::with_capacity(frames);
        for _ in 0..=frames {
            let start = Instant::now();
            self.submit_frame(&plan, &mut Recording::default())?;
            times.push(start.elapsed().as_secs_f64());
        }
        times.remove(0);
        Ok(times)
    }

    /// The checked plan of a configuration.
    fn plan(&self, tile: &TileOptions) -> Result<Plan, String> {
        let options = &tile.options;
        let layout = tile_layout(options)?;
        match tile.path {
            Path::Subpass => self.subpass_plan(options, layout, false),
            Path::TwoPass => self.two_pass_plan(options),
            other => Err(format!(
                "--path {} is GLES's: use --backend gles",
                other.flag()
            )),
        }
    }

    /// The packed words the geometry writes (a debug view: the G-buffer stored, before decals
    /// and light), `layout.words()` per pixel, row by row.
    pub fn gbuffer_words(&self, options: &Options) -> Result<Vec<u32>, String> {
        let layout = tile_layout(options)?;
        let plan = self.subpass_plan(options, layout, true)?;
        self.submit_frame(&plan, &mut Recording::default())?;
        let targets = plan
            .gbuffer
            .iter()
            .map(|(_, buffer)| self.vulkan.read_buffer(buffer))
            .collect::<Result<Vec<_>, String>>()?;
        Ok(crate::renderer::texels_of(
            &targets,
            (plan.width * plan.height) as usize,
            layout.layout().words(),
        ))
    }

    /// The subpass path: one render pass, one subpass, six pipelines. With `store_gbuffer`
    /// (the debug view) the G-buffer is stored and only the geometry drawn.
    fn subpass_plan(
        &self,
        options: &Options,
        layout: crate::gbuffers::SeedLayout,
        store_gbuffer: bool,
    ) -> Result<Plan, String> {
        let model = layout.layout();
        let (include, interface) = includes::include(&model, Include::SubpassPacked, 1)
            .map_err(|error| error.to_string())?;
        let targets = interface.attachments.len() as u32;
        let limits = &self.vulkan.limits;
        if targets + 1 > limits.max_color_attachments
            || targets + 1 > limits.max_fragment_output_attachments
            || targets > limits.max_per_stage_descriptor_input_attachments
        {
            return Err(format!(
                "layout `{}` on --path subpass needs {} colour attachments and {targets} input \
                 attachments, but the device offers maxColorAttachments = {}, \
                 maxFragmentOutputAttachments = {} and maxPerStageDescriptorInputAttachments = {}",
                layout.flag(),
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
        let mut views = Vec::new();
        let mut gbuffer = Vec::new();
        for _ in 0..targets {
            let usage = vk::ImageUsageFlags::COLOR_ATTACHMENT
                | vk::ImageUsageFlags::INPUT_ATTACHMENT
                | kept;
            let (image, view, _) = self
                .vulkan
                .image(PACKED_FORMAT, (width, height, 1), usage)?;
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
        views.push(output_view);
        let (_, depth_view, _) = self.vulkan.image(
            DEPTH_FORMAT,
            (width, height, 1),
            vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | transient,
        )?;
        views.push(depth_view);

        // Attachments: the G-buffer targets (cleared, never stored, GENERAL: read and written
        // in the same subpass), the output (stored), depth (never stored).
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
        let render_pass = self.render_pass(&descriptions, &subpass, &dependencies)?;
        let framebuffer = self.framebuffer(render_pass, &views, width, height)?;

        // Descriptors: the inputs the stages sample in set 0, the G-buffer inputs in set 1,
        // the volume index as a push constant.
        let wgsl = fused_wgsl(options, layout, -1.0);
        let sampled = used_bindings(&wgsl, "translation_entry");
        let (set0_layout, set0) = self.sampled_set(&sampled, &[])?;
        let input_views: Vec<vk::ImageView> = views[..targets as usize].to_vec();
        let (set1_layout, set1) = self.input_attachment_set(&input_views)?;
        let layout_handle = self.pipeline_layout(&[set0_layout, set1_layout], true)?;

        let snake = model.snake_name();
        let names = includes::translate(&model)
            .map_err(|error| error.to_string())?
            .names;
        let texel = &names.layout;
        let outputs: String = (0..targets)
            .map(|index| {
                format!("layout(location = {index}) out highp uvec4 gbuffer_out{index};\n")
            })
            .chain([format!(
                "layout(location = {targets}) out highp vec4 frame_colour;\n"
            )])
            .collect();
        let store = includes::store_statements(&model, &names, &interface, |attachment| {
            format!("gbuffer_out{}", attachment.index)
        });
        // The volume drawn comes as a push constant; each draw writes only what it changes.
        let volume = "layout(push_constant) uniform Volume {\n    uint volume_index;\n};\n";
        let translation = glsl::translate(
            &wgsl,
            naga::ShaderStage::Fragment,
            "translation_entry",
            Dialect::Vulkan,
        )?;
        let declarations = glsl::declarations(&translation.text, &include);
        let mut pipeline_stages = Vec::new();
        for stage in Stage::ALL {
            let depth = match stage {
                Stage::Geometry => Depth::Write,
                Stage::Sky => Depth::Sky,
                _ => Depth::Surfaces,
            };
            let writes = stage.writes(layout, targets as usize, 4);
            let fragment = format!(
                "#version 450\n\n{include}\n{outputs}{volume}\n{declarations}\n{}",
                stage.fragment_main(texel, &snake, &store)
            );
            let pipeline = self
                .pipeline(
                    &wgsl,
                    stage.vertex_entry(),
                    &fragment,
                    render_pass,
                    layout_handle,
                    (depth, &writes),
                    (width, height),
                )
                .map_err(|error| format!("the {} pipeline: {error}", stage.name()))?;
            pipeline_stages.push(StagePipeline {
                name: stage.name(),
                pipeline,
            });
        }
        let mut draws = vec![(0, Draw::Mesh)];
        if !store_gbuffer {
            draws.extend(
                (0..DECALS.len())
                    .map(|decal| (1, Draw::Volume((POINT_LIGHT_COUNT + decal) as u32))),
            );
            draws.push((2, Draw::Fullscreen));
            draws.extend((0..POINT_LIGHT_COUNT).map(|light| (3, Draw::Volume(light as u32))));
            draws.push((4, Draw::Fullscreen));
            draws.push((5, Draw::Fullscreen));
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
                render_pass,
                framebuffer,
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

    /// The two-pass path: wgpu's G-buffer pass into stored images, then its lighting pass
    /// (with the tone mapping) sampling them.
    fn two_pass_plan(&self, options: &Options) -> Result<Plan, String> {
        let (width, height) = (options.width, options.height);
        let formats: Vec<(vk::Format, u32)> = options
            .gbuffer
            .target_formats()
            .iter()
            .map(|format| match format {
                wgpu::TextureFormat::R32Uint => (vk::Format::R32_UINT, 4),
                wgpu::TextureFormat::Rg32Uint => (vk::Format::R32G32_UINT, 8),
                _ => (PACKED_FORMAT, 16),
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
        let first_pass = self.render_pass(&descriptions, &subpass, &to_sampling)?;
        let mut views = gbuffer_views.clone();
        views.push(depth_view);
        let first_framebuffer = self.framebuffer(first_pass, &views, width, height)?;
        let gbuffer_wgsl = crate::renderer::gbuffer_wgsl(options, -1.0);
        let (set_layout, set) =
            self.sampled_set(&used_bindings(&gbuffer_wgsl, "gbuffer_main"), &[])?;
        let first_layout = self.pipeline_layout(&[set_layout], false)?;
        let gbuffer_fragment = glsl::translate(
            &gbuffer_wgsl,
            naga::ShaderStage::Fragment,
            "gbuffer_main",
            Dialect::Vulkan,
        )?;
        let gbuffer = self.pipeline(
            &gbuffer_wgsl,
            "geometry_vertex",
            &gbuffer_fragment.text,
            first_pass,
            first_layout,
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
            self.render_pass(&output_description, &subpass, &[output_to_transfer()])?;
        let second_framebuffer = self.framebuffer(second_pass, &[output_view], width, height)?;
        let lighting_wgsl = crate::renderer::lighting_pass_wgsl(options, Positions::Texel)?;
        let gbuffer_bindings: Vec<(u32, vk::ImageView)> = gbuffer_views
            .iter()
            .enumerate()
            .map(|(index, view)| (10 + index as u32, *view))
            .collect();
        let (lighting_set_layout, lighting_set) = self.sampled_set(
            &used_bindings(&lighting_wgsl, "lighting_resolve_main"),
            &gbuffer_bindings,
        )?;
        let second_layout = self.pipeline_layout(&[lighting_set_layout], false)?;
        let lighting_fragment = glsl::translate(
            &lighting_wgsl,
            naga::ShaderStage::Fragment,
            "lighting_resolve_main",
            Dialect::Vulkan,
        )?;
        let lighting = self.pipeline(
            &lighting_wgsl,
            "full_screen",
            &lighting_fragment.text,
            second_pass,
            second_layout,
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
                    render_pass: first_pass,
                    framebuffer: first_framebuffer,
                    attachments: first_attachments,
                    clears,
                    layout: first_layout,
                    sets: vec![set],
                    stages: vec![StagePipeline {
                        name: "gbuffer",
                        pipeline: gbuffer,
                    }],
                    draws: vec![(0, Draw::Mesh)],
                    samples: Vec::new(),
                },
                Pass {
                    render_pass: second_pass,
                    framebuffer: second_framebuffer,
                    attachments: vec![(named("output", 4), true)],
                    clears: vec![clear_float(0.0)],
                    layout: second_layout,
                    sets: vec![lighting_set],
                    stages: vec![StagePipeline {
                        name: "lighting and resolve",
                        pipeline: lighting,
                    }],
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

    /// Records and submits a frame of the plan, and copies the output to the read-back
    /// buffer; waits until it is done.
    fn submit_frame(&self, plan: &Plan, recording: &mut Recording) -> Result<(), String> {
        let extent = vk::Extent2D {
            width: plan.width,
            height: plan.height,
        };
        self.vulkan.submit_and_wait(|device, commands| {
            // SAFETY: the plan's objects are alive; the commands are recorded in order.
            unsafe {
                for pass in &plan.passes {
                    recording.push(Call::BeginPass {
                        attachments: pass
                            .attachments
                            .iter()
                            .map(|(attachment, _)| (attachment.clone(), Load::Clear))
                            .collect(),
                    });
                    for sample in &pass.samples {
                        recording.push(Call::Sample(sample.clone()));
                    }
                    device.cmd_begin_render_pass(
                        commands,
                        &vk::RenderPassBeginInfo::default()
                            .render_pass(pass.render_pass)
                            .framebuffer(pass.framebuffer)
                            .render_area(vk::Rect2D {
                                offset: vk::Offset2D::default(),
                                extent,
                            })
                            .clear_values(&pass.clears),
                        vk::SubpassContents::INLINE,
                    );
                    device.cmd_bind_descriptor_sets(
                        commands,
                        vk::PipelineBindPoint::GRAPHICS,
                        pass.layout,
                        0,
                        &pass.sets,
                        &[],
                    );
                    let mut previous: Option<usize> = None;
                    for &(stage, draw) in &pass.draws {
                        if previous.is_some() && plan.passes.len() == 1 {
                            // The next draw reads what this one wrote (the self-dependency).
                            let barrier = vk::MemoryBarrier::default()
                                .src_access_mask(vk::AccessFlags::COLOR_ATTACHMENT_WRITE)
                                .dst_access_mask(vk::AccessFlags::INPUT_ATTACHMENT_READ);
                            device.cmd_pipeline_barrier(
                                commands,
                                vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT,
                                vk::PipelineStageFlags::FRAGMENT_SHADER,
                                vk::DependencyFlags::BY_REGION,
                                &[barrier],
                                &[],
                                &[],
                            );
                        }
                        if previous != Some(stage) {
                            device.cmd_bind_pipeline(
                                commands,
                                vk::PipelineBindPoint::GRAPHICS,
                                pass.stages[stage].pipeline,
                            );
                        }
                        previous = Some(stage);
                        recording.push(Call::Draw {
                            program: pass.stages[stage].name.to_string(),
                        });
                        match draw {
                            Draw::Mesh => {
                                device.cmd_bind_vertex_buffers(
                                    commands,
                                    0,
                                    &[self.vertices.buffer],
                                    &[0],
                                );
                                device.cmd_bind_index_buffer(
                                    commands,
                                    self.indices.buffer,
                                    0,
                                    vk::IndexType::UINT32,
                                );
                                device.cmd_draw_indexed(commands, self.index_count, 1, 0, 0, 0);
                            }
                            Draw::Fullscreen => device.cmd_draw(commands, 3, 1, 0, 0),
                            Draw::Volume(volume) => {
                                device.cmd_bind_vertex_buffers(
                                    commands,
                                    0,
                                    &[self.volume_indices.buffer],
                                    &[4 * u64::from(volume)],
                                );
                                device.cmd_push_constants(
                                    commands,
                                    pass.layout,
                                    vk::ShaderStageFlags::FRAGMENT,
                                    0,
                                    &volume.to_le_bytes(),
                                );
                                device.cmd_draw(commands, 6, 1, 0, 0);
                            }
                        }
                    }
                    device.cmd_end_render_pass(commands);
                    recording.push(Call::EndPass {
                        stored: pass
                            .attachments
                            .iter()
                            .filter(|(_, stored)| *stored)
                            .map(|(attachment, _)| attachment.name.clone())
                            .collect(),
                    });
                }
                device.cmd_copy_image_to_buffer(
                    commands,
                    plan.output,
                    vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                    plan.read_back.buffer,
                    &[vk::BufferImageCopy::default()
                        .image_subresource(color_layers(0))
                        .image_extent(vk::Extent3D {
                            width: plan.width,
                            height: plan.height,
                            depth: 1,
                        })],
                );
                for (image, buffer) in &plan.gbuffer {
                    device.cmd_copy_image_to_buffer(
                        commands,
                        *image,
                        vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                        buffer.buffer,
                        &[vk::BufferImageCopy::default()
                            .image_subresource(color_layers(0))
                            .image_extent(vk::Extent3D {
                                width: plan.width,
                                height: plan.height,
                                depth: 1,
                            })],
                    );
                }
                let to_host = vk::MemoryBarrier::default()
                    .src_access_mask(vk::AccessFlags::TRANSFER_WRITE)
                    .dst_access_mask(vk::AccessFlags::HOST_READ);
                device.cmd_pipeline_barrier(
                    commands,
                    vk::PipelineStageFlags::TRANSFER,
                    vk::PipelineStageFlags::HOST,
                    vk::DependencyFlags::empty(),
                    &[to_host],
                    &[],
                    &[],
                );
            }
        })
    }

    /// An image of `mips` uploaded through a staging buffer, left for sampling.
    fn upload(&self, format: vk::Format, mips: &[Texels]) -> Result<vk::ImageView, String> {
        let usage = vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST;
        let (image, view, _) = self.vulkan.image(
            format,
            (mips[0].width, mips[0].height, mips.len() as u32),
            usage,
        )?;
        let bytes: Vec<u8> = mips
            .iter()
            .flat_map(|mip| mip.bytes.iter().copied())
            .collect();
        let staging = buffer_of(&self.vulkan, &bytes, vk::BufferUsageFlags::TRANSFER_SRC)?;
        let range = vk::ImageSubresourceRange {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            base_mip_level: 0,
            level_count: mips.len() as u32,
            base_array_layer: 0,
            layer_count: 1,
        };
        self.vulkan.submit_and_wait(|device, commands| {
            // SAFETY: the image and the staging buffer are alive; each copy is within both.
            unsafe {
                let to_transfer = vk::ImageMemoryBarrier::default()
                    .dst_access_mask(vk::AccessFlags::TRANSFER_WRITE)
                    .old_layout(vk::ImageLayout::UNDEFINED)
                    .new_layout(vk::ImageLayout::TRANSFER_DST_OPTIMAL)
                    .image(image)
                    .subresource_range(range);
                device.cmd_pipeline_barrier(
                    commands,
                    vk::PipelineStageFlags::TOP_OF_PIPE,
                    vk::PipelineStageFlags::TRANSFER,
                    vk::DependencyFlags::empty(),
                    &[],
                    &[],
                    &[to_transfer],
                );
                let mut offset = 0;
                let copies: Vec<vk::BufferImageCopy> = mips
                    .iter()
                    .enumerate()
                    .map(|(level, mip)| {
                        let copy = vk::BufferImageCopy::default()
                            .buffer_offset(offset)
                            .image_subresource(color_layers(level as u32))
                            .image_extent(vk::Extent3D {
                                width: mip.width,
                                height: mip.height,
                                depth: 1,
                            });
                        offset += mip.bytes.len() as u64;
                        copy
                    })
                    .collect();
                device.cmd_copy_buffer_to_image(
                    commands,
                    staging.buffer,
                    image,
                    vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                    &copies,
                );
                let to_sampling = vk::ImageMemoryBarrier::default()
                    .src_access_mask(vk::AccessFlags::TRANSFER_WRITE)
                    .dst_access_mask(vk::AccessFlags::SHADER_READ)
                    .old_layout(vk::ImageLayout::TRANSFER_DST_OPTIMAL)
                    .new_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)
                    .image(image)
                    .subresource_range(range);
                device.cmd_pipeline_barrier(
                    commands,
                    vk::PipelineStageFlags::TRANSFER,
                    vk::PipelineStageFlags::FRAGMENT_SHADER,
                    vk::DependencyFlags::empty(),
                    &[],
                    &[],
                    &[to_sampling],
                );
            }
        })?;
        Ok(view)
    }

    fn render_pass(
        &self,
        attachments: &[vk::AttachmentDescription],
        subpasses: &[vk::SubpassDescription],
        dependencies: &[vk::SubpassDependency],
    ) -> Result<vk::RenderPass, String> {
        // SAFETY: the descriptions reference only `attachments`.
        let render_pass = unsafe {
            self.vulkan.device.create_render_pass(
                &vk::RenderPassCreateInfo::default()
                    .attachments(attachments)
                    .subpasses(subpasses)
                    .dependencies(dependencies),
                None,
            )
        }
        .map_err(|error| format!("vkCreateRenderPass: {error}"))?;
        self.vulkan.track(Object::RenderPass(render_pass));
        Ok(render_pass)
    }

    fn framebuffer(
        &self,
        render_pass: vk::RenderPass,
        views: &[vk::ImageView],
        width: u32,
        height: u32,
    ) -> Result<vk::Framebuffer, String> {
        self.vulkan.framebuffer(render_pass, views, width, height)
    }

    /// A descriptor set (and its layout) of combined image samplers at `bindings`: the inputs
    /// (linear sampler) and `frame_textures` (nearest), for the fragment stage.
    fn sampled_set(
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
    fn input_attachment_set(
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
    fn descriptor_set(
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

    fn pipeline_layout(
        &self,
        sets: &[vk::DescriptorSetLayout],
        push_constant: bool,
    ) -> Result<vk::PipelineLayout, String> {
        let ranges = [vk::PushConstantRange {
            stage_flags: vk::ShaderStageFlags::FRAGMENT,
            offset: 0,
            size: 4,
        }];
        let mut info = vk::PipelineLayoutCreateInfo::default().set_layouts(sets);
        if push_constant {
            info = info.push_constant_ranges(&ranges);
        }
        // SAFETY: the set layouts are alive.
        let layout = unsafe { self.vulkan.device.create_pipeline_layout(&info, None) }
            .map_err(|error| format!("vkCreatePipelineLayout: {error}"))?;
        self.vulkan.track(Object::PipelineLayout(layout));
        Ok(layout)
    }

    /// A pipeline: `vertex` of the WGSL translated and `fragment` (GLSL 450), compiled by
    /// glslang, with the vertex input its vertex stage takes, a depth test, and colour writes
    /// to the attachments `writes` marks.
    #[allow(clippy::too_many_arguments)]
    fn pipeline(
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
        let entry = c"main";
        let stages = [
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::VERTEX)
                .module(vertex_module)
                .name(entry),
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::FRAGMENT)
                .module(fragment_module)
                .name(entry),
        ];
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
        let vertex_input = vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(&bindings)
            .vertex_attribute_descriptions(&attributes);
        let assembly = vk::PipelineInputAssemblyStateCreateInfo::default()
            .topology(vk::PrimitiveTopology::TRIANGLE_LIST);
        let viewports = [vk::Viewport {
            x: 0.0,
            y: 0.0,
            width: width as f32,
            height: height as f32,
            min_depth: 0.0,
            max_depth: 1.0,
        }];
        let scissors = [vk::Rect2D {
            offset: vk::Offset2D::default(),
            extent: vk::Extent2D { width, height },
        }];
        let viewport = vk::PipelineViewportStateCreateInfo::default()
            .viewports(&viewports)
            .scissors(&scissors);
        let rasterisation = vk::PipelineRasterizationStateCreateInfo::default()
            .polygon_mode(vk::PolygonMode::FILL)
            .cull_mode(vk::CullModeFlags::NONE)
            .line_width(1.0);
        let multisample = vk::PipelineMultisampleStateCreateInfo::default()
            .rasterization_samples(vk::SampleCountFlags::TYPE_1);
        let (test, write, compare) = match depth {
            Depth::None => (false, false, vk::CompareOp::ALWAYS),
            Depth::Write => (true, true, vk::CompareOp::LESS),
            Depth::Surfaces => (true, false, vk::CompareOp::GREATER),
            Depth::Sky => (true, false, vk::CompareOp::EQUAL),
        };
        let depth_state = vk::PipelineDepthStencilStateCreateInfo::default()
            .depth_test_enable(test)
            .depth_write_enable(write)
            .depth_compare_op(compare);
        let blends: Vec<vk::PipelineColorBlendAttachmentState> = writes
            .iter()
            .map(|&writes| {
                vk::PipelineColorBlendAttachmentState::default().color_write_mask(if writes {
                    vk::ColorComponentFlags::RGBA
                } else {
                    vk::ColorComponentFlags::empty()
                })
            })
            .collect();
        let blend = vk::PipelineColorBlendStateCreateInfo::default().attachments(&blends);
        let mut info = vk::GraphicsPipelineCreateInfo::default()
            .stages(&stages)
            .vertex_input_state(&vertex_input)
            .input_assembly_state(&assembly)
            .viewport_state(&viewport)
            .rasterization_state(&rasterisation)
            .multisample_state(&multisample)
            .color_blend_state(&blend)
            .layout(layout)
            .render_pass(render_pass)
            .subpass(0);
        if depth != Depth::None {
            info = info.depth_stencil_state(&depth_state);
        }
        // SAFETY: every state the pipeline needs is given; the objects it names are alive.
        let pipeline = unsafe {
            self.vulkan
                .device
                .create_graphics_pipelines(vk::PipelineCache::null(), &[info], None)
        }
        .map_err(|(_, error)| format!("vkCreateGraphicsPipelines: {error}"))?[0];
        self.vulkan.track(Object::Pipeline(pipeline));
        Ok(pipeline)
    }
}

/// How a pipeline tests depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Depth {
    /// No depth attachment.
    None,
    /// The mesh: LESS, written.
    Write,
    /// Fullscreen and volume draws over the surfaces: GREATER than their depth.
    Surfaces,
    /// The sky: EQUAL to the cleared far plane.
    Sky,
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

fn color_layers(mip_level: u32) -> vk::ImageSubresourceLayers {
    vk::ImageSubresourceLayers {
        aspect_mask: vk::ImageAspectFlags::COLOR,
        mip_level,
        base_array_layer: 0,
        layer_count: 1,
    }
}

fn clear_uint(value: u32) -> vk::ClearValue {
    vk::ClearValue {
        color: vk::ClearColorValue { uint32: [value; 4] },
    }
}

fn clear_float(value: f32) -> vk::ClearValue {
    vk::ClearValue {
        color: vk::ClearColorValue {
            float32: [value; 4],
        },
    }
}

fn clear_depth() -> vk::ClearValue {
    vk::ClearValue {
        depth_stencil: vk::ClearDepthStencilValue {
            depth: 1.0,
            stencil: 0,
        },
    }
}

fn named(name: &str, bytes_per_pixel: u32) -> Attachment {
    Attachment {
        name: name.to_string(),
        bytes_per_pixel,
    }
}

/// A host-visible buffer for `usage` holding `bytes` (padded to whole words).
fn buffer_of(
    vulkan: &Vulkan,
    bytes: &[u8],
    usage: vk::BufferUsageFlags,
) -> Result<StorageBuffer, String> {
    let mut words = vec![0u32; bytes.len().div_ceil(4)];
    bytemuck::cast_slice_mut::<u32, u8>(&mut words)[..bytes.len()].copy_from_slice(bytes);
    let buffer = vulkan.host_buffer(words.len(), usage)?;
    vulkan.write_buffer(&buffer, &words)?;
    Ok(buffer)
}
