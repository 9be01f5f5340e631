//! The three passes of one configuration on wgpu: the G-buffer, the lighting (with the point
//! lights' volumes) and the tone mapping, their targets, pipelines and bindings, and how a frame
//! encodes them.

use gbuffer_solver::Feature;

use crate::gbuffers::GBuffer;
use crate::options::Options;
use crate::recording::{Attachment, Call, Load, Recording};
use crate::scene::POINT_LIGHT_COUNT;
use crate::shaders::{
    self, gbuffer_wgsl, lighting_pass_wgsl, tonemap_wgsl, Positions, CLAMPED_SAMPLER_BINDING,
    ENVIRONMENT_BINDING, ENVIRONMENT_SAMPLER_BINDING, GBUFFER_FIRST_BINDING,
};

use super::{Renderer, DEPTH_FORMAT, HDR_FORMAT};

/// The three passes of one configuration, with their targets.
pub(super) struct Passes {
    /// The point lights' volumes: their pipeline and bindings (seed and classic layouts; a
    /// solved layout's lighting function loops over its lights).
    pub(super) point_lights: Option<(wgpu::RenderPipeline, wgpu::BindGroup)>,
    /// The G-buffer targets as the recording names them, with their bytes per pixel.
    pub(super) gbuffer_attachments: Vec<Attachment>,
    /// What the lighting pass samples of the frame (the G-buffer, the depth buffer).
    pub(super) lighting_samples: Vec<Attachment>,
    pub(super) gbuffer_views: Vec<wgpu::TextureView>,
    pub(super) gbuffer_clear: Vec<wgpu::Color>,
    pub(super) depth_view: wgpu::TextureView,
    pub(super) hdr_view: wgpu::TextureView,
    pub(super) output: wgpu::Texture,
    pub(super) output_view: wgpu::TextureView,
    pub(super) gbuffer: wgpu::RenderPipeline,
    pub(super) lighting: wgpu::RenderPipeline,
    pub(super) tonemap: wgpu::RenderPipeline,
    pub(super) gbuffer_bindings: wgpu::BindGroup,
    pub(super) lighting_bindings: wgpu::BindGroup,
    pub(super) tonemap_bindings: wgpu::BindGroup,
}

/// The vertex buffer's layout: position, normal, object (`mesh::Vertex`).
pub const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Uint32];

impl Passes {
    /// The passes of a frame, the lighting reading positions from `positions`.
    pub(super) fn new(renderer: &Renderer, options: &Options, positions: Positions) -> Passes {
        let device = &renderer.device;
        let size = wgpu::Extent3d {
            width: options.width,
            height: options.height,
            depth_or_array_layers: 1,
        };
        let target = |label: &str, format: wgpu::TextureFormat, usage: wgpu::TextureUsages| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        // The G-buffer and the depth buffer are read back by the lighting pass as textures
        // (wgpu has no framebuffer fetch), so they are real attachments here: this is the round
        // trip through memory that the on-tile paths avoid.
        let read_back_usage =
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        let view = |texture: &wgpu::Texture| texture.create_view(&Default::default());
        let gbuffer_views: Vec<wgpu::TextureView> = match options.gbuffer.layout() {
            // A packed layout's targets, as the library's wgpu helpers make them.
            Some(layout) => {
                gbuffer_runtime::targets::create_targets(
                    device,
                    &layout,
                    options.width,
                    options.height,
                    wgpu::TextureUsages::empty(),
                )
                .views
            }
            None => options
                .gbuffer
                .target_formats()
                .into_iter()
                .map(|format| view(&target("gbuffer", format, read_back_usage)))
                .collect(),
        };
        // Sky pixels keep the clear value: all ones in the packed words, zero alpha in the
        // classic light target; the lighting pass draws the sky there.
        let all_ones = f64::from(u32::MAX);
        let sky = match options.gbuffer {
            GBuffer::Classic => wgpu::Color::TRANSPARENT,
            _ => wgpu::Color {
                r: all_ones,
                g: all_ones,
                b: all_ones,
                a: all_ones,
            },
        };
        let gbuffer_clear = vec![sky; gbuffer_views.len()];
        let depth_view = view(&target("depth", DEPTH_FORMAT, read_back_usage));
        let hdr_view = view(&target("hdr", HDR_FORMAT, read_back_usage));
        let output = target(
            "output",
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let output_view = view(&output);

        let pipeline = |label, source, entries, formats: &[wgpu::TextureFormat], geometry| {
            renderer.render_pipeline(label, source, entries, formats, (geometry, false))
        };
        let gbuffer = pipeline(
            "gbuffer",
            gbuffer_wgsl(options, 1.0),
            ("geometry_vertex", "gbuffer_main"),
            &options.gbuffer.target_formats(),
            true,
        );
        let lighting_source = lighting_pass_wgsl(options, positions)
            .expect("Renderer::positions chose positions the layout has");
        let lighting_bindings_used = shaders::used_bindings(&lighting_source, "lighting_main");
        // Seed and classic layouts draw the point lights as volumes (a solved layout's lighting
        // function loops over its lights): the pipeline, and the bindings it reads.
        let point_lights = (options.gbuffer.features().contains(Feature::PointLights)
            && !matches!(options.gbuffer, GBuffer::Solved(_)))
        .then(|| {
            let pipeline = renderer.render_pipeline(
                "point lights",
                lighting_source.clone(),
                ("light_volume_vertex", "point_light_main"),
                &[HDR_FORMAT],
                (false, true),
            );
            let used = shaders::used_bindings(&lighting_source, "point_light_main");
            (pipeline, used)
        });
        let lighting = pipeline(
            "lighting",
            lighting_source,
            ("full_screen", "lighting_main"),
            &[HDR_FORMAT],
            false,
        );
        let tonemap = pipeline(
            "tonemap",
            tonemap_wgsl(),
            ("full_screen", "tonemap_main"),
            &[wgpu::TextureFormat::Rgba8Unorm],
            false,
        );

        let texture = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let sampler = |binding, sampler| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::Sampler(sampler),
        };
        let clamped_sampler = sampler(CLAMPED_SAMPLER_BINDING, &renderer.clamped_sampler);
        let gbuffer_bindings = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &gbuffer.get_bind_group_layout(0),
            entries: &[clamped_sampler.clone(), texture(5, &renderer.light_map)],
        });
        let mut entries = vec![
            texture(ENVIRONMENT_BINDING, &renderer.environment),
            texture(2, &renderer.lut),
            sampler(ENVIRONMENT_SAMPLER_BINDING, &renderer.environment_sampler),
            texture(4, &depth_view),
            clamped_sampler,
        ];
        for (index, target_view) in gbuffer_views.iter().enumerate() {
            entries.push(texture(GBUFFER_FIRST_BINDING + index as u32, target_view));
        }
        // The pass binds only what its forms and terms read.
        let all_entries = entries.clone();
        entries.retain(|entry| lighting_bindings_used.contains(&entry.binding));
        let lighting_bindings = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &lighting.get_bind_group_layout(0),
            entries: &entries,
        });
        // The light volumes read what the lighting pass reads, less what their forms skip.
        let mut sampled = lighting_bindings_used.clone();
        let point_lights = point_lights.map(|(pipeline, used)| {
            sampled.extend(&used);
            let entries: Vec<wgpu::BindGroupEntry> = all_entries
                .iter()
                .filter(|entry| used.contains(&entry.binding))
                .cloned()
                .collect();
            let bindings = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: None,
                layout: &pipeline.get_bind_group_layout(0),
                entries: &entries,
            });
            (pipeline, bindings)
        });
        let tonemap_bindings = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &tonemap.get_bind_group_layout(0),
            entries: &[texture(0, &hdr_view)],
        });
        let gbuffer_attachments: Vec<Attachment> = options
            .gbuffer
            .target_formats()
            .iter()
            .enumerate()
            .map(|(index, format)| Attachment {
                name: format!("gbuffer{index}"),
                bytes_per_pixel: format.block_copy_size(None).unwrap_or(0),
            })
            .collect();
        let depth_attachment = Attachment {
            name: "depth".into(),
            bytes_per_pixel: 4,
        };
        sampled.sort_unstable();
        sampled.dedup();
        let lighting_samples = sampled
            .iter()
            .filter_map(|&binding| match binding {
                4 => Some(depth_attachment.clone()),
                10.. => gbuffer_attachments.get(binding as usize - 10).cloned(),
                _ => None,
            })
            .collect();
        Passes {
            point_lights,
            gbuffer_attachments,
            lighting_samples,
            gbuffer_views,
            gbuffer_clear,
            depth_view,
            hdr_view,
            output,
            output_view,
            gbuffer,
            lighting,
            tonemap,
            gbuffer_bindings,
            lighting_bindings,
            tonemap_bindings,
        }
    }

    /// The frame's commands, and in `recording` the passes they make (every attachment is
    /// cleared and stored); with a query set, a timestamp at the start of the G-buffer pass
    /// (query 0) and at the end of the tone-mapping pass (query 1).
    pub(super) fn encode(
        &self,
        renderer: &Renderer,
        timestamps: Option<&wgpu::QuerySet>,
        recording: &mut Recording,
    ) -> wgpu::CommandBuffer {
        let named = |name: &str, bytes_per_pixel| Attachment {
            name: name.into(),
            bytes_per_pixel,
        };
        let mut gbuffer_pass: Vec<Attachment> = self.gbuffer_attachments.clone();
        gbuffer_pass.push(named("depth", 4));
        let passes = [
            (gbuffer_pass, "gbuffer", Vec::new()),
            (
                vec![named("hdr", 8)],
                "lighting",
                self.lighting_samples.clone(),
            ),
            (vec![named("output", 4)], "tonemap", vec![named("hdr", 8)]),
        ];
        for (attachments, program, samples) in passes {
            recording.push(Call::BeginPass {
                attachments: attachments
                    .iter()
                    .map(|attachment| (attachment.clone(), Load::Clear))
                    .collect(),
            });
            for sample in samples {
                recording.push(Call::Sample(sample));
            }
            recording.push(Call::Draw {
                program: program.into(),
            });
            if program == "lighting" && self.point_lights.is_some() {
                for _ in 0..POINT_LIGHT_COUNT {
                    recording.push(Call::Draw {
                        program: "point light".into(),
                    });
                }
            }
            recording.push(Call::EndPass {
                stored: attachments
                    .into_iter()
                    .map(|attachment| attachment.name)
                    .collect(),
            });
        }
        let mut encoder = renderer.device.create_command_encoder(&Default::default());
        fn attachment(
            view: &wgpu::TextureView,
            clear: wgpu::Color,
        ) -> Option<wgpu::RenderPassColorAttachment<'_>> {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear),
                    store: wgpu::StoreOp::Store,
                },
            })
        }
        let at = |beginning: Option<u32>, end: Option<u32>| {
            timestamps.map(|query_set| wgpu::RenderPassTimestampWrites {
                query_set,
                beginning_of_pass_write_index: beginning,
                end_of_pass_write_index: end,
            })
        };
        {
            let attachments: Vec<_> = self
                .gbuffer_views
                .iter()
                .zip(&self.gbuffer_clear)
                .map(|(view, clear)| attachment(view, *clear))
                .collect();
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("gbuffer"),
                color_attachments: &attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: at(Some(0), None),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.gbuffer);
            pass.set_bind_group(0, &self.gbuffer_bindings, &[]);
            pass.set_vertex_buffer(0, renderer.vertices.slice(..));
            pass.set_index_buffer(renderer.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..renderer.index_count, 0, 0..1);
        }
        let fullscreen = |encoder: &mut wgpu::CommandEncoder,
                          view: &wgpu::TextureView,
                          (pipeline, bindings): (&wgpu::RenderPipeline, &wgpu::BindGroup),
                          volumes: Option<&(wgpu::RenderPipeline, wgpu::BindGroup)>,
                          timestamp_writes| {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &[attachment(view, wgpu::Color::BLACK)],
                depth_stencil_attachment: None,
                timestamp_writes,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bindings, &[]);
            pass.draw(0..3, 0..1);
            if let Some((pipeline, bindings)) = volumes {
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, bindings, &[]);
                for light in 0..POINT_LIGHT_COUNT as u32 {
                    pass.draw(0..6, light..light + 1);
                }
            }
        };
        fullscreen(
            &mut encoder,
            &self.hdr_view,
            (&self.lighting, &self.lighting_bindings),
            self.point_lights.as_ref(),
            None,
        );
        fullscreen(
            &mut encoder,
            &self.output_view,
            (&self.tonemap, &self.tonemap_bindings),
            None,
            at(None, Some(1)),
        );
        encoder.finish()
    }
}
