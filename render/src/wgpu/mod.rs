//! The reference deferred renderer on wgpu, headless: the G-buffer round trip through memory,
//! as a renderer without framebuffer fetch has to do it.
//!
//! 0. once: the inputs are baked on the CPU (`inputs`) and uploaded, with the scene's mesh;
//! 1. the G-buffer pass rasterises the mesh with a depth test and writes the chosen layout
//!    (packed `Rgba32Uint` targets, or the classic native targets): the surface, the decals
//!    painted over it in the same fragment, its light accumulation holding the static light;
//! 2. the lighting pass unpacks with the generated WGSL and shades with the shading library:
//!    the image-based light, the sun, and the point lights in a loop at the position the depth
//!    buffer gives;
//! 3. the tone-mapping pass writes sRGB.
//!
//! The GLES and Vulkan backends (`crate::gles`, `crate::vulkan`) draw the same frame, and on
//! their fused paths keep the G-buffer in the render pass.

mod passes;
mod textures;
pub use textures::texture_with_data;

use std::time::Instant;

use wgpu::util::DeviceExt;

use gbuffer_gpu::adapter::{Gpu, Request};

use crate::inputs::Inputs;
use crate::mesh::{Mesh, Vertex};
use crate::options::{Frame, Options};
use crate::recording::{Call, Recording};
use crate::shaders::{self, gbuffer_wgsl, Positions};

use gbuffer_gpu::timestamps::Timestamps;
use passes::{Passes, VERTEX_ATTRIBUTES};

const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The GPU side: device, the baked inputs and the scene's mesh.
pub struct Renderer {
    /// The device it renders with.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter it runs on.
    pub adapter: wgpu::AdapterInfo,
    environment: wgpu::TextureView,
    lut: wgpu::TextureView,
    light_map: wgpu::TextureView,
    /// Trilinear, wrapping around the sky in u.
    environment_sampler: wgpu::Sampler,
    /// Trilinear, clamped to the edges: the LUT and the light map.
    clamped_sampler: wgpu::Sampler,
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    timestamps: Option<Timestamps>,
}

impl Renderer {
    /// Opens an adapter (any wgpu finds, software ones included) and prepares the inputs,
    /// reporting progress.
    pub fn new(progress: &dyn Fn(&str)) -> Result<Renderer, String> {
        Renderer::with_request(
            &Request {
                label: "deferred",
                limits: None,
                features: wgpu::Features::TIMESTAMP_QUERY,
                backends: None,
            },
            progress,
        )
    }

    /// As [`Renderer::new`], on the device `request` asks for: a backend, limits to hold it
    /// to (WebGL2's: `wgpu::Limits::downlevel_webgl2_defaults()` on `wgpu::Backends::GL`).
    pub fn with_request(request: &Request, progress: &dyn Fn(&str)) -> Result<Renderer, String> {
        let Gpu {
            device,
            queue,
            info,
        } = Gpu::open(request)?;
        let timestamp_feature = device.features() & wgpu::Features::TIMESTAMP_QUERY;
        progress(&format!("adapter: {} ({:?})", info.name, info.backend));

        progress("baking the split-sum LUT, the light map and the prefiltered sky...");
        let inputs = Inputs::bake();
        let upload =
            |label, format, mips: &[_]| texture_with_data(&device, &queue, label, format, mips);
        let lut = upload("lut", wgpu::TextureFormat::Rgba16Float, &[inputs.lut]);
        let light_map = upload(
            "light map",
            wgpu::TextureFormat::Rgba8Unorm,
            &[inputs.light_map],
        );
        let environment = upload(
            "environment",
            wgpu::TextureFormat::Rgba8Unorm,
            &inputs.environment,
        );
        // Trilinear; the environment's wraps around the sky in u, the other clamps to the
        // edges (the LUT's n.v = 1 column must not blend with its n.v = 0 one).
        let sampler = |address_mode_u| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                address_mode_u,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                ..Default::default()
            })
        };
        let environment_sampler = sampler(wgpu::AddressMode::Repeat);
        let clamped_sampler = sampler(wgpu::AddressMode::ClampToEdge);
        let mesh = Mesh::scene();
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("vertices"),
            contents: bytemuck::cast_slice(&mesh.vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("indices"),
            contents: bytemuck::cast_slice(&mesh.indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        let timestamps = (!timestamp_feature.is_empty()).then(|| Timestamps::new(&device, "frame"));
        Ok(Renderer {
            device,
            queue,
            adapter: info,
            environment,
            lut,
            light_map,
            environment_sampler,
            clamped_sampler,
            vertices,
            indices,
            index_count: mesh.indices.len() as u32,
            timestamps,
        })
    }

    /// Renders a frame and reads it back.
    pub fn render(&self, options: &Options) -> Result<Frame, String> {
        self.render_recorded(options).map(|(frame, _)| frame)
    }

    /// Renders a frame and reads it back, with the passes it made.
    pub fn render_recorded(&self, options: &Options) -> Result<(Frame, Recording), String> {
        let passes = self.passes(options)?;
        let mut recording = Recording::default();
        self.queue
            .submit([passes.encode(self, None, &mut recording)]);
        recording.push(Call::ReadBack("output".into()));
        let pixels = self
            .read_texture(&passes.output, options.width, options.height, 4)?
            .chunks_exact(4)
            .map(|pixel| [pixel[0], pixel[1], pixel[2], pixel[3]])
            .collect();
        let frame = Frame {
            width: options.width,
            height: options.height,
            pixels,
        };
        Ok((frame, recording))
    }

    /// Whether frame times come from timestamp queries (else wall clock around the submit).
    pub fn has_timestamps(&self) -> bool {
        self.timestamps.is_some()
    }

    /// A frame of `options` ready to time: its passes built once, each
    /// [`TimedFrame::seconds`] one frame submitted and waited for. The protocol around it
    /// (warm-up, rounds) is `gbuffer_gpu::timing`'s.
    pub fn timed_frame(&self, options: &Options) -> Result<TimedFrame<'_>, String> {
        Ok(TimedFrame {
            renderer: self,
            passes: self.passes(options)?,
        })
    }

    /// A render pipeline of `source`'s entry points (vertex, fragment) writing `formats`;
    /// `geometry` draws the mesh with a depth test, else vertices without buffers (a
    /// fullscreen triangle, a light volume); `additive` blends what it writes onto the target.
    fn render_pipeline(
        &self,
        label: &str,
        source: String,
        (vertex_entry, fragment_entry): (&str, &str),
        formats: &[wgpu::TextureFormat],
        (geometry, additive): (bool, bool),
    ) -> wgpu::RenderPipeline {
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        let add = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let targets: Vec<Option<wgpu::ColorTargetState>> = formats
            .iter()
            .map(|&format| {
                Some(wgpu::ColorTargetState {
                    format,
                    blend: additive.then_some(wgpu::BlendState {
                        color: add,
                        alpha: add,
                    }),
                    write_mask: wgpu::ColorWrites::ALL,
                })
            })
            .collect();
        let vertex_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &VERTEX_ATTRIBUTES,
        })];
        self.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: None,
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vertex_entry),
                    compilation_options: Default::default(),
                    buffers: if geometry { &vertex_buffers } else { &[] },
                },
                primitive: Default::default(),
                depth_stencil: geometry.then_some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(fragment_entry),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
    }

    /// The packed words the G-buffer pass writes before the decals (a debug view, stored to
    /// compare the backends), `layout.words()` per pixel, row by row.
    pub fn gbuffer_words(&self, options: &Options) -> Result<Vec<u32>, String> {
        let layout = options
            .gbuffer
            .layout()
            .ok_or("the classic G-buffer has no packed words")?;
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let formats = options.gbuffer.target_formats();
        let pipeline = self.render_pipeline(
            "gbuffer words",
            gbuffer_wgsl(options, 1.0),
            ("geometry_vertex", "gbuffer_unpainted_main"),
            &formats,
            (true, false),
        );
        // The layout's targets as the library makes them, copied out afterwards.
        let targets = gbuffer_runtime::targets::create_targets(
            &self.device,
            &layout,
            options.width,
            options.height,
            wgpu::TextureUsages::COPY_SRC,
        );
        let depth = self
            .device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("gbuffer words depth"),
                size: wgpu::Extent3d {
                    width: options.width,
                    height: options.height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: DEPTH_FORMAT,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                view_formats: &[],
            })
            .create_view(&Default::default());
        let bindings = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: shaders::CLAMPED_SAMPLER_BINDING,
                    resource: wgpu::BindingResource::Sampler(&self.clamped_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: wgpu::BindingResource::TextureView(&self.light_map),
                },
            ],
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let attachments = targets.color_attachments(wgpu::Color::TRANSPARENT);
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("gbuffer words"),
                color_attachments: &attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bindings, &[]);
            pass.set_vertex_buffer(0, self.vertices.slice(..));
            pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..self.index_count, 0, 0..1);
        }
        self.queue.submit([encoder.finish()]);
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(format!("wgpu rejected the G-buffer words pass: {error}"));
        }
        let per_target: Vec<Vec<u32>> = targets
            .textures
            .iter()
            .map(|target| {
                let bytes = target.format().block_copy_size(None).unwrap_or(16);
                let texels = self.read_texture(target, options.width, options.height, bytes)?;
                Ok(bytemuck::pod_collect_to_vec(&texels))
            })
            .collect::<Result<_, String>>()?;
        Ok(crate::gbuffers::texels_of(
            &per_target,
            (options.width * options.height) as usize,
            layout.words(),
        ))
    }

    /// The passes of a frame, or why this device cannot make them: what the backend lacks, or
    /// what wgpu rejected (a validation or internal error, caught rather than left to panic).
    fn passes(&self, options: &Options) -> Result<Passes, String> {
        let positions = self.positions(options)?;
        let internal = self.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let passes = Passes::new(self, options, positions);
        let errors = [
            pollster::block_on(validation.pop()),
            pollster::block_on(internal.pop()),
        ];
        match errors.into_iter().flatten().next() {
            Some(error) => Err(format!(
                "wgpu rejected the passes for {} on {} ({:?}): {error}",
                options.gbuffer.name(),
                self.adapter.name,
                self.adapter.backend
            )),
            None => Ok(passes),
        }
    }

    /// Where the lighting pass finds positions: the depth buffer, except on the GL backend,
    /// whose GLSL (GLSL ES 3.00 on WebGL2) cannot load from a depth texture; there, from the
    /// texel of a layout that stores depth or position, and no other layout can render.
    fn positions(&self, options: &Options) -> Result<Positions, String> {
        if self.adapter.backend != wgpu::Backend::Gl {
            return Ok(Positions::DepthBuffer);
        }
        let texel_position = match options.gbuffer.packed_layout() {
            Some(layout) => layout.texel_position_wgsl().map(|_| ()),
            None => Err("its G-buffer is not one of the packed layouts".to_string()),
        };
        texel_position.map(|()| Positions::Texel).map_err(|reason| {
            format!(
                "`{}` cannot render on wgpu's GL backend: GLSL (GLSL ES 3.00 on WebGL2) cannot \
                 load from a depth texture, so the point lights take positions from the \
                 G-buffer's texel, and {reason}",
                options.gbuffer.name()
            )
        })
    }
}

/// A frame ready to time ([`Renderer::timed_frame`]).
pub struct TimedFrame<'a> {
    renderer: &'a Renderer,
    passes: Passes,
}

impl TimedFrame<'_> {
    /// One frame's seconds: from timestamp queries around its passes where the adapter has
    /// them, else from the wall clock around the submit and its wait.
    pub fn seconds(&self) -> Result<f64, String> {
        let renderer = self.renderer;
        let commands = self.passes.encode(
            renderer,
            renderer
                .timestamps
                .as_ref()
                .map(|timestamps| &timestamps.query_set),
            &mut Recording::default(),
        );
        let start = Instant::now();
        renderer.queue.submit([commands]);
        renderer
            .device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| error.to_string())?;
        let wall_clock = start.elapsed().as_secs_f64();
        match &renderer.timestamps {
            Some(timestamps) => {
                let mut encoder = renderer.device.create_command_encoder(&Default::default());
                timestamps.resolve(&mut encoder);
                renderer.queue.submit([encoder.finish()]);
                timestamps.seconds(&renderer.device, &renderer.queue)
            }
            None => Ok(wall_clock),
        }
    }
}
