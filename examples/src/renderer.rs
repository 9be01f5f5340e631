//! The reference deferred renderer on wgpu, headless:
//!
//! 0. once: the split-sum LUT and the light map are baked on the CPU; the procedural sky is
//!    prefiltered into a mip chain by GGX importance sampling in a compute pass and stored as
//!    RGBM, as the seed stores its PMREM (mip = roughness x mips, Listing 2.6);
//! 1. the G-buffer pass writes the chosen layout (packed `Rgba32Uint` targets, or the classic
//!    native targets), its light accumulation holding the static diffuse light;
//! 2. the lighting pass unpacks with the generated WGSL and shades with the shading library: the sun with
//!    GGX or `d_approx`, image-based light with the LUT or `env_brdf_approx`;
//! 3. the tone-mapping pass writes sRGB.

use std::time::Instant;

use gbuffer::shading::env_brdf_lut::EnvBrdfLut;
use gbuffer::shading::mirror as m;
use wgpu::util::DeviceExt;

use gbuffer::packing::Layout;
use gbuffer_scenes::lighting::{self, Forms};
use gbuffer_scenes::quantity::Quantity;
use gbuffer_scenes::Solution;

use crate::gbuffers::{GBuffer, SURFACE_WGSL};
use crate::scene::{self, LIGHT_MAP_EXTENT, LIGHT_MAP_RANGE};

pub use gbuffer_scenes::lighting::{IblForm, SunForm};

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

const LUT_SIZE: usize = 32;
const LIGHT_MAP_SIZE: u32 = 128;
const ENVIRONMENT_WIDTH: u32 = 512;
/// Importance samples per texel of the prefiltered environment (the CPU reference uses the same).
pub const PREFILTER_SAMPLES: u32 = 256;
/// Exposure before tone mapping.
pub const EXPOSURE: f64 = 0.7;
const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The GPU side: device, the baked and prefiltered inputs.
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

/// WGSL of the full-screen triangle every pass draws.
const FULL_SCREEN_WGSL: &str = "
@vertex
fn full_screen(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - vec2<f32>(1.0), 0.0, 1.0);
}

// Direction to equirectangular coordinates (u around the vertical, v from the zenith).
fn equirectangular(direction: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(atan2(direction.x, direction.z) * 0.15915494 + 0.5, acos(clamp(direction.y, -1.0, 1.0)) * 0.31830988);
}
";

fn library(modules: &[&str]) -> String {
    gbuffer::modules::compose(modules).expect("the library's modules exist")
}

impl Renderer {
    /// Opens an adapter (any wgpu finds, software ones included) and prepares the inputs,
    /// reporting progress.
    pub fn new(progress: &dyn Fn(&str)) -> Result<Renderer, String> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        };
        let adapter = pollster::block_on(instance.request_adapter(&options))
            .map_err(|error| format!("no GPU adapter ({error}); on a machine without a GPU install Mesa's software drivers (apt-get install -y mesa-vulkan-drivers libegl1)"))?;
        let info = adapter.get_info();
        let timestamp_feature = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let descriptor = wgpu::DeviceDescriptor {
            label: Some("deferred"),
            required_features: timestamp_feature,
            required_limits: adapter.limits(),
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
            .map_err(|error| error.to_string())?;
        progress(&format!("adapter: {} ({:?})", info.name, info.backend));

        progress("baking the split-sum LUT (32x32, 256 samples)...");
        let lut = EnvBrdfLut::bake(LUT_SIZE, PREFILTER_SAMPLES);
        let lut_texels: Vec<u16> = lut
            .texels
            .iter()
            .flat_map(|[scale, bias]| {
                [*scale, *bias, 0.0, 1.0]
                    .map(|value| gbuffer_codegen::convert::half_from_f32(value) as u16)
            })
            .collect();
        let lut = texture_with_data(
            &device,
            &queue,
            "lut",
            LUT_SIZE as u32,
            LUT_SIZE as u32,
            wgpu::TextureFormat::Rgba16Float,
            bytemuck::cast_slice(&lut_texels),
        );

        progress("baking the light map (128x128, RGBM squared, range 6)...");
        let light_map: Vec<u8> = (0..LIGHT_MAP_SIZE * LIGHT_MAP_SIZE)
            .flat_map(|index| {
                let centre = |coordinate: u32| {
                    ((f64::from(coordinate) + 0.5) / f64::from(LIGHT_MAP_SIZE) * 2.0 - 1.0)
                        * LIGHT_MAP_EXTENT
                };
                let irradiance = scene::light_map(
                    centre(index % LIGHT_MAP_SIZE),
                    centre(index / LIGHT_MAP_SIZE),
                );
                let encoded =
                    m::hdr::rgbm_squared_encode(irradiance.as_vec3(), LIGHT_MAP_RANGE as f32);
                encoded
                    .to_array()
                    .map(|channel| gbuffer_codegen::convert::unorm_from_f32(channel, 8) as u8)
            })
            .collect();
        let light_map = texture_with_data(
            &device,
            &queue,
            "light map",
            LIGHT_MAP_SIZE,
            LIGHT_MAP_SIZE,
            wgpu::TextureFormat::Rgba8Unorm,
            &light_map,
        );

        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            address_mode_u: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        progress(&format!(
            "prefiltering the environment ({} mips, {PREFILTER_SAMPLES} GGX samples a texel)...",
            scene::ENVIRONMENT_MIPS + 1
        ));
        let environment = prefilter_environment(&device, &queue)?;
        let timestamps = (!timestamp_feature.is_empty()).then(|| Timestamps::new(&device));
        Ok(Renderer {
            device,
            queue,
            adapter: info,
            environment,
            lut,
            light_map,
            sampler,
            timestamps,
        })
    }

    /// Renders a frame and reads it back.
    pub fn render(&self, options: &Options) -> Result<Frame, String> {
        let passes = self.passes(options)?;
        self.queue.submit([passes.encode(self, None)]);
        let pixels = self.read_back(&passes.output, options.width, options.height)?;
        Ok(Frame {
            width: options.width,
            height: options.height,
            pixels,
        })
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

    fn read_back(
        &self,
        texture: &wgpu::Texture,
        width: u32,
        height: u32,
    ) -> Result<Vec<[u8; 4]>, String> {
        let row_bytes = (width * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
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
                view[(row * row_bytes) as usize..][..(width * 4) as usize]
                    .chunks(4)
                    .map(|pixel| [pixel[0], pixel[1], pixel[2], pixel[3]])
                    .collect::<Vec<_>>()
            })
            .collect())
    }
}

fn texture_with_data(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    data: &[u8],
) -> wgpu::TextureView {
    device
        .create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            data,
        )
        .create_view(&Default::default())
}

/// The prefiltered sky: an equirectangular RGBM mip chain, mip m integrating the GGX lobe of
/// roughness m / ENVIRONMENT_MIPS (Karis's split sum: n = v = r) with PREFILTER_SAMPLES
/// importance samples.
fn prefilter_environment(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
) -> Result<wgpu::TextureView, String> {
    let mips = scene::ENVIRONMENT_MIPS + 1;
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("environment"),
        size: wgpu::Extent3d {
            width: ENVIRONMENT_WIDTH,
            height: ENVIRONMENT_WIDTH / 2,
            depth_or_array_layers: 1,
        },
        mip_level_count: mips,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::STORAGE_BINDING,
        view_formats: &[],
    });
    let source = format!(
        "{}\n{}\n{FULL_SCREEN_WGSL}\n
@group(0) @binding(0) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(1) var<uniform> level: vec4<f32>; // roughness, width, height, samples

@compute @workgroup_size(8, 8)
fn prefilter(@builtin(global_invocation_id) id: vec3<u32>) {{
    if f32(id.x) >= level.y || f32(id.y) >= level.z {{
        return;
    }}
    let u = (f32(id.x) + 0.5) / level.y;
    let v = (f32(id.y) + 0.5) / level.z;
    let phi = (u - 0.5) * 6.2831853;
    let theta = v * 3.14159265;
    let normal = vec3<f32>(sin(theta) * sin(phi), cos(theta), sin(theta) * cos(phi));
    var radiance = sky(normal);
    if level.x > 0.0 {{
        radiance = prefiltered_sky(normal, level.x, u32(level.w));
    }}
    textureStore(output, vec2<i32>(id.xy), rgbm_encode(radiance, ENVIRONMENT_RANGE));
}}

// The GGX lobe of `roughness` around `normal` (n = v = r) integrated over the sky.
fn prefiltered_sky(normal: vec3<f32>, roughness: f32, samples: u32) -> vec3<f32> {{
    let up = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 0.0, 1.0), abs(normal.z) < 0.999);
    let tangent = normalize(cross(up, normal));
    let bitangent = cross(normal, tangent);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var index = 0u; index < samples; index++) {{
        let local = importance_sample_ggx(hammersley(index, samples), roughness);
        let half_vector = tangent * local.x + bitangent * local.y + normal * local.z;
        let light = 2.0 * dot(normal, half_vector) * half_vector - normal;
        let n_dot_l = dot(normal, light);
        if n_dot_l > 0.0 {{
            sum += sky(light) * n_dot_l;
            weight += n_dot_l;
        }}
    }}
    return sum / weight;
}}
",
        library(&["environment", "hdr", "normals"]),
        scene::scene_wgsl(gbuffer_scenes::Features::reference_scene())
    );
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("prefilter"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("prefilter"),
        layout: None,
        module: &module,
        entry_point: Some("prefilter"),
        compilation_options: Default::default(),
        cache: None,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    for mip in 0..mips {
        let (width, height) = (
            (ENVIRONMENT_WIDTH >> mip).max(1),
            ((ENVIRONMENT_WIDTH / 2) >> mip).max(1),
        );
        let roughness = mip as f32 / scene::ENVIRONMENT_MIPS as f32;
        let level = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytemuck::cast_slice(&[
                roughness,
                width as f32,
                height as f32,
                PREFILTER_SAMPLES as f32,
            ]),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            base_mip_level: mip,
            mip_level_count: Some(1),
            ..Default::default()
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: level.as_entire_binding(),
                },
            ],
        });
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
    }
    queue.submit([encoder.finish()]);
    if let Some(error) = pollster::block_on(scope.pop()) {
        return Err(format!("prefiltering the environment: {error}"));
    }
    Ok(texture.create_view(&Default::default()))
}

/// The three passes of one configuration, with their targets.
struct Passes {
    gbuffer_views: Vec<wgpu::TextureView>,
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

/// The G-buffer pass's last statements for a packed layout (sky pixels get all ones, a
/// surface its packed words) and the type it returns: `<Name>Targets`.
fn write_packed_targets(layout: &Layout) -> (String, String) {
    let (name, snake) = (&layout.name, layout.snake_name());
    let sentinel = vec!["vec4<u32>(0xffffffffu)"; layout.targets()].join(", ");
    (
        format!("if surface.distance < 0.0 {{\n        return {name}Targets({sentinel});\n    }}\n    return pack_{snake}_targets(encode_texel(surface));"),
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

/// The G-buffer pass's WGSL for a configuration.
fn gbuffer_wgsl(gbuffer: &GBuffer) -> String {
    let modules = vec!["normals", "colour", "hdr", "material", "mobile"];
    let (layout_wgsl, encode, output_type, output) = match gbuffer {
        GBuffer::Packed(layout) => {
            let (encode, output_type) = write_packed_targets(&layout.layout());
            (
                format!("{}\n{}", layout.wgsl(), layout.encode_wgsl()),
                encode,
                output_type,
                String::new(),
            )
        }
        GBuffer::Solved(solution) => {
            let (encode, output_type) = write_packed_targets(&solution.layout);
            (
                format!(
                    "{}\n{}",
                    gbuffer_scenes::texel::texel_wgsl(solution),
                    solved_encode_wgsl(solution)
                ),
                encode,
                output_type,
                String::new(),
            )
        }
        GBuffer::Classic => (
            String::new(),
            "if surface.distance < 0.0 {\n        return ClassicTargets(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));\n    }\n    return ClassicTargets(vec4<f32>(surface.light, 1.0), vec4<f32>(normal_to_unorm(surface.normal), surface.roughness), vec4<f32>(surface.base_colour, surface.metallic));".to_string(),
            "ClassicTargets".to_string(),
            "struct ClassicTargets {\n    @location(0) light: vec4<f32>,\n    @location(1) normal_roughness: vec4<f32>,\n    @location(2) base_colour_metallic: vec4<f32>,\n}\n".to_string(),
        ),
    };
    format!(
        "{}\n{}\n{FULL_SCREEN_WGSL}\n{SURFACE_WGSL}\n{layout_wgsl}\n{output}
const LIGHT_SCALE: f32 = {light_scale:?};
@group(0) @binding(0) var<uniform> viewport: vec4<f32>;
@group(0) @binding(1) var light_map: texture_2d<f32>;
@group(0) @binding(2) var linear_sampler: sampler;

// The first surface the ray meets; distance < 0 for none.
fn trace(origin: vec3<f32>, direction: vec3<f32>) -> Surface {{
    var best = 1e30;
    var best_column = 0u;
    var best_row = 0u;
    for (var row = 0u; row < SCENE_ROWS; row++) {{
        for (var column = 0u; column < SCENE_COLUMNS; column++) {{
            let offset = origin - sphere_centre(column, row);
            let b = dot(offset, direction);
            let discriminant = b * b - (dot(offset, offset) - SPHERE_RADIUS * SPHERE_RADIUS);
            if discriminant > 0.0 {{
                let distance = -b - sqrt(discriminant);
                if distance > 0.0 && distance < best {{
                    best = distance;
                    best_column = column;
                    best_row = row;
                }}
            }}
        }}
    }}
    var ground = 1e30;
    if direction.y < 0.0 {{
        ground = -origin.y / direction.y;
    }}
    var surface: Surface;
    surface.distance = -1.0;
    var emission = vec3<f32>(0.0);
    if best < 1e29 && best < ground {{
        let point = origin + direction * best;
        var materials = ROW_MATERIALS;
        let material = materials[best_row];
        surface.normal = normalize(point - sphere_centre(best_column, best_row));
        surface.roughness = f32(best_column) / f32(SCENE_COLUMNS - 1u);
        surface.base_colour = material.rgb;
        surface.metallic = select(0.0, material.a, SCENE_METALS);
        surface.light = select(vec3<f32>(0.0), sky_irradiance(surface.normal), SCENE_IMAGE_BASED_LIGHTING);
        if SCENE_EMISSIVE && best_row == EMISSIVE_ROW && best_column == EMISSIVE_COLUMN {{
            emission = EMISSION;
        }}
        surface.distance = best;
        surface.position = point;
    }} else if ground < 40.0 {{
        let point = origin + direction * ground;
        let mask = ground_metallic(point.x, point.z);
        surface.normal = vec3<f32>(0.0, 1.0, 0.0);
        if SCENE_NORMAL_MAPS {{
            surface.normal = ground_normal(point.x, point.z);
        }}
        surface.roughness = 0.75 * (1.0 - mask) + 0.28 * mask;
        surface.base_colour = ground_base_colour(point.x, point.z, mask);
        surface.metallic = select(0.0, mask, SCENE_METALS);
        surface.light = select(vec3<f32>(0.0), sky_irradiance(vec3<f32>(0.0, 1.0, 0.0)), SCENE_IMAGE_BASED_LIGHTING);
        if SCENE_LIGHT_MAPS && abs(point.x) < LIGHT_MAP_EXTENT && abs(point.z) < LIGHT_MAP_EXTENT {{
            let uv = vec2<f32>(point.x, point.z) / (2.0 * LIGHT_MAP_EXTENT) + vec2<f32>(0.5);
            surface.light = rgbm_squared_decode(textureSampleLevel(light_map, linear_sampler, uv, 0.0), LIGHT_MAP_RANGE);
        }}
        surface.distance = ground;
        surface.position = point;
    }}
    if SCENE_FULLY_ROUGH {{
        surface.roughness = 1.0;
    }}
    // The light accumulation holds the static diffuse light (irradiance times diffuse colour)
    // and the emitted light. On fully rough scenes with image-based light the environment's
    // specular is folded in as 0.45 f0 (seed 001): the lighting pass skips the environment.
    let colours = metallic_workflow(surface.base_colour, surface.metallic, DIELECTRIC_F0);
    var ambient_colour = colours.diffuse;
    if SCENE_FULLY_ROUGH && SCENE_IMAGE_BASED_LIGHTING {{
        ambient_colour = fully_rough_diffuse_colour(colours.diffuse, colours.f0);
    }}
    surface.light = surface.light * ambient_colour + emission;
    return surface;
}}

@fragment
fn gbuffer_main(@builtin(position) position: vec4<f32>) -> {output_type} {{
    let surface = trace(SCENE_EYE, camera_ray(position.xy, viewport.xy));
    {encode}
}}
",
        library(&modules),
        scene::scene_wgsl(gbuffer.features()),
        light_scale = crate::gbuffers::LIGHT_SCALE,
    )
}

/// The lighting pass's WGSL for a configuration (entry point `lighting_main`), and the
/// bindings of group 0 it uses.
pub fn lighting_wgsl(options: &Options) -> (String, Vec<u32>) {
    let targets = options.gbuffer.target_formats().len() as u32;
    let (bindings, read) = match &options.gbuffer {
        GBuffer::Solved(solution) => return solved_lighting_wgsl(solution, options),
        GBuffer::Packed(layout) => {
            let model = layout.layout();
            let (bindings, targets) = read_packed_targets(&model);
            let snake = model.snake_name();
            (
                format!("{}\n{}\n{bindings}", layout.wgsl(), layout.decode_wgsl()),
                format!("let targets = {targets};\n    if targets.first.x == 0xffffffffu {{\n        return vec4<f32>(sky(direction), 1.0);\n    }}\n    let shading = decode_texel(unpack_{snake}_targets(targets));"),
            )
        }
        GBuffer::Classic => (
            "@group(0) @binding(10) var gbuffer_light: texture_2d<f32>;\n@group(0) @binding(11) var gbuffer_normal: texture_2d<f32>;\n@group(0) @binding(12) var gbuffer_colour: texture_2d<f32>;\n".to_string(),
            "let light = textureLoad(gbuffer_light, pixel, 0);\n    if light.a == 0.0 {\n        return vec4<f32>(sky(direction), 1.0);\n    }\n    let normal_roughness = textureLoad(gbuffer_normal, pixel, 0);\n    let colour = textureLoad(gbuffer_colour, pixel, 0);\n    let colours = metallic_workflow(colour.rgb, colour.a, DIELECTRIC_F0);\n    let shading = Shading(unorm_to_normal(normal_roughness.xyz), normal_roughness.w, colours.diffuse, colours.f0, light.rgb);".to_string(),
        ),
    };
    let sun = match options.sun {
        SunForm::Ggx => "shade_directional(normal, view, SUN_DIRECTION, SUN_COLOUR, shading.diffuse, shading.f0, shading.roughness, env_brdf)",
        SunForm::Approx => "shade_directional_mobile(normal, view, SUN_DIRECTION, SUN_COLOUR, shading.diffuse, shading.f0, shading.roughness)",
    };
    let ibl = match options.ibl {
        IblForm::Lut => "shade_ibl(shading.light, shading.f0, vec3<f32>(1.0), radiance, env_brdf)",
        IblForm::Approx => "shade_ibl_mobile(shading.light, shading.f0, shading.roughness, n_dot_v, vec3<f32>(1.0), radiance)",
    };
    let source = format!(
        "{}\n{}\n{FULL_SCREEN_WGSL}\n{SURFACE_WGSL}\n{bindings}
const LIGHT_SCALE: f32 = {light_scale:?};
@group(0) @binding(0) var<uniform> viewport: vec4<f32>;
@group(0) @binding(1) var environment: texture_2d<f32>;
@group(0) @binding(2) var lut: texture_2d<f32>;
@group(0) @binding(3) var linear_sampler: sampler;

@fragment
fn lighting_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    let pixel = vec2<i32>(position.xy);
    let direction = camera_ray(position.xy, viewport.xy);
    {read}
    let normal = shading.normal;
    let view = -direction;
    let n_dot_v = clamp(dot(normal, view), MIN_N_DOT_V, 1.0);
    let reflected = 2.0 * dot(normal, view) * normal - view;
    let mip = ibl_mip_level(shading.roughness, ENVIRONMENT_MIPS);
    let radiance = rgbm_decode(textureSampleLevel(environment, linear_sampler, equirectangular(reflected), mip), ENVIRONMENT_RANGE);
    let env_brdf = textureSampleLevel(lut, linear_sampler, vec2<f32>(n_dot_v, shading.roughness), 0.0).xy;
    return vec4<f32>({sun} + {ibl}, 1.0);
}}
",
        library(&["shading", "environment", "normals", "colour", "hdr", "material"]),
        scene::scene_wgsl(options.gbuffer.features()),
        light_scale = crate::gbuffers::LIGHT_SCALE,
    );
    (
        source,
        [0, 1, 2, 3].into_iter().chain(10..10 + targets).collect(),
    )
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
/// scene (`gbuffer_scenes::lighting`), with only the host inputs its terms read.
fn solved_lighting_wgsl(solution: &Solution, options: &Options) -> (String, Vec<u32>) {
    let forms = Forms {
        sun: options.sun,
        ibl: options.ibl,
    };
    let inputs = lighting::host_inputs(solution, forms);
    let mut bindings = vec![0];
    let mut host = String::new();
    if inputs.environment {
        bindings.push(1);
        host.push_str("@group(0) @binding(1) var environment: texture_2d<f32>;
fn environment_radiance(direction: vec3<f32>, roughness: f32) -> vec3<f32> {
    let mip = ibl_mip_level(roughness, ENVIRONMENT_MIPS);
    return rgbm_decode(textureSampleLevel(environment, linear_sampler, equirectangular(direction), mip), ENVIRONMENT_RANGE);
}
");
    }
    if inputs.env_brdf_lut {
        bindings.push(2);
        host.push_str(
            "@group(0) @binding(2) var lut: texture_2d<f32>;
fn env_brdf_lut(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    return textureSampleLevel(lut, linear_sampler, vec2<f32>(n_dot_v, roughness), 0.0).xy;
}
",
        );
    }
    if inputs.environment || inputs.env_brdf_lut {
        bindings.push(3);
        host.push_str("@group(0) @binding(3) var linear_sampler: sampler;\n");
    }
    let layout = &solution.layout;
    let snake = layout.snake_name();
    bindings.extend((0..layout.targets() as u32).map(|target| 10 + target));
    let (target_bindings, targets) = read_packed_targets(layout);
    let position = if solution.placement(Quantity::Depth).is_some() {
        "SCENE_EYE + direction * values.depth"
    } else {
        "vec3<f32>(0.0)" // without point lights nothing reads it
    };
    let modules = vec![
        "shading",
        "environment",
        "normals",
        "colour",
        "hdr",
        "material",
        "mobile",
    ];
    let source = format!(
        "{}\n{}\n{FULL_SCREEN_WGSL}\n{}\n{target_bindings}{host}
@group(0) @binding(0) var<uniform> viewport: vec4<f32>;

{}
@fragment
fn lighting_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    let pixel = vec2<i32>(position.xy);
    let direction = camera_ray(position.xy, viewport.xy);
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
        library(&modules),
        scene::scene_wgsl(solution.scene.features),
        gbuffer_scenes::texel::texel_wgsl(solution),
        lighting::lighting_wgsl(solution, forms),
        shade = lighting::lighting_function_name(solution),
    );
    (source, bindings)
}

fn tonemap_wgsl() -> String {
    format!(
        "{}\n{FULL_SCREEN_WGSL}
@group(0) @binding(0) var hdr: texture_2d<f32>;

@fragment
fn tonemap_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{
    let colour = textureLoad(hdr, vec2<i32>(position.xy), 0).rgb;
    return vec4<f32>(linear_to_srgb(tonemap_aces_fitted(colour * {exposure:?})), 1.0);
}}
",
        library(&["tonemap", "colour"]),
        exposure = EXPOSURE as f32,
    )
}

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
        // The G-buffer is read back by the lighting pass as textures (wgpu has no framebuffer
        // fetch), so it is a real attachment here; a tile-based backend would keep it on chip.
        let gbuffer_usage =
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        let gbuffer_targets: Vec<wgpu::Texture> = options
            .gbuffer
            .target_formats()
            .into_iter()
            .map(|format| target("gbuffer", format, gbuffer_usage))
            .collect();
        let gbuffer_views: Vec<wgpu::TextureView> = gbuffer_targets
            .iter()
            .map(|texture| texture.create_view(&Default::default()))
            .collect();
        let hdr = target("hdr", HDR_FORMAT, gbuffer_usage);
        let output = target(
            "output",
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );

        let viewport = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytemuck::cast_slice(&[
                options.width as f32,
                options.height as f32,
                0.0,
                0.0,
            ]),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let pipeline =
            |label: &str, source: String, entry: &str, formats: &[wgpu::TextureFormat]| {
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(label),
                    source: wgpu::ShaderSource::Wgsl(source.into()),
                });
                let targets: Vec<Option<wgpu::ColorTargetState>> = formats
                    .iter()
                    .map(|format| Some((*format).into()))
                    .collect();
                device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some(label),
                    layout: None,
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some("full_screen"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: Default::default(),
                    depth_stencil: None,
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &module,
                        entry_point: Some(entry),
                        compilation_options: Default::default(),
                        targets: &targets,
                    }),
                    multiview_mask: None,
                    cache: None,
                })
            };
        let gbuffer = pipeline(
            "gbuffer",
            gbuffer_wgsl(&options.gbuffer),
            "gbuffer_main",
            &options.gbuffer.target_formats(),
        );
        let (lighting_source, lighting_bindings_used) = lighting_wgsl(options);
        let lighting = pipeline("lighting", lighting_source, "lighting_main", &[HDR_FORMAT]);
        let tonemap = pipeline(
            "tonemap",
            tonemap_wgsl(),
            "tonemap_main",
            &[wgpu::TextureFormat::Rgba8Unorm],
        );

        let view = |texture: &wgpu::Texture| texture.create_view(&Default::default());
        let gbuffer_bindings = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &gbuffer.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: viewport.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&renderer.light_map),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&renderer.sampler),
                },
            ],
        });
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: viewport.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(&renderer.environment),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&renderer.lut),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::Sampler(&renderer.sampler),
            },
        ];
        for (index, target_view) in gbuffer_views.iter().enumerate() {
            entries.push(wgpu::BindGroupEntry {
                binding: 10 + index as u32,
                resource: wgpu::BindingResource::TextureView(target_view),
            });
        }
        // A solved layout's lighting pass declares only the bindings its terms read.
        entries.retain(|entry| lighting_bindings_used.contains(&entry.binding));
        let lighting_bindings = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &lighting.get_bind_group_layout(0),
            entries: &entries,
        });
        let hdr_view = view(&hdr);
        let output_view = view(&output);
        let tonemap_bindings = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &tonemap.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&hdr_view),
            }],
        });
        Passes {
            gbuffer_views,
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

    /// The frame's commands.
    /// The frame's commands; with a query set, a timestamp at the start of the G-buffer pass
    /// (query 0) and at the end of the tone-mapping pass (query 1).
    fn encode(
        &self,
        renderer: &Renderer,
        timestamps: Option<&wgpu::QuerySet>,
    ) -> wgpu::CommandBuffer {
        let mut encoder = renderer.device.create_command_encoder(&Default::default());
        fn attachment(
            view: &wgpu::TextureView,
            clear: wgpu::Color,
        ) -> wgpu::RenderPassColorAttachment<'_> {
            wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear),
                    store: wgpu::StoreOp::Store,
                },
            }
        }
        let draw = |encoder: &mut wgpu::CommandEncoder,
                    attachments: Vec<Option<wgpu::RenderPassColorAttachment>>,
                    pipeline: &wgpu::RenderPipeline,
                    bindings: &wgpu::BindGroup,
                    timestamp_writes: Option<wgpu::RenderPassTimestampWrites>| {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &attachments,
                depth_stencil_attachment: None,
                timestamp_writes,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bindings, &[]);
            pass.draw(0..3, 0..1);
        };
        let gbuffer_attachments = self
            .gbuffer_views
            .iter()
            .map(|view| Some(attachment(view, wgpu::Color::TRANSPARENT)))
            .collect();
        let at = |beginning: Option<u32>, end: Option<u32>| {
            timestamps.map(|query_set| wgpu::RenderPassTimestampWrites {
                query_set,
                beginning_of_pass_write_index: beginning,
                end_of_pass_write_index: end,
            })
        };
        draw(
            &mut encoder,
            gbuffer_attachments,
            &self.gbuffer,
            &self.gbuffer_bindings,
            at(Some(0), None),
        );
        draw(
            &mut encoder,
            vec![Some(attachment(&self.hdr_view, wgpu::Color::BLACK))],
            &self.lighting,
            &self.lighting_bindings,
            None,
        );
        draw(
            &mut encoder,
            vec![Some(attachment(&self.output_view, wgpu::Color::BLACK))],
            &self.tonemap,
            &self.tonemap_bindings,
            at(None, Some(1)),
        );
        encoder.finish()
    }
}
