//! The on-tile renderer on GLES 3.2 (EGL surfaceless, `glow`): the fused paths read the
//! G-buffer by EXT_shader_framebuffer_fetch inside one framebuffer and invalidate it before
//! the frame ends; the two-pass path stores it to textures and samples them, as wgpu does.
//!
//! GL draws upside down here (`CLIP_Y_SIGN` -1): the framebuffer's first row is the image's
//! top, so `gl_FragCoord` counts rows from the top as WGSL's position does and `glReadPixels`
//! returns the image in order.
//!
//! Here: the renderer, its uploads and the frame's calls; `plans` makes each path's programs
//! and framebuffers.

use std::time::Instant;

use gbuffer_core::Named;
use glow::HasContext as _;

use gbuffer_codegen::emit::glsl::Include;
use gbuffer_gpu::gles::Gles;

mod plans;

use crate::fused_programs::{fused_programs, FusedDialect};
use crate::inputs::{Inputs, Texels};
use crate::mesh::Mesh;
use crate::on_tile::{tile_layout, Path, Stage, TileOptions};
use crate::options::{Frame, Options};
use crate::recording::{Attachment, Call, Load, Recording};
use crate::scene::{DECALS, POINT_LIGHT_COUNT};

const FETCH: &str = "GL_EXT_shader_framebuffer_fetch";
/// Texture units of the inputs: the bindings the WGSL gives them.
use crate::shaders::{
    ENVIRONMENT_BINDING as ENVIRONMENT_UNIT, LIGHT_MAP_BINDING as LIGHT_MAP_UNIT,
    LUT_BINDING as LUT_UNIT,
};
/// The two-pass lighting reads the G-buffer from unit 10 on.
const GBUFFER_UNIT: u32 = 10;

/// A GLES 3.2 context with the inputs and the mesh uploaded.
pub struct GlesRenderer {
    gles: Gles,
    mesh: glow::VertexArray,
    index_count: i32,
    volumes: glow::VertexArray,
    volume_indices: glow::Buffer,
}

/// A framebuffer attachment: its GL object and what the recording calls it.
struct Target {
    name: String,
    attachment: gbuffer_gpu::gles::Attachment,
    format: u32,
    bytes_per_pixel: u32,
}

/// The programs and framebuffers of one configuration, made once and drawn every frame.
struct Plan {
    path: Path,
    width: i32,
    height: i32,
    programs: Vec<(&'static str, glow::Program)>,
    /// Per program, which colour attachments of its framebuffer it writes (the rest are
    /// masked: an on-tile draw writes back only what it changed).
    writes: Vec<Vec<bool>>,
    framebuffers: Vec<glow::Framebuffer>,
    /// Per framebuffer, its colour attachments (location order) then its depth.
    targets: Vec<Vec<Target>>,
    depth: Vec<Target>,
}

impl GlesRenderer {
    /// A context on EGL's surfaceless platform, with the inputs and the mesh uploaded. The
    /// error says what is missing (libEGL, GLES 3.2).
    pub fn new(progress: &dyn Fn(&str)) -> Result<GlesRenderer, String> {
        let gles = Gles::new()?;
        progress(&format!("GLES: {}", gles.describe()));
        progress("baking the split-sum LUT, the light map and the prefiltered sky...");
        let inputs = Inputs::bake();
        let mesh = Mesh::scene();
        // SAFETY: objects of the current context; the slices outlive the uploads.
        unsafe {
            let gl = &gles.gl;
            upload(
                gl,
                ENVIRONMENT_UNIT,
                glow::RGBA8,
                glow::UNSIGNED_BYTE,
                &inputs.environment,
            )?;
            upload(gl, LUT_UNIT, glow::RGBA16F, glow::HALF_FLOAT, &[inputs.lut])?;
            upload(
                gl,
                LIGHT_MAP_UNIT,
                glow::RGBA8,
                glow::UNSIGNED_BYTE,
                &[inputs.light_map],
            )?;
            // As wgpu's samplers: trilinear, the environment's wrapping around the sky in u, the
            // LUT's and the light map's clamped to their edges.
            for (wrap, units) in [
                (glow::REPEAT, &[ENVIRONMENT_UNIT][..]),
                (glow::CLAMP_TO_EDGE, &[LUT_UNIT, LIGHT_MAP_UNIT][..]),
            ] {
                let sampler = gl.create_sampler()?;
                for (name, value) in [
                    (glow::TEXTURE_MIN_FILTER, glow::LINEAR_MIPMAP_LINEAR),
                    (glow::TEXTURE_MAG_FILTER, glow::LINEAR),
                    (glow::TEXTURE_WRAP_S, wrap),
                    (glow::TEXTURE_WRAP_T, glow::CLAMP_TO_EDGE),
                ] {
                    gl.sampler_parameter_i32(sampler, name, value as i32);
                }
                for &unit in units {
                    gl.bind_sampler(unit, Some(sampler));
                }
            }

            let vertices = buffer(gl, glow::ARRAY_BUFFER, bytemuck::cast_slice(&mesh.vertices))?;
            let mesh_array = gl.create_vertex_array()?;
            gl.bind_vertex_array(Some(mesh_array));
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(vertices));
            let stride = std::mem::size_of::<crate::mesh::Vertex>() as i32;
            gl.enable_vertex_attrib_array(0);
            gl.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, stride, 0);
            gl.enable_vertex_attrib_array(1);
            gl.vertex_attrib_pointer_f32(1, 3, glow::FLOAT, false, stride, 12);
            gl.enable_vertex_attrib_array(2);
            gl.vertex_attrib_pointer_i32(2, 1, glow::UNSIGNED_INT, stride, 24);
            buffer(
                gl,
                glow::ELEMENT_ARRAY_BUFFER,
                bytemuck::cast_slice(&mesh.indices),
            )?;
            // Volumes read their index from an instanced attribute: a buffer of 0, 1, 2, ...,
            // whose offset picks the volume (GLES has no base instance).
            let volume_count = (POINT_LIGHT_COUNT + DECALS.len()) as u32;
            let indices: Vec<u32> = (0..volume_count).collect();
            let volumes = gl.create_vertex_array()?;
            gl.bind_vertex_array(Some(volumes));
            let volume_indices = buffer(gl, glow::ARRAY_BUFFER, bytemuck::cast_slice(&indices))?;
            gl.enable_vertex_attrib_array(0);
            gl.vertex_attrib_divisor(0, 1);
            gl.bind_vertex_array(None);
            gles.check("uploading the inputs and the mesh")?;
            Ok(GlesRenderer {
                gles,
                mesh: mesh_array,
                index_count: mesh.indices.len() as i32,
                volumes,
                volume_indices,
            })
        }
    }

    /// Renders a frame and reads it back, with the calls it made.
    pub fn render(&self, tile: &TileOptions) -> Result<(Frame, Recording), String> {
        self.gles.make_current()?;
        let plan = self.plan(tile)?;
        let mut recording = Recording::default();
        let result = self.draw(&plan, &mut recording).and_then(|()| {
            let pixels = self.read_output(&plan, &mut recording)?;
            Ok(Frame {
                width: tile.options.width,
                height: tile.options.height,
                pixels,
            })
        });
        self.delete(plan);
        result.map(|frame| (frame, recording))
    }

    /// A frame of `tile` ready to time: each [`TimedFrame::seconds`] is one frame; the
    /// protocol around it is `gbuffer_gpu::timing`'s. Its GL objects go when it is dropped.
    pub fn timed_frame(&self, tile: &TileOptions) -> Result<TimedFrame<'_>, String> {
        self.gles.make_current()?;
        Ok(TimedFrame {
            renderer: self,
            plan: Some(self.plan(tile)?),
        })
    }

    /// The packed words the geometry writes (a debug view: the G-buffer stored, before decals
    /// and light), `layout.words()` per pixel, row by row, whatever the path.
    pub fn gbuffer_words(&self, options: &Options) -> Result<Vec<u32>, String> {
        self.gles.make_current()?;
        let layout = tile_layout(options)?;
        let (width, height) = (options.width as i32, options.height as i32);
        let model = layout.layout();
        // The packed fetch path's geometry program: it writes the words the layout packs.
        let fused = fused_programs(options, FusedDialect::Fetch(Include::FetchPacked))?;
        let interface = fused.interface;
        let geometry = &fused.programs[0];
        let vertex = geometry.glsl_vertex()?;
        let program = self.gles.link(vertex, &geometry.fragment)?;
        let targets = interface.attachments.len();
        let formats: Vec<(u32, u32)> = interface
            .attachments
            .iter()
            .map(|attachment| {
                let format = attachment.format;
                (format.gl.internal_format, format.webgpu.byte_cost)
            })
            .collect();
        // SAFETY: objects of the current context, deleted before returning.
        unsafe {
            let gl = &self.gles.gl;
            let (framebuffer, colours, depth) = self.framebuffer(&formats, width, height, true)?;
            gl.viewport(0, 0, width, height);
            for index in 0..targets {
                gl.color_mask_draw_buffer(index as u32, true, true, true, true);
                gl.clear_buffer_u32_slice(glow::COLOR, index as u32, &[0; 4]);
            }
            gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
            gl.enable(glow::DEPTH_TEST);
            gl.depth_mask(true);
            gl.depth_func(glow::LESS);
            gl.use_program(Some(program));
            gl.bind_vertex_array(Some(self.mesh));
            gl.draw_elements(glow::TRIANGLES, self.index_count, glow::UNSIGNED_INT, 0);
            let mut words = vec![0u32; (width * height) as usize * 4 * targets];
            let per_target = (width * height) as usize * 4;
            for index in 0..targets {
                gl.read_buffer(glow::COLOR_ATTACHMENT0 + index as u32);
                gl.read_pixels(
                    0,
                    0,
                    width,
                    height,
                    glow::RGBA_INTEGER,
                    glow::UNSIGNED_INT,
                    glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(
                        &mut words[index * per_target..(index + 1) * per_target],
                    ))),
                );
            }
            self.gles.check("reading the G-buffer back")?;
            gl.delete_program(program);
            gl.delete_framebuffer(framebuffer);
            for target in colours.into_iter().chain(depth) {
                target.attachment.delete(gl);
            }
            let targets: Vec<Vec<u32>> = words.chunks(per_target).map(<[u32]>::to_vec).collect();
            Ok(crate::gbuffers::texels_of(
                &targets,
                (width * height) as usize,
                model.words(),
            ))
        }
    }

    /// Draws a frame of the plan, recording its calls.
    fn draw(&self, plan: &Plan, recording: &mut Recording) -> Result<(), String> {
        // SAFETY: objects of the current context, made by `plan`.
        unsafe {
            let gl = &self.gles.gl;
            gl.viewport(0, 0, plan.width, plan.height);
            gl.enable(glow::DEPTH_TEST);
            let index = |name: &str| {
                plan.programs
                    .iter()
                    .position(|(program, _)| *program == name)
                    .expect("the plan has the program")
            };
            let program = |name: &str| plan.programs[index(name)].1;
            let draw = |recording: &mut Recording, name: &str, mode: Draw| {
                gl.use_program(Some(program(name)));
                for (buffer, &writes) in plan.writes[index(name)].iter().enumerate() {
                    gl.color_mask_draw_buffer(buffer as u32, writes, writes, writes, writes);
                }
                recording.push(Call::Draw {
                    program: name.to_string(),
                });
                match mode {
                    Draw::Mesh => {
                        gl.bind_vertex_array(Some(self.mesh));
                        gl.draw_elements(glow::TRIANGLES, self.index_count, glow::UNSIGNED_INT, 0);
                    }
                    Draw::Fullscreen => gl.draw_arrays(glow::TRIANGLES, 0, 3),
                    Draw::Volume(volume) => {
                        // The vertex stage reads the volume from the buffer of indices, at its
                        // offset; the fragment stage from `volume_index`.
                        gl.bind_vertex_array(Some(self.volumes));
                        gl.bind_buffer(glow::ARRAY_BUFFER, Some(self.volume_indices));
                        gl.vertex_attrib_pointer_i32(
                            0,
                            1,
                            glow::UNSIGNED_INT,
                            4,
                            4 * volume as i32,
                        );
                        let location = gl.get_uniform_location(program(name), "volume_index");
                        gl.uniform_1_u32(location.as_ref(), volume as u32);
                        gl.draw_arrays_instanced(glow::TRIANGLES, 0, 6, 1);
                    }
                }
            };
            self.begin(plan, 0, recording);
            gl.depth_mask(true);
            gl.depth_func(glow::LESS);
            draw(
                recording,
                if plan.path.is_fused() {
                    "geometry"
                } else {
                    "gbuffer"
                },
                Draw::Mesh,
            );
            if plan.path.is_fused() {
                // Everything after the geometry is drawn over the surfaces only (GREATER than
                // their depth) or the sky only (EQUAL to the cleared far plane).
                gl.depth_mask(false);
                gl.depth_func(glow::GREATER);
                for decal in 0..DECALS.len() {
                    draw(
                        recording,
                        Stage::Decal.name(),
                        Draw::Volume(POINT_LIGHT_COUNT + decal),
                    );
                }
                draw(recording, Stage::Lighting.name(), Draw::Fullscreen);
                draw(recording, Stage::Resolve.name(), Draw::Fullscreen);
                gl.depth_func(glow::EQUAL);
                draw(recording, Stage::Sky.name(), Draw::Fullscreen);
                // The G-buffer and depth die here: on a tiler they are never written out.
                let gbuffer = &plan.targets[0][..plan.targets[0].len() - 1];
                let mut attachments: Vec<u32> = (0..gbuffer.len() as u32)
                    .map(|index| glow::COLOR_ATTACHMENT0 + index)
                    .collect();
                attachments.push(glow::DEPTH_ATTACHMENT);
                gl.invalidate_framebuffer(glow::FRAMEBUFFER, &attachments);
                let mut names: Vec<String> =
                    gbuffer.iter().map(|target| target.name.clone()).collect();
                names.push("depth".into());
                recording.push(Call::Invalidate(names));
                self.end(plan, 0, recording);
            } else {
                // The lighting reads positions from the G-buffer: depth is not kept.
                gl.invalidate_framebuffer(glow::FRAMEBUFFER, &[glow::DEPTH_ATTACHMENT]);
                recording.push(Call::Invalidate(vec!["depth".into()]));
                self.end(plan, 0, recording);
                self.begin(plan, 1, recording);
                gl.disable(glow::DEPTH_TEST);
                for (index, target) in plan.targets[0].iter().enumerate() {
                    gl.active_texture(glow::TEXTURE0 + GBUFFER_UNIT + index as u32);
                    gl.bind_texture(glow::TEXTURE_2D, target.attachment.texture());
                    recording.push(Call::Sample(attachment(target)));
                }
                gl.active_texture(glow::TEXTURE0);
                draw(recording, "lighting and resolve", Draw::Fullscreen);
                self.end(plan, 1, recording);
            }
            self.gles.check("drawing the frame")
        }
    }

    /// Binds framebuffer `index` and clears it (every attachment starts cleared: nothing is
    /// loaded): the G-buffer of the two-pass path to all ones (its sky marker), the rest to 0,
    /// depth to the far plane.
    ///
    /// # Safety
    /// The context must be current.
    unsafe fn begin(&self, plan: &Plan, index: usize, recording: &mut Recording) {
        let gl = &self.gles.gl;
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(plan.framebuffers[index]));
        // Clears honour the colour masks: every attachment is written here.
        for buffer in 0..plan.targets[index].len() as u32 {
            gl.color_mask_draw_buffer(buffer, true, true, true, true);
        }
        let mut attachments = Vec::new();
        for (location, target) in plan.targets[index].iter().enumerate() {
            let integer = matches!(
                target.format,
                glow::RGBA32UI | glow::RG32UI | glow::R32UI | glow::RGBA8UI | glow::RGB10_A2UI
            );
            let signed = matches!(target.format, glow::RGBA8I);
            let sky_marker = plan.path == Path::TwoPass && target.name.starts_with("gbuffer");
            if integer {
                let value = if sky_marker { u32::MAX } else { 0 };
                gl.clear_buffer_u32_slice(glow::COLOR, location as u32, &[value; 4]);
            } else if signed {
                gl.clear_buffer_i32_slice(glow::COLOR, location as u32, &[0; 4]);
            } else {
                gl.clear_buffer_f32_slice(glow::COLOR, location as u32, &[0.0; 4]);
            }
            attachments.push((attachment(target), Load::Clear));
        }
        if index == 0 {
            gl.depth_mask(true);
            gl.clear_buffer_f32_slice(glow::DEPTH, 0, &[1.0]);
            attachments.push((attachment(&plan.depth[0]), Load::Clear));
        }
        recording.push(Call::BeginPass { attachments });
    }

    /// Ends framebuffer `index`'s pass in the recording: what was not invalidated is stored.
    fn end(&self, plan: &Plan, index: usize, recording: &mut Recording) {
        let invalidated = recording
            .invalidated()
            .iter()
            .map(|name| name.to_string())
            .collect::<Vec<_>>();
        let mut stored: Vec<String> = plan.targets[index]
            .iter()
            .map(|target| target.name.clone())
            .filter(|name| !invalidated.contains(name))
            .collect();
        if index == 0 && !invalidated.iter().any(|name| name == "depth") {
            stored.push("depth".into());
        }
        recording.push(Call::EndPass { stored });
    }

    /// Reads the output attachment back.
    fn read_output(&self, plan: &Plan, recording: &mut Recording) -> Result<Vec<[u8; 4]>, String> {
        let last = plan.targets.len() - 1;
        let location = plan.targets[last]
            .iter()
            .position(|target| target.name == "output")
            .expect("the plan has an output");
        let mut pixels = vec![[0u8; 4]; (plan.width * plan.height) as usize];
        // SAFETY: the slice holds width x height RGBA8 pixels; the pack alignment is 1.
        unsafe {
            let gl = &self.gles.gl;
            gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(plan.framebuffers[last]));
            gl.read_buffer(glow::COLOR_ATTACHMENT0 + location as u32);
            gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
            gl.read_pixels(
                0,
                0,
                plan.width,
                plan.height,
                glow::RGBA,
                glow::UNSIGNED_BYTE,
                glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut pixels))),
            );
        }
        recording.push(Call::ReadBack("output".into()));
        self.gles.check("reading the frame back")?;
        Ok(pixels)
    }

    fn delete(&self, plan: Plan) {
        // SAFETY: objects of the current context, not used again.
        unsafe {
            let gl = &self.gles.gl;
            for (_, program) in plan.programs {
                gl.delete_program(program);
            }
            for framebuffer in plan.framebuffers {
                gl.delete_framebuffer(framebuffer);
            }
            for target in plan.targets.into_iter().flatten().chain(plan.depth) {
                target.attachment.delete(gl);
            }
        }
    }
}

/// What a draw covers.
#[derive(Clone, Copy)]
enum Draw {
    Mesh,
    Fullscreen,
    /// A volume's screen rectangle: point light `n` below POINT_LIGHT_COUNT, then the decals.
    Volume(usize),
}

fn attachment(target: &Target) -> Attachment {
    Attachment {
        name: target.name.clone(),
        bytes_per_pixel: target.bytes_per_pixel,
    }
}

/// A buffer bound to `target` holding `bytes`.
///
/// # Safety
/// The context must be current.
unsafe fn buffer(gl: &glow::Context, target: u32, bytes: &[u8]) -> Result<glow::Buffer, String> {
    let buffer = gl.create_buffer()?;
    gl.bind_buffer(target, Some(buffer));
    gl.buffer_data_u8_slice(target, bytes, glow::STATIC_DRAW);
    Ok(buffer)
}

/// A texture of `mips` on `unit`, in `format` with texels of type `ty`.
///
/// # Safety
/// The context must be current.
unsafe fn upload(
    gl: &glow::Context,
    unit: u32,
    format: u32,
    ty: u32,
    mips: &[Texels],
) -> Result<glow::Texture, String> {
    let texture = gl.create_texture()?;
    gl.active_texture(glow::TEXTURE0 + unit);
    gl.bind_texture(glow::TEXTURE_2D, Some(texture));
    gl.tex_storage_2d(
        glow::TEXTURE_2D,
        mips.len() as i32,
        format,
        mips[0].width as i32,
        mips[0].height as i32,
    );
    gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
    for (level, mip) in mips.iter().enumerate() {
        gl.tex_sub_image_2d(
            glow::TEXTURE_2D,
            level as i32,
            0,
            0,
            mip.width as i32,
            mip.height as i32,
            glow::RGBA,
            ty,
            glow::PixelUnpackData::Slice(Some(&mip.bytes)),
        );
    }
    gl.active_texture(glow::TEXTURE0);
    Ok(texture)
}

/// A frame ready to time ([`GlesRenderer::timed_frame`]).
pub struct TimedFrame<'a> {
    renderer: &'a GlesRenderer,
    /// Taken by `drop`, which deletes its GL objects.
    plan: Option<Plan>,
}

impl TimedFrame<'_> {
    /// One frame's seconds, by the wall clock around the draws and `glFinish` (llvmpipe has no
    /// timer queries).
    pub fn seconds(&self) -> Result<f64, String> {
        let plan = self.plan.as_ref().ok_or("the frame was deleted")?;
        self.renderer.gles.make_current()?;
        let start = Instant::now();
        self.renderer.draw(plan, &mut Recording::default())?;
        // SAFETY: a plain synchronisation of the current context.
        unsafe { self.renderer.gles.gl.finish() };
        Ok(start.elapsed().as_secs_f64())
    }
}

impl Drop for TimedFrame<'_> {
    fn drop(&mut self) {
        if let Some(plan) = self.plan.take() {
            // The context must be current for the deletes; if it cannot be made so, the
            // objects go with the context.
            if self.renderer.gles.make_current().is_ok() {
                self.renderer.delete(plan);
            }
        }
    }
}
