//! The on-tile renderer on Vulkan (`ash`): the subpass path draws the frame in one render pass
//! whose G-buffer attachments are `TRANSIENT` (in lazily allocated memory where the device
//! offers it), read back as input attachments by the later draws of the same subpass (a
//! feedback loop: `GENERAL` layout, a by-region self-dependency and a barrier before each draw
//! that reads what earlier draws wrote)
//! and never stored (`DONT_CARE`); only the output is stored. The local-read paths draw the
//! same frame with the same attachments in one dynamic rendering, without render pass or
//! framebuffer objects (`VK_KHR_dynamic_rendering_local_read`: the G-buffer in
//! `RENDERING_LOCAL_READ_KHR`, the same by-region barrier between draws), and the ordered one
//! without any barrier, its pipelines reading in rasterization order
//! (`VK_EXT_rasterization_order_attachment_access`). The two-pass path stores the
//! G-buffer to images and samples them in a second render pass, as wgpu does.
//!
//! Shaders are naga's GLSL 450 of the renderer's WGSL compiled by glslang; the fragment stages
//! that read the G-buffer wrap the translation around the layout's generated Vulkan include.
//! Clip space is y-down in Vulkan: the scene renders with `CLIP_Y_SIGN` -1.
//!
//! Here: the renderer, its uploads and the frame's commands; `plans` makes each path's render
//! passes, `objects` the Vulkan objects they are built of, [`fused_pipelines`] the fused
//! stages' compiled shaders and pipeline state.

use std::time::Instant;

use ash::vk;
use gbuffer_core::Named;
use gbuffer_core::PackedTarget;
use gbuffer_gpu::vulkan::{
    feedback_barrier, host_read_barrier, Access, ImageTransition, RenderingAttachments,
    StorageBuffer, Vulkan, FEEDBACK,
};

pub mod fused_pipelines;
mod objects;
mod plans;

use plans::Fused;

use crate::inputs::{Inputs, Texels};
use crate::mesh::Mesh;
use crate::on_tile::{tile_layout, Path, TileOptions};
use crate::options::{Frame, Options};
use crate::recording::{Attachment, Call, Load, Recording};
use crate::scene::{DECALS, POINT_LIGHT_COUNT};

const OUTPUT_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;
const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;
/// The fused paths' packed attachments: four words each, as the includes declare them.
const PACKED_FORMAT: vk::Format =
    vk::Format::from_raw(PackedTarget::FourWords.target().vulkan.format);

/// A Vulkan device with the inputs and the mesh uploaded.
pub struct VulkanRenderer {
    vulkan: Vulkan,
    /// The inputs by binding: environment (1), LUT (2), light map (5).
    inputs: Vec<(u32, vk::ImageView)>,
    /// Trilinear, wrapping around the sky in u.
    environment_sampler: vk::Sampler,
    /// Trilinear, clamped to the edges: the LUT and the light map.
    clamped_sampler: vk::Sampler,
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
    /// Whether its draws read what the draws before them wrote in the same subpass (an input
    /// attachment another draw writes): a by-region barrier goes before each.
    reads_earlier_draws: bool,
}

impl StagePipeline {
    fn named(name: &'static str, pipeline: vk::Pipeline) -> StagePipeline {
        StagePipeline {
            name,
            pipeline,
            reads_earlier_draws: false,
        }
    }
}

/// How a pass begins: a render pass object over a framebuffer, or a dynamic rendering.
enum Begin {
    RenderPass {
        render_pass: vk::RenderPass,
        framebuffer: vk::Framebuffer,
    },
    Rendering(Rendering),
}

/// A dynamic rendering's attachments: the colour attachments (the G-buffer's, then the
/// output) and depth, as images (for their layout transitions) and views, and what the
/// pipelines were told of them.
struct Rendering {
    /// The colour attachments' images, then depth's.
    images: Vec<vk::Image>,
    /// Their views, in the same order.
    views: Vec<vk::ImageView>,
    attachments: RenderingAttachments,
    /// The commands that map the attachments to the shaders' locations and indices.
    commands: ash::khr::dynamic_rendering_local_read::Device,
}

/// Colour attachment writes, where they happen: the first half of the feedback barrier.
const COLOUR_WRITES: Access = FEEDBACK.0;

/// The layout change of a whole single-mip colour image.
fn colour_transition(image: vk::Image) -> ImageTransition {
    image_transition(image, vk::ImageAspectFlags::COLOR)
}

fn image_transition(image: vk::Image, aspect_mask: vk::ImageAspectFlags) -> ImageTransition {
    ImageTransition {
        image,
        range: vk::ImageSubresourceRange {
            aspect_mask,
            base_mip_level: 0,
            level_count: 1,
            base_array_layer: 0,
            layer_count: 1,
        },
    }
}

/// Begins a dynamic rendering over `rendering`'s attachments, each cleared to its value of
/// `clears`: the G-buffer's in `RENDERING_LOCAL_READ_KHR` (written and read as input
/// attachments by the draws, never stored), the output in `COLOR_ATTACHMENT_OPTIMAL` (stored),
/// depth (never stored); then sets the attachments' locations and input attachment indices
/// the pipelines were created with.
///
/// # Safety
///
/// `commands` is recording outside a render pass; the rendering's objects are alive.
unsafe fn begin_rendering(
    device: &ash::Device,
    commands: vk::CommandBuffer,
    rendering: &Rendering,
    clears: &[vk::ClearValue],
    area: vk::Rect2D,
) {
    let colours = rendering.attachments.colour_formats.len();
    let gbuffer = colours - 1;
    let nothing = (
        vk::ImageLayout::UNDEFINED,
        (
            vk::AccessFlags::empty(),
            vk::PipelineStageFlags::TOP_OF_PIPE,
        ),
    );
    let local_read = (
        vk::ImageLayout::RENDERING_LOCAL_READ_KHR,
        (
            vk::AccessFlags::COLOR_ATTACHMENT_WRITE | vk::AccessFlags::INPUT_ATTACHMENT_READ,
            vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT
                | vk::PipelineStageFlags::FRAGMENT_SHADER,
        ),
    );
    let written = (vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL, COLOUR_WRITES);
    let depth = (
        vk::ImageLayout::DEPTH_ATTACHMENT_OPTIMAL,
        (
            vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_READ
                | vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_WRITE,
            vk::PipelineStageFlags::EARLY_FRAGMENT_TESTS
                | vk::PipelineStageFlags::LATE_FRAGMENT_TESTS,
        ),
    );
    let attachment = |index: usize, layout, store| {
        vk::RenderingAttachmentInfo::default()
            .image_view(rendering.views[index])
            .image_layout(layout)
            .load_op(vk::AttachmentLoadOp::CLEAR)
            .store_op(if store {
                vk::AttachmentStoreOp::STORE
            } else {
                vk::AttachmentStoreOp::DONT_CARE
            })
            .clear_value(clears[index])
    };
    let colour_attachments: Vec<vk::RenderingAttachmentInfo> = (0..colours)
        .map(|index| {
            if index < gbuffer {
                attachment(index, local_read.0, false)
            } else {
                attachment(index, written.0, true)
            }
        })
        .collect();
    let depth_attachment = attachment(colours, depth.0, false);
    // SAFETY: as the caller promises; the transitions precede the rendering that uses them.
    unsafe {
        for (index, &image) in rendering.images.iter().enumerate() {
            if index < gbuffer {
                colour_transition(image).record(device, commands, nothing, local_read);
            } else if index == gbuffer {
                colour_transition(image).record(device, commands, nothing, written);
            } else {
                image_transition(image, vk::ImageAspectFlags::DEPTH)
                    .record(device, commands, nothing, depth);
            }
        }
        device.cmd_begin_rendering(
            commands,
            &vk::RenderingInfo::default()
                .render_area(area)
                .layer_count(1)
                .color_attachments(&colour_attachments)
                .depth_attachment(&depth_attachment),
        );
        rendering.commands.cmd_set_rendering_attachment_locations(
            commands,
            &vk::RenderingAttachmentLocationInfoKHR::default()
                .color_attachment_locations(&rendering.attachments.locations),
        );
        rendering
            .commands
            .cmd_set_rendering_input_attachment_indices(
                commands,
                &vk::RenderingInputAttachmentIndexInfoKHR::default()
                    .color_attachment_input_indices(&rendering.attachments.input_indices),
            );
    }
}

/// A pass of a plan: how it begins, its attachments (for the recording), clear values, the
/// descriptor sets its pipelines bind and its draws.
struct Pass {
    begin: Begin,
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
        Self::on(Vulkan::new()?, progress)
    }

    /// The renderer on an opened device, with the inputs and the mesh uploaded.
    pub fn on(vulkan: Vulkan, progress: &dyn Fn(&str)) -> Result<VulkanRenderer, String> {
        progress(&format!("Vulkan: {}", vulkan.describe()));
        progress(&match vulkan.local_read() {
            Ok(local_read) => match &local_read.rasterization_order {
                Ok(name) => format!(
                    "dynamic rendering with local read, and rasterization-order attachment \
                     access ({})",
                    name.to_string_lossy()
                ),
                Err(why) => format!(
                    "dynamic rendering with local read; no rasterization-order attachment \
                     access: {why}"
                ),
            },
            Err(why) => format!("no dynamic rendering with local read: {why}"),
        });
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
            vulkan.sampler(&info)
        };
        // As wgpu's samplers: trilinear, the environment's wrapping around the sky in u.
        let environment_sampler = sampler(
            vk::Filter::LINEAR,
            vk::SamplerMipmapMode::LINEAR,
            vk::SamplerAddressMode::REPEAT,
        )?;
        let clamped_sampler = sampler(
            vk::Filter::LINEAR,
            vk::SamplerMipmapMode::LINEAR,
            vk::SamplerAddressMode::CLAMP_TO_EDGE,
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
            environment_sampler,
            clamped_sampler,
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

    /// The device's name, API and driver versions.
    pub fn describe(&self) -> &str {
        self.vulkan.describe()
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

    /// A frame of `tile` ready to time, without the draws of the stages or passes named in
    /// `left_out` (a fused path's stages: `Stage::name`; the two-pass path's passes:
    /// `gbuffer`, `lighting and resolve`): the bench builds the frame up by leaving out every
    /// stage after the ones it times, so that a stage's time is what it adds to the frame before
    /// it. An unknown name is an error. Each [`TimedFrame::seconds`] is one
    /// frame; the protocol around it is `gbuffer_gpu::timing`'s.
    pub fn timed_frame(
        &self,
        tile: &TileOptions,
        left_out: &[&str],
    ) -> Result<TimedFrame<'_>, String> {
        let mut plan = self.plan(tile)?;
        for name in left_out {
            if !plan
                .passes
                .iter()
                .any(|pass| pass.stages.iter().any(|stage| stage.name == *name))
            {
                return Err(format!(
                    "the {} path has no stage `{name}`",
                    tile.path.name()
                ));
            }
        }
        for pass in &mut plan.passes {
            let stages = &pass.stages;
            pass.draws
                .retain(|(stage, _)| !left_out.contains(&stages[*stage].name));
        }
        Ok(TimedFrame {
            renderer: self,
            plan,
        })
    }

    /// The checked plan of a configuration.
    fn plan(&self, tile: &TileOptions) -> Result<Plan, String> {
        let options = &tile.options;
        let layout = tile_layout(options)?;
        match tile.path {
            Path::Subpass => self.fused_plan(
                options,
                layout,
                Fused::Subpass {
                    store_gbuffer: false,
                },
            ),
            Path::LocalRead => self.fused_plan(
                options,
                layout,
                Fused::LocalRead {
                    rasterization_order: false,
                },
            ),
            Path::LocalReadOrdered => self.fused_plan(
                options,
                layout,
                Fused::LocalRead {
                    rasterization_order: true,
                },
            ),
            Path::TwoPass => self.two_pass_plan(options),
            other => Err(format!(
                "--path {} is GLES's: use --backend gles",
                other.name()
            )),
        }
    }

    /// The packed words the geometry writes (a debug view: the G-buffer stored, before decals
    /// and light), `layout.words()` per pixel, row by row.
    pub fn gbuffer_words(&self, options: &Options) -> Result<Vec<u32>, String> {
        let layout = tile_layout(options)?;
        let plan = self.fused_plan(
            options,
            layout,
            Fused::Subpass {
                store_gbuffer: true,
            },
        )?;
        self.submit_frame(&plan, &mut Recording::default())?;
        let targets = plan
            .gbuffer
            .iter()
            .map(|(_, buffer)| self.vulkan.read_buffer(buffer))
            .collect::<Result<Vec<_>, String>>()?;
        Ok(crate::gbuffers::texels_of(
            &targets,
            (plan.width * plan.height) as usize,
            layout.layout().words(),
        ))
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
                    let area = vk::Rect2D {
                        offset: vk::Offset2D::default(),
                        extent,
                    };
                    match &pass.begin {
                        Begin::RenderPass {
                            render_pass,
                            framebuffer,
                        } => device.cmd_begin_render_pass(
                            commands,
                            &vk::RenderPassBeginInfo::default()
                                .render_pass(*render_pass)
                                .framebuffer(*framebuffer)
                                .render_area(area)
                                .clear_values(&pass.clears),
                            vk::SubpassContents::INLINE,
                        ),
                        Begin::Rendering(rendering) => {
                            begin_rendering(device, commands, rendering, &pass.clears, area)
                        }
                    }
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
                        if previous.is_some() && pass.stages[stage].reads_earlier_draws {
                            // The draw reads what the draws before it wrote (the
                            // self-dependency); one that reads nothing of theirs needs none.
                            feedback_barrier(device, commands);
                            recording.push(Call::Barrier);
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
                    match &pass.begin {
                        Begin::RenderPass { .. } => device.cmd_end_render_pass(commands),
                        Begin::Rendering(rendering) => {
                            device.cmd_end_rendering(commands);
                            // As the render pass's dependency to the copy does: the output,
                            // written, becomes the copy's source.
                            let written =
                                (vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL, COLOUR_WRITES);
                            let copied = (
                                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                                (
                                    vk::AccessFlags::TRANSFER_READ,
                                    vk::PipelineStageFlags::TRANSFER,
                                ),
                            );
                            let output = rendering.attachments.colour_formats.len() - 1;
                            colour_transition(rendering.images[output])
                                .record(device, commands, written, copied);
                        }
                    }
                    recording.push(Call::EndPass {
                        stored: pass
                            .attachments
                            .iter()
                            .filter(|(_, stored)| *stored)
                            .map(|(attachment, _)| attachment.name.clone())
                            .collect(),
                    });
                }
                let whole_image = [vk::BufferImageCopy::default()
                    .image_subresource(color_layers(0))
                    .image_extent(vk::Extent3D {
                        width: plan.width,
                        height: plan.height,
                        depth: 1,
                    })];
                let source = vk::ImageLayout::TRANSFER_SRC_OPTIMAL;
                let read_backs = std::iter::once((plan.output, &plan.read_back))
                    .chain(plan.gbuffer.iter().map(|(image, buffer)| (*image, buffer)));
                for (image, buffer) in read_backs {
                    device.cmd_copy_image_to_buffer(
                        commands,
                        image,
                        source,
                        buffer.buffer,
                        &whole_image,
                    );
                }
                let copies = (
                    vk::AccessFlags::TRANSFER_WRITE,
                    vk::PipelineStageFlags::TRANSFER,
                );
                host_read_barrier(device, commands, copies);
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
                let transition = ImageTransition { image, range };
                let transfer = (
                    vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                    (
                        vk::AccessFlags::TRANSFER_WRITE,
                        vk::PipelineStageFlags::TRANSFER,
                    ),
                );
                let nothing = (
                    vk::AccessFlags::empty(),
                    vk::PipelineStageFlags::TOP_OF_PIPE,
                );
                let undefined = (vk::ImageLayout::UNDEFINED, nothing);
                transition.record(device, commands, undefined, transfer);
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
                let sampling = (
                    vk::AccessFlags::SHADER_READ,
                    vk::PipelineStageFlags::FRAGMENT_SHADER,
                );
                let read_only = (vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL, sampling);
                transition.record(device, commands, transfer, read_only);
            }
        })?;
        Ok(view)
    }
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

/// A frame ready to time ([`VulkanRenderer::timed_frame`]).
pub struct TimedFrame<'a> {
    renderer: &'a VulkanRenderer,
    plan: Plan,
}

impl TimedFrame<'_> {
    /// One frame's seconds, by the wall clock around its submit and wait.
    pub fn seconds(&self) -> Result<f64, String> {
        let start = Instant::now();
        self.renderer
            .submit_frame(&self.plan, &mut Recording::default())?;
        Ok(start.elapsed().as_secs_f64())
    }
}
