//! A deferred frame in wgpu through a G-buffer that a derive declares. The G-buffer pass draws a
//! sphere and packs each pixel's surface into the layout's targets (the generated
//! `pack_surface_targets`); the lighting pass unpacks the texel under it (`read_surface_targets`)
//! and lights it. In a window where there is a display; with `--png FILE`, or where there is no
//! display, one frame written to FILE.
//!
//! From the repository: `cargo run --manifest-path examples/wgpu-app/Cargo.toml`, with
//! `-- --png frame.png` or `-- --frames N` (closes the window after N frames).

use std::process::ExitCode;
use std::sync::Arc;

use gbuffer::glam::Vec3;
use gbuffer::{GBufferLayout, GBufferTargets, GBufferTextures};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::{Window, WindowId};

/// 96 bits a pixel: three 32-bit words, one render target each.
#[derive(GBufferLayout, Clone, Copy, Debug)]
#[gbuffer(budget = 96)]
struct Surface {
    #[pls(rgba8)]
    albedo: Vec3,
    #[bits(24, octahedral)]
    normal: Vec3, // 24 bits of a shared word...
    #[bits(8, unorm)]
    roughness: f32, // ...and 8 more
    #[pls(r32f)]
    depth: f32,
}

/// Both passes draw one triangle that covers the frame; `uv` runs from -1 to 1 across it, y up.
const FULL_FRAME: &str = "
struct Varyings {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vertex_main(@builtin(vertex_index) vertex: u32) -> Varyings {
    let uv = vec2<f32>(f32((vertex << 1u) & 2u), f32(vertex & 2u)) * 2.0 - 1.0;
    return Varyings(vec4<f32>(uv, 0.0, 1.0), uv);
}
";

/// The G-buffer pass: a sphere in bands of two materials, over a background at depth 1.
const GBUFFER_PASS: &str = "
@fragment
fn gbuffer_main(in: Varyings) -> SurfaceTargets {
    // Width over height, from how fast uv moves across a pixel: round in any window.
    let aspect = abs(dpdy(in.uv.y) / dpdx(in.uv.x));
    let p = vec2<f32>(in.uv.x * aspect, in.uv.y) / 0.8;
    var surface = Surface(vec3<f32>(0.0), vec3<f32>(0.0, 0.0, 1.0), 1.0, 1.0);
    if dot(p, p) < 1.0 {
        surface.normal = vec3<f32>(p, sqrt(1.0 - dot(p, p)));
        surface.depth = 1.0 - surface.normal.z;
        // Bands of latitude: smooth gold, then rough blue.
        let rough = (u32(floor(surface.normal.y * 4.0 + 4.0)) & 1u) == 1u;
        surface.albedo = select(vec3<f32>(0.8, 0.45, 0.06), vec3<f32>(0.04, 0.1, 0.5), rough);
        surface.roughness = select(0.15, 0.8, rough);
    }
    return pack_surface_targets(surface);
}
";

/// The lighting pass: one light, Lambert's diffuse and a normalised Blinn-Phong highlight whose
/// exponent falls with roughness (from 2^11 smooth to 1 rough), so that the bands' highlights
/// differ through what the G-buffer kept. The output is linear; an sRGB target encodes it.
const LIGHTING_PASS: &str = "
@fragment
fn lighting_main(in: Varyings) -> @location(0) vec4<f32> {
    let surface = read_surface_targets(vec2<u32>(in.position.xy));
    if surface.depth >= 1.0 {
        return vec4<f32>(0.02, 0.02, 0.03, 1.0);
    }
    let to_light = normalize(vec3<f32>(-0.4, 0.6, 0.7));
    let half_way = normalize(to_light + vec3<f32>(0.0, 0.0, 1.0));
    let n_dot_l = max(dot(surface.normal, to_light), 0.0);
    let exponent = exp2(11.0 * (1.0 - surface.roughness));
    let highlight = 0.25 * (exponent + 8.0) / 8.0 * pow(max(dot(surface.normal, half_way), 0.0), exponent);
    let colour = surface.albedo * (0.05 + n_dot_l) + vec3<f32>(highlight * n_dot_l);
    return vec4<f32>(colour, 1.0);
}
";

/// The two passes' pipelines, and the targets of the last size drawn.
struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    gbuffer_pass: wgpu::RenderPipeline,
    lighting_pass: wgpu::RenderPipeline,
    targets_layout: wgpu::BindGroupLayout,
    targets: Option<((u32, u32), GBufferTextures, wgpu::BindGroup)>,
}

impl Renderer {
    /// A device whose limits hold the layout's targets, and pipelines that end in `output`.
    fn new(adapter: &wgpu::Adapter, output: wgpu::TextureFormat) -> Result<Renderer, String> {
        Surface::check_limits(&adapter.limits()).map_err(|error| error.to_string())?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            required_limits: Surface::required_limits(wgpu::Limits::downlevel_defaults()),
            ..Default::default()
        }))
        .map_err(|error| format!("no device: {error}"))?;
        let targets_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("G-buffer targets"),
            entries: &Surface::bind_group_layout_entries(0, wgpu::ShaderStages::FRAGMENT),
        });
        let lighting_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("lighting pass"),
            bind_group_layouts: &[Some(&targets_layout)],
            immediate_size: 0,
        });
        // The layout's WGSL (its struct, pack and unpack) comes first in both modules; the
        // lighting pass's also has the targets' bindings and `read_surface_targets`.
        let gbuffer_wgsl = format!("{}\n{FULL_FRAME}\n{GBUFFER_PASS}", Surface::WGSL);
        let lighting_wgsl = format!(
            "{}\n{}\n{FULL_FRAME}\n{LIGHTING_PASS}",
            Surface::WGSL,
            Surface::lighting_wgsl(0, 0)
        );
        let gbuffer_pass = pipeline(&device, &gbuffer_wgsl, None, &Surface::color_targets());
        let lighting_pass = pipeline(
            &device,
            &lighting_wgsl,
            Some(&lighting_layout),
            &[Some(output.into())],
        );
        Ok(Renderer {
            device,
            queue,
            gbuffer_pass,
            lighting_pass,
            targets_layout,
            targets: None,
        })
    }

    /// Draws a frame into `output`: the G-buffer pass into targets of its size, then the
    /// lighting pass from them into it. Submits, with `then` recorded after the two passes.
    fn draw(&mut self, output: &wgpu::Texture, then: impl FnOnce(&mut wgpu::CommandEncoder)) {
        let size = (output.width(), output.height());
        if self.targets.as_ref().map(|(made_for, ..)| *made_for) != Some(size) {
            let textures =
                Surface::create_targets(&self.device, size.0, size.1, wgpu::TextureUsages::empty());
            let bind_group =
                Surface::create_bind_group(&self.device, &self.targets_layout, 0, &textures);
            self.targets = Some((size, textures, bind_group));
        }
        let (_, textures, bind_group) = self.targets.as_ref().expect("made above");
        let view = output.create_view(&Default::default());
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let passes: [(&wgpu::RenderPipeline, Vec<_>, Option<&wgpu::BindGroup>); 2] = [
            (
                &self.gbuffer_pass,
                textures.color_attachments(wgpu::Color::TRANSPARENT),
                None,
            ),
            (
                &self.lighting_pass,
                vec![Some(attachment(&view))],
                Some(bind_group),
            ),
        ];
        for (pipeline, color_attachments, bind_group) in passes {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &color_attachments,
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(pipeline);
            if let Some(bind_group) = bind_group {
                pass.set_bind_group(0, bind_group, &[]);
            }
            pass.draw(0..3, 0..1);
        }
        then(&mut encoder);
        self.queue.submit([encoder.finish()]);
    }
}

/// A pipeline of the full-frame triangle and the module's one fragment entry point.
fn pipeline(
    device: &wgpu::Device,
    wgsl: &str,
    layout: Option<&wgpu::PipelineLayout>,
    targets: &[Option<wgpu::ColorTargetState>],
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: None,
        layout,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vertex_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: None,
            compilation_options: Default::default(),
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// An attachment cleared, drawn and kept.
fn attachment(view: &wgpu::TextureView) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
            store: wgpu::StoreOp::Store,
        },
    }
}

/// One 512x512 frame, read back and written to `path` as an 8-bit sRGB PNG.
fn write_png(path: &str) -> Result<(), String> {
    const SIZE: u32 = 512; // 2048 bytes a row: a multiple of wgpu's 256-byte row alignment
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))
        .map_err(|error| format!("no adapter: {error}"))?;
    let mut renderer = Renderer::new(&adapter, wgpu::TextureFormat::Rgba8UnormSrgb)?;
    let frame = renderer.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("frame"),
        size: wgpu::Extent3d {
            width: SIZE,
            height: SIZE,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let readback = renderer.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("frame readback"),
        size: u64::from(SIZE * SIZE * 4),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    renderer.draw(&frame, |encoder| {
        encoder.copy_texture_to_buffer(
            frame.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(SIZE * 4),
                    rows_per_image: None,
                },
            },
            frame.size(),
        )
    });
    readback.slice(..).map_async(wgpu::MapMode::Read, |_| {});
    renderer
        .device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|error| format!("the frame: {error}"))?;
    let pixels = readback
        .slice(..)
        .get_mapped_range()
        .map_err(|e| e.to_string())?
        .to_vec();

    // Encoded whole before the file is made, so that a failure leaves no half-written file.
    let mut encoded = Vec::new();
    let mut encoder = png::Encoder::new(&mut encoded, SIZE, SIZE);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder
        .write_header()
        .and_then(|mut writer| writer.write_image_data(&pixels))
        .map_err(|error| format!("encoding the frame: {error}"))?;
    std::fs::write(path, encoded).map_err(|error| format!("{path}: {error}"))?;
    let info = adapter.get_info();
    println!(
        "wrote {path} ({SIZE}x{SIZE}) on {} ({:?})",
        info.name, info.backend
    );
    Ok(())
}

/// The window, its surface and the renderer, made when the event loop first resumes.
struct App {
    frames_left: Option<u32>,
    window: Option<(
        Arc<Window>,
        wgpu::Surface<'static>,
        wgpu::SurfaceConfiguration,
        Renderer,
    )>,
    error: Option<String>,
}

impl App {
    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<(), String> {
        let attributes = Window::default_attributes()
            .with_title("gbuffer: a deferred frame")
            .with_inner_size(winit::dpi::LogicalSize::new(512, 512));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| e.to_string())?,
        );
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| e.to_string())?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .map_err(|error| format!("no adapter for the window: {error}"))?;
        let size = window.inner_size();
        let config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .ok_or("the adapter cannot present to this window")?;
        let renderer = Renderer::new(&adapter, config.format)?;
        surface.configure(&renderer.device, &config);
        let info = adapter.get_info();
        println!("a window on {} ({:?})", info.name, info.backend);
        self.window = Some((window, surface, config, renderer));
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_none() {
            if let Err(error) = self.open(event_loop) {
                self.error = Some(error);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some((window, surface, config, renderer)) = &mut self.window else {
            return;
        };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) if size.width > 0 && size.height > 0 => {
                (config.width, config.height) = (size.width, size.height);
                surface.configure(&renderer.device, config);
                window.request_redraw();
            }
            WindowEvent::RedrawRequested => {
                let frame = match surface.get_current_texture() {
                    wgpu::CurrentSurfaceTexture::Success(frame)
                    | wgpu::CurrentSurfaceTexture::Suboptimal(frame) => frame,
                    wgpu::CurrentSurfaceTexture::Timeout
                    | wgpu::CurrentSurfaceTexture::Occluded => return, // the next redraw may
                    _ => {
                        // Outdated or lost (a resize on the way): configure again, then retry.
                        surface.configure(&renderer.device, config);
                        window.request_redraw();
                        return;
                    }
                };
                renderer.draw(&frame.texture, |_| {});
                window.pre_present_notify();
                renderer.queue.present(frame);
                match &mut self.frames_left {
                    Some(0 | 1) => event_loop.exit(),
                    Some(left) => {
                        *left -= 1;
                        window.request_redraw();
                    }
                    None => {}
                }
            }
            _ => {}
        }
    }
}

const USAGE: &str = "usage: wgpu-app [--png FILE] [--frames N]";

/// Where the frame goes (`--png FILE`) and how many frames the window shows (`--frames N`).
fn options() -> Result<(Option<String>, Option<u32>), String> {
    let (mut png, mut frames) = (None, None);
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match (arg.as_str(), args.next()) {
            ("--png", Some(path)) => png = Some(path),
            ("--frames", Some(n)) => {
                frames = Some(
                    n.parse()
                        .map_err(|_| format!("--frames {n}: not a count"))?,
                )
            }
            _ => {
                return Err(format!(
                    "{arg}: not an argument it takes, or its value is missing"
                ))
            }
        }
    }
    Ok((png, frames))
}

/// The window until it closes, or until it has shown `frames`.
fn show_window(frames: Option<u32>) -> Result<(), String> {
    let event_loop = EventLoop::new().map_err(|error| format!("no window: {error}"))?;
    let mut app = App {
        frames_left: frames,
        window: None,
        error: None,
    };
    event_loop
        .run_app(&mut app)
        .map_err(|error| error.to_string())?;
    app.error.map_or(Ok(()), Err)
}

fn main() -> ExitCode {
    let (png, frames) = match options() {
        Ok(options) => options,
        Err(error) => {
            eprintln!("wgpu-app: {error}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    let has_display = ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|name| std::env::var_os(name).is_some());
    let result = match png {
        Some(path) => write_png(&path),
        None if !has_display => write_png("frame.png"),
        None => show_window(frames),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("wgpu-app: {error}");
            ExitCode::FAILURE
        }
    }
}
