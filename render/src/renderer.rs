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
//! The on-tile paths (`crate::on_tile`) draw the same frame with the G-buffer kept in the
//! render pass.

use std::time::Instant;

use wgpu::util::DeviceExt;

use gbuffer::packing::Layout;
use gbuffer_gpu::adapter::{Gpu, Request};
use gbuffer_gpu::fullscreen::FULLSCREEN_WGSL;
use gbuffer_solver::lighting::{self, Forms};
use gbuffer_solver::quantity::Quantity;
use gbuffer_solver::{Feature, Solution};

use crate::gbuffers::GBuffer;
use crate::inputs::{Inputs, Texels};
use crate::mesh::{Mesh, Vertex};
use crate::on_tile::recording::{Attachment, Call, Load, Recording};
use crate::scene::{self, POINT_LIGHT_COUNT};
use crate::shaders::{self, library, INPUTS_WGSL, VOLUME_WGSL};
use gbuffer::seed_conventions::SURFACE_WGSL;

pub use gbuffer_solver::lighting::{IblForm, SunForm};

/// A frame size from the command line: `WIDTHxHEIGHT`, each between 1 and 8192.
pub fn parse_size(size: &str) -> Result<(u32, u32), String> {
    size.split_once('x')
        .and_then(|(width, height)| Some((width.parse::<u32>().ok()?, height.parse::<u32>().ok()?)))
        .filter(|&(width, height)| (1..=8192).contains(&width) && (1..=8192).contains(&height))
        .ok_or_else(|| {
            format!("bad size `{size}`: write WIDTHxHEIGHT, e.g. 1280x720 (at most 8192 each)")
        })
}

/// One configuration of the renderer. A solved G-buffer brings its scene description: the
/// scene shows its features, and the lighting pass is generated for them.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The G-buffer the frame goes through.
    pub gbuffer: GBuffer,
    /// The sun's specular form.
    pub sun: SunForm,
    /// The image-based light's form.
    pub ibl: IblForm,
    /// Frame width, pixels.
    pub width: u32,
    /// Frame height, pixels.
    pub height: u32,
}

/// A rendered frame: sRGB pixels, row by row.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// RGBA, 8 bits per channel, sRGB encoded.
    pub pixels: Vec<[u8; 4]>,
}

/// Exposure before tone mapping.
pub const EXPOSURE: f64 = 0.7;
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
    sampler: wgpu::Sampler,
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    timestamps: Option<Timestamps>,
}

/// Two timestamp queries around a frame and the buffers that read them back.
struct Timestamps {
    query_set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read_back: wgpu::Buffer,
}

impl Timestamps {
    fn new(device: &wgpu::Device) -> Self {
        let buffer = |usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: 16,
                usage,
                mapped_at_creation: false,
            })
        };
        Timestamps {
            query_set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolve: buffer(wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            read_back: buffer(wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ),
        }
    }

    /// The seconds between the two timestamps of the last frame.
    fn read(&self, renderer: &Renderer) -> Result<f64, String> {
        let mut encoder = renderer.device.create_command_encoder(&Default::default());
        encoder.resolve_query_set(&self.query_set, 0..2, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read_back, 0, 16);
        renderer.queue.submit([encoder.finish()]);
        let slice = self.read_back.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        renderer
            .device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| error.to_string())?;
        let ticks: [u64; 2] = {
            let view = slice
                .get_mapped_range()
                .map_err(|error| error.to_string())?;
            bytemuck::pod_read_unaligned(&view[..16])
        };
        self.read_back.unmap();
        Ok(ticks[1].saturating_sub(ticks[0]) as f64
            * f64::from(renderer.queue.get_timestamp_period())
            * 1e-9)
    }
}

impl Renderer {
    /// Opens an adapter (any wgpu finds, software ones included) and prepares the inputs,
    /// reporting progress.
    pub fn new(progress: &dyn Fn(&str)) -> Result<Renderer, String> {
        let Gpu {
            device,
            queue,
            info,
        } = Gpu::open(&Request {
            label: "deferred",
            limits: None,
            features: wgpu::Features::TIMESTAMP_QUERY,
        })?;
        let timestamp_feature = device.features() & wgpu::Features::TIMESTAMP_QUERY;
        progress(&format!("adapter: {} ({:?})", info.name, info.backend));

        progress("baking the split-sum LUT, the light map and the prefiltered sky...");
        let inputs = Inputs::bake();
        let lut = texture_with_data(
            &device,
            &queue,
            "lut",
            wgpu::TextureFormat::Rgba16Float,
            &[inputs.lut],
        );
        let light_map = texture_with_data(
            &device,
            &queue,
            "light map",
            wgpu::TextureFormat::Rgba8Unorm,
            &[inputs.light_map],
        );
        let environment = texture_with_data(
            &device,
            &queue,
            "environment",
            wgpu::TextureFormat::Rgba8Unorm,
            &inputs.environment,
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            address_mode_u: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
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
        let timestamps = (!timestamp_feature.is_empty()).then(|| Timestamps::new(&device));
        Ok(Renderer {
            device,
            queue,
            adapter: info,
            environment,
            lut,
            light_map,
            sampler,
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

    /// Times `frames` frames, each submitted and waited for: seconds per frame, from timestamp
    /// queries where the adapter has them, else from the wall clock around the submit.
    pub fn time_frames(&self, options: &Options, frames: usize) -> Result<Vec<f64>, String> {
        let passes = self.passes(options)?;
        let mut times = Vec::with_capacity(frames);
        for _ in 0..=frames {
            let commands = passes.encode(
                self,
                self.timestamps
                    .as_ref()
                    .map(|timestamps| &timestamps.query_set),
                &mut Recording::default(),
            );
            let start = Instant::now();
            self.queue.submit([commands]);
            self.device
                .poll(wgpu::PollType::wait_indefinitely())
                .map_err(|error| error.to_string())?;
            let wall_clock = start.elapsed().as_secs_f64();
            times.push(match &self.timestamps {
                Some(timestamps) => timestamps.read(self)?,
                None => wall_clock,
            });
        }
        times.remove(0); // the first frame warms caches and compiles lazily
        Ok(times)
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
        let texture = |format| {
            self.device.create_texture(&wgpu::TextureDescriptor {
                label: None,
                size: wgpu::Extent3d {
                    width: options.width,
                    height: options.height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        let targets: Vec<wgpu::Texture> = formats.iter().map(|format| texture(*format)).collect();
        let views: Vec<wgpu::TextureView> = targets
            .iter()
            .map(|target| target.create_view(&Default::default()))
            .collect();
        let depth = texture(DEPTH_FORMAT).create_view(&Default::default());
        let bindings = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: shaders::SAMPLER_BINDING,
                    resource: wgpu::BindingResource::Sampler(&self.sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: wgpu::BindingResource::TextureView(&self.light_map),
                },
            ],
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let attachments: Vec<_> = views
                .iter()
                .map(|view| {
                    Some(wgpu::RenderPassColorAttachment {
                        view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                            store: wgpu::StoreOp::Store,
                        },
                    })
                })
                .collect();
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
            .iter()
            .zip(&formats)
            .map(|(target, format)| {
                let bytes = format.block_copy_size(None).unwrap_or(16);
                let texels = self.read_texture(target, options.width, options.height, bytes)?;
                Ok(bytemuck::pod_collect_to_vec(&texels))
            })
            .collect::<Result<_, String>>()?;
        Ok(texels_of(
            &per_target,
            (options.width * options.height) as usize,
            layout.words(),
        ))
    }

    fn passes(&self, options: &Options) -> Result<Passes, String> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let passes = Passes::new(self, options);
        match pollster::block_on(scope.pop()) {
            Some(error) => Err(format!(
                "wgpu rejected the passes for {}: {error}",
                options.gbuffer.name()
            )),
            None => Ok(passes),
        }
    }

    /// The texels of `texture` (`bytes_per_pixel` each), row by row, tightly packed.
    fn read_texture(
        &self,
        texture: &wgpu::Texture,
        width: u32,
        height: u32,
        bytes_per_pixel: u32,
    ) -> Result<Vec<u8>, String> {
        let row_bytes =
            (width * bytes_per_pixel).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: u64::from(row_bytes * height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row_bytes),
                    rows_per_image: None,
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        let slice = buffer.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| error.to_string())?;
        let view = slice
            .get_mapped_range()
            .map_err(|error| error.to_string())?;
        Ok((0..height)
            .flat_map(|row| {
                view[(row * row_bytes) as usize..][..(width * bytes_per_pixel) as usize].to_vec()
            })
            .collect())
    }
}

/// Per pixel, the first `words` words of its texels in `targets` (each target's words for all
/// pixels, row by row), in target order.
pub fn texels_of(targets: &[Vec<u32>], pixels: usize, words: usize) -> Vec<u32> {
    let mut texels = Vec::with_capacity(pixels * words);
    for pixel in 0..pixels {
        let texel: Vec<u32> = targets
            .iter()
            .flat_map(|target| {
                let per_pixel = target.len() / pixels;
                target[pixel * per_pixel..(pixel + 1) * per_pixel]
                    .iter()
                    .copied()
            })
            .collect();
        texels.extend_from_slice(&texel[..words]);
    }
    texels
}

/// A sampled texture of `mips` (largest first), uploaded.
fn texture_with_data(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    format: wgpu::TextureFormat,
    mips: &[Texels],
) -> wgpu::TextureView {
    let bytes: Vec<u8> = mips
        .iter()
        .flat_map(|mip| mip.bytes.iter().copied())
        .collect();
    device
        .create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: mips[0].width,
                    height: mips[0].height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: mips.len() as u32,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            &bytes,
        )
        .create_view(&Default::default())
}

/// The three passes of one configuration, with their targets.
struct Passes {
    /// The point lights' volumes: their pipeline and bindings (seed and classic layouts; a
    /// solved layout's lighting function loops over its lights).
    point_lights: Option<(wgpu::RenderPipeline, wgpu::BindGroup)>,
    /// The G-buffer targets as the recording names them, with their bytes per pixel.
    gbuffer_attachments: Vec<Attachment>,
    /// What the lighting pass samples of the frame (the G-buffer, the depth buffer).
    lighting_samples: Vec<Attachment>,
    gbuffer_views: Vec<wgpu::TextureView>,
    gbuffer_clear: Vec<wgpu::Color>,
    depth_view: wgpu::TextureView,
    hdr_view: wgpu::TextureView,
    output: wgpu::Texture,
    output_view: wgpu::TextureView,
    gbuffer: wgpu::RenderPipeline,
    lighting: wgpu::RenderPipeline,
    tonemap: wgpu::RenderPipeline,
    gbuffer_bindings: wgpu::BindGroup,
    lighting_bindings: wgpu::BindGroup,
    tonemap_bindings: wgpu::BindGroup,
}

/// The G-buffer pass's last statement for a packed layout and the type it returns:
/// `<Name>Targets`. Sky pixels keep the clear value, all ones in every word.
fn write_packed_targets(layout: &Layout) -> (String, String) {
    let (name, snake) = (&layout.name, layout.snake_name());
    (
        format!("return pack_{snake}_targets(encode_texel(surface));"),
        format!("{name}Targets"),
    )
}

/// The lighting pass's bindings of a packed layout's targets (10, 11, ...) and the expression
/// that loads them at `pixel` as a `<Name>Targets`.
fn read_packed_targets(layout: &Layout) -> (String, String) {
    let bindings = (0..layout.targets())
        .map(|target| {
            format!(
                "@group(0) @binding({}) var gbuffer{target}: texture_2d<u32>;\n",
                10 + target
            )
        })
        .collect();
    let loads: Vec<String> = (0..layout.targets())
        .map(|target| format!("textureLoad(gbuffer{target}, pixel, 0)"))
        .collect();
    (
        bindings,
        format!("{}Targets({})", layout.name, loads.join(", ")),
    )
}

/// The G-buffer pass's WGSL for a configuration: `geometry_vertex`, and `gbuffer_main`, which
/// writes the surface with the decals painted over it. `y_sign` is the backend's clip-space y
/// (wgpu 1, GL and Vulkan -1).
pub fn gbuffer_wgsl(options: &Options, y_sign: f32) -> String {
    let (layout_wgsl, encode, output_type) = match &options.gbuffer {
        GBuffer::Packed(layout) => {
            let (encode, output_type) = write_packed_targets(&layout.layout());
            (
                format!("{}\n{}", layout.wgsl(), layout.encode_wgsl()),
                encode,
                output_type,
            )
        }
        GBuffer::Solved(solution) => {
            let (encode, output_type) = write_packed_targets(&solution.layout);
            (
                format!(
                    "{}\n{}",
                    gbuffer_solver::texel::texel_wgsl(solution),
                    solved_encode_wgsl(solution)
                ),
                encode,
                output_type,
            )
        }
        GBuffer::Classic => (
            "struct ClassicTargets {\n    @location(0) light: vec4<f32>,\n    @location(1) normal_roughness: vec4<f32>,\n    @location(2) base_colour_metallic: vec4<f32>,\n}\n".to_string(),
            "return ClassicTargets(vec4<f32>(surface.light, 1.0), vec4<f32>(normal_to_unorm(surface.normal), surface.roughness), vec4<f32>(surface.base_colour, surface.metallic));".to_string(),
            "ClassicTargets".to_string(),
        ),
    };
    format!(
        "{}\n{}\n{}\n{INPUTS_WGSL}\n{layout_wgsl}

@fragment
fn gbuffer_main(input: GeometryVarying) -> {output_type} {{
    let surface = paint_surface(surface_at(input.object, input.position, input.normal));
    {encode}
}}

// The G-buffer as the geometry writes it before the decals: the debug view every backend
// stores, to compare their words.
@fragment
fn gbuffer_unpainted_main(input: GeometryVarying) -> {output_type} {{
    let surface = surface_at(input.object, input.position, input.normal);
    {encode}
}}
",
        library(&shaders::MODULES),
        shaders::frame_wgsl(options, y_sign),
        shaders::geometry_wgsl(options),
    )
}

/// Where the lighting pass finds the position of the surface at a pixel, for the point lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Positions {
    /// From the depth buffer, sampled (`surface_position(pixel, direction)`): any layout.
    DepthBuffer,
    /// From the texel's depth or position (`texel_position(texel, direction)`): the layouts
    /// the on-tile paths keep (GLSL cannot load from a depth texture).
    Texel,
}

/// What the lighting pass of a seed or classic layout shares: the library, the scene, the
/// inputs, and with positions from the depth buffer, the buffer and `surface_position`.
fn lighting_prelude(options: &Options, positions: Positions) -> String {
    let depth_buffer = match positions {
        Positions::Texel => "",
        Positions::DepthBuffer => DEPTH_BUFFER_WGSL,
    };
    format!(
        "{}\n{}\n{}\n{SURFACE_WGSL}\n{INPUTS_WGSL}\n{}\n{}\n{FULLSCREEN_WGSL}\n{depth_buffer}",
        library(&shaders::MODULES),
        shaders::frame_wgsl(options, 1.0),
        scene::scene_wgsl(options.gbuffer.features()),
        shaders::lighting_functions_wgsl(options),
        shaders::display_wgsl(),
    )
}

/// The depth buffer, and the position it gives the surface at a pixel.
const DEPTH_BUFFER_WGSL: &str = "
@group(0) @binding(4) var depth_buffer: texture_depth_2d;

// Where the surface at `pixel` lies: the depth buffer's depth along the camera ray.
fn surface_position(pixel: vec2<i32>, direction: vec3<f32>) -> vec3<f32> {
    let depth = textureLoad(depth_buffer, pixel, 0);
    let view_depth = CAMERA_NEAR / (1.0 - depth * (CAMERA_FAR - CAMERA_NEAR) / CAMERA_FAR);
    return SCENE_EYE + direction * (view_depth / dot(direction, normalize(SCENE_TARGET - SCENE_EYE)));
}
";

/// The lighting pass's WGSL for a configuration: `lighting_main` (radiance) and
/// `lighting_resolve_main` (tone-mapped), reading positions from `positions`.
pub fn lighting_pass_wgsl(options: &Options, positions: Positions) -> Result<String, String> {
    let (bindings, read) = match &options.gbuffer {
        GBuffer::Solved(solution) => return Ok(solved_lighting_wgsl(solution, options)),
        GBuffer::Packed(layout) => {
            let model = layout.layout();
            let (bindings, targets) = read_packed_targets(&model);
            let snake = model.snake_name();
            let texel_positions = match positions {
                Positions::Texel => layout.on_tile_wgsl()?,
                Positions::DepthBuffer => "",
            };
            (
                format!("{}\n{}\n{texel_positions}\n{bindings}", layout.wgsl(), layout.decode_wgsl()),
                format!("let targets = {targets};\n    if targets.first.x == 0xffffffffu {{\n        SKY\n    }}\n    let texel = unpack_{snake}_targets(targets);\n    let shading = decode_texel(texel);"),
            )
        }
        GBuffer::Classic => (
            "@group(0) @binding(10) var gbuffer_light: texture_2d<f32>;\n@group(0) @binding(11) var gbuffer_normal: texture_2d<f32>;\n@group(0) @binding(12) var gbuffer_colour: texture_2d<f32>;\n".to_string(),
            "let light = textureLoad(gbuffer_light, pixel, 0);\n    if light.a == 0.0 {\n        SKY\n    }\n    let normal_roughness = textureLoad(gbuffer_normal, pixel, 0);\n    let colour = textureLoad(gbuffer_colour, pixel, 0);\n    let colours = metallic_workflow(colour.rgb, colour.a, DIELECTRIC_F0);\n    let shading = Shading(unorm_to_normal(normal_roughness.xyz), normal_roughness.w, colours.diffuse, colours.f0, light.rgb);".to_string(),
        ),
    };
    // The texel at `pixel` as `shading`, and what a sky pixel does instead.
    let read = |sky: &str| read.replace("SKY", sky);
    Ok(format!(
        "{}\n{VOLUME_WGSL}\n{bindings}
// The image-based light and the sun at a pixel (the sky where there is no surface).
fn pixel_radiance(position: vec4<f32>) -> vec3<f32> {{
    let pixel = vec2<i32>(position.xy);
    let direction = camera_ray(position.xy, VIEWPORT);
    {read_radiance}
    let view = -direction;
    return environment_light(shading, view) + sun_light(shading, view);
}}

// Every point light at a pixel, one after the other (the on-tile two-pass path's way).
fn pixel_point_lights(position: vec4<f32>) -> vec3<f32> {{
    let pixel = vec2<i32>(position.xy);
    let direction = camera_ray(position.xy, VIEWPORT);
    {read_dark}
    let surface = {position};
    var radiance = vec3<f32>(0.0);
    for (var index = 0u; index < POINT_LIGHT_COUNT; index++) {{
        radiance += point_light(shading, -direction, surface, index);
    }}
    return radiance;
}}

@fragment
fn lighting_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    return vec4<f32>(pixel_radiance(position), 1.0);
}}

struct LightVolume {{
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) light: u32,
}}

// Point light `light`'s volume: the screen rectangle around its reach (instance `light`).
@vertex
fn light_volume_vertex(@builtin(vertex_index) vertex: u32, @builtin(instance_index) light: u32) -> LightVolume {{
    return LightVolume(vec4<f32>(volume_rectangle(vertex, light), 0.0, 1.0), light);
}}

// Point light `light` on the surfaces it reaches in its volume, added by blending.
@fragment
fn point_light_main(volume: LightVolume) -> @location(0) vec4<f32> {{
    let pixel = vec2<i32>(volume.clip.xy);
    let direction = camera_ray(volume.clip.xy, VIEWPORT);
    {read_discard}
    let surface = {position};
    if distance(POINT_LIGHT_POSITIONS[volume.light], surface) >= POINT_LIGHT_RADIUS {{
        discard;
    }}
    return vec4<f32>(point_light(shading, -direction, surface, volume.light), 0.0);
}}

// Lighting and tone mapping in one pass (the on-tile backends' two-pass path).
@fragment
fn lighting_resolve_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    var radiance = pixel_radiance(position);
    if SCENE_POINT_LIGHTS {{
        radiance += pixel_point_lights(position);
    }}
    return display_colour(radiance);
}}
",
        lighting_prelude(options, positions),
        read_radiance = read("return sky(direction);"),
        read_dark = read("return vec3<f32>(0.0);"),
        read_discard = read("discard;"),
        position = match positions {
            Positions::DepthBuffer => "surface_position(pixel, direction)",
            Positions::Texel => "texel_position(texel, direction)",
        },
    ))
}

/// The G-buffer pass's `encode_texel` for a solved layout: the surface's values for the
/// quantities the layout stores.
fn solved_encode_wgsl(solution: &Solution) -> String {
    let mut members = String::new();
    for placement in &solution.placements {
        let value = match placement.quantity {
            Quantity::Light => "surface.light",
            Quantity::Depth => "surface.distance",
            Quantity::Normal => "surface.normal",
            Quantity::Roughness => "surface.roughness",
            Quantity::BaseColour => "surface.base_colour",
            Quantity::Metallic => "surface.metallic",
            // The scene's dielectrics all reflect 0.04: UE4's default specular.
            Quantity::Specular => "0.5",
            Quantity::Albedo => "colours.diffuse",
            Quantity::SpecularColour => "colours.f0",
        };
        members.push_str(&format!(
            "    values.{} = {value};\n",
            placement.quantity.name()
        ));
    }
    format!(
        "fn encode_texel(surface: Surface) -> {name} {{
    let colours = metallic_workflow(surface.base_colour, surface.metallic, DIELECTRIC_F0);
    var values: {values};
{members}    return encode_{snake}(values);
}}",
        name = solution.layout.name,
        values = solution.values_type(),
        snake = solution.layout.snake_name(),
    )
}

/// The lighting pass of a solved layout: decode, then the lighting function generated for the
/// scene (`gbuffer_solver::lighting`), with only the host inputs its terms read.
fn solved_lighting_wgsl(solution: &Solution, options: &Options) -> String {
    let forms = Forms {
        sun: options.sun,
        ibl: options.ibl,
    };
    let layout = &solution.layout;
    let snake = layout.snake_name();
    let (target_bindings, targets) = read_packed_targets(layout);
    let position = if solution.placement(Quantity::Depth).is_some() {
        "SCENE_EYE + direction * values.depth"
    } else {
        "vec3<f32>(0.0)" // without point lights nothing reads it
    };
    format!(
        "{}\n{}\n{}\n{FULLSCREEN_WGSL}\n{INPUTS_WGSL}\n{}\n{target_bindings}
{}
@fragment
fn lighting_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    let pixel = vec2<i32>(position.xy);
    let direction = camera_ray(position.xy, VIEWPORT);
    let targets = {targets};
    // The G-buffer pass marks sky pixels with all ones in the first word (the first target
    // may be narrower than four words).
    if targets.first.x == 0xffffffffu {{
        return vec4<f32>(sky(direction), 1.0);
    }}
    let values = decode_{snake}(unpack_{snake}_targets(targets));
    let surface_position = {position};
    return vec4<f32>({shade}(values, -direction, surface_position), 1.0);
}}
",
        library(&shaders::MODULES),
        shaders::frame_wgsl(options, 1.0),
        scene::scene_wgsl(solution.scene.features),
        gbuffer_solver::texel::texel_wgsl(solution),
        lighting::lighting_wgsl(solution, forms),
        shade = lighting::lighting_function_name(solution),
    )
}

fn tonemap_wgsl() -> String {
    format!(
        "{}\n{FULLSCREEN_WGSL}\n{}
@group(0) @binding(0) var hdr: texture_2d<f32>;

@fragment
fn tonemap_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    return display_colour(textureLoad(hdr, vec2<i32>(position.xy), 0).rgb);
}}
",
        library(&["tonemap", "colour"]),
        shaders::display_wgsl(),
    )
}

/// The vertex buffer's layout: position, normal, object (`mesh::Vertex`).
pub const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Uint32];

impl Passes {
    fn new(renderer: &Renderer, options: &Options) -> Passes {
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
        let gbuffer_views: Vec<wgpu::TextureView> = options
            .gbuffer
            .target_formats()
            .into_iter()
            .map(|format| view(&target("gbuffer", format, read_back_usage)))
            .collect();
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
        let lighting_source = lighting_pass_wgsl(options, Positions::DepthBuffer)
            .expect("positions from the depth buffer suit every layout");
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
        let sampler = wgpu::BindGroupEntry {
            binding: 3,
            resource: wgpu::BindingResource::Sampler(&renderer.sampler),
        };
        let gbuffer_bindings = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &gbuffer.get_bind_group_layout(0),
            entries: &[sampler.clone(), texture(5, &renderer.light_map)],
        });
        let mut entries = vec![
            texture(1, &renderer.environment),
            texture(2, &renderer.lut),
            sampler,
            texture(4, &depth_view),
        ];
        for (index, target_view) in gbuffer_views.iter().enumerate() {
            entries.push(texture(10 + index as u32, target_view));
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
    fn encode(
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
