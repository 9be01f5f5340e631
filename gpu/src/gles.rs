//! A GLES 3.2 context on a real driver, without a window: EGL's surfaceless platform (Mesa's
//! llvmpipe here), loaded at run time with `khronos-egl`, and `glow` for the GL calls. Tests
//! compile GLSL ES, draw fullscreen passes into framebuffers and read the attachments back.

use glow::HasContext as _;

/// EGL_PLATFORM_SURFACELESS_MESA (EGL_MESA_platform_surfaceless).
const PLATFORM_SURFACELESS_MESA: khronos_egl::Enum = 0x31DD;

type Egl = khronos_egl::DynamicInstance<khronos_egl::EGL1_5>;

/// A current GLES 3.2 context.
pub struct Gles {
    /// The GL functions of the context.
    pub gl: glow::Context,
    egl: Egl,
    display: khronos_egl::Display,
    context: khronos_egl::Context,
}

impl Gles {
    /// Creates a GLES 3.2 context on EGL's surfaceless platform and makes it current on this
    /// thread. The error says what was missing (libEGL, the platform, a GLES 3.2 config).
    pub fn new() -> Result<Gles, String> {
        // SAFETY: loading libEGL runs its initialisers; it is the system's EGL library.
        let egl = unsafe { Egl::load_required() }.map_err(|error| {
            format!("cannot load libEGL ({error}): install Debian's libegl1 and libegl-mesa0")
        })?;
        let client_extensions = egl
            .query_string(None, khronos_egl::EXTENSIONS)
            .map(|text| text.to_string_lossy().into_owned())
            .unwrap_or_default();
        if !client_extensions.contains("EGL_MESA_platform_surfaceless") {
            return Err(format!(
                "EGL has no surfaceless platform (EGL_MESA_platform_surfaceless); its client \
                 extensions: {client_extensions}"
            ));
        }
        // SAFETY: the surfaceless platform takes no native display.
        let display = unsafe {
            egl.get_platform_display(
                PLATFORM_SURFACELESS_MESA,
                khronos_egl::DEFAULT_DISPLAY,
                &[khronos_egl::ATTRIB_NONE],
            )
        }
        .map_err(|error| format!("eglGetPlatformDisplay(surfaceless): {error}"))?;
        egl.initialize(display)
            .map_err(|error| format!("eglInitialize: {error}"))?;
        let config = egl
            .choose_first_config(
                display,
                &[
                    khronos_egl::RENDERABLE_TYPE,
                    khronos_egl::OPENGL_ES3_BIT,
                    khronos_egl::SURFACE_TYPE,
                    khronos_egl::PBUFFER_BIT,
                    khronos_egl::NONE,
                ],
            )
            .map_err(|error| format!("eglChooseConfig: {error}"))?
            .ok_or("EGL offers no GLES 3 config")?;
        egl.bind_api(khronos_egl::OPENGL_ES_API)
            .map_err(|error| format!("eglBindAPI(GLES): {error}"))?;
        let context = egl
            .create_context(
                display,
                config,
                None,
                &[
                    khronos_egl::CONTEXT_MAJOR_VERSION,
                    3,
                    khronos_egl::CONTEXT_MINOR_VERSION,
                    2,
                    khronos_egl::NONE,
                ],
            )
            .map_err(|error| format!("no GLES 3.2 context: {error}"))?;
        egl.make_current(display, None, None, Some(context))
            .map_err(|error| format!("eglMakeCurrent (surfaceless): {error}"))?;
        // SAFETY: the context is current on this thread; the loader returns its entry points.
        let gl = unsafe {
            glow::Context::from_loader_function(|name| {
                egl.get_proc_address(name)
                    .map_or(std::ptr::null(), |function| function as *const _)
            })
        };
        Ok(Gles {
            gl,
            egl,
            display,
            context,
        })
    }

    /// Makes the context current on this thread again: other GL users (wgpu's GL backend
    /// among them) may have made theirs current since.
    pub fn make_current(&self) -> Result<(), String> {
        // Only when it is not: making current again costs a driver round trip.
        if self.egl.get_current_context() == Some(self.context) {
            return Ok(());
        }
        self.egl
            .make_current(self.display, None, None, Some(self.context))
            .map_err(|error| format!("eglMakeCurrent (surfaceless): {error}"))
    }

    /// The renderer and version strings, for test output.
    pub fn describe(&self) -> String {
        // SAFETY: plain queries on the current context.
        unsafe {
            format!(
                "{} ({})",
                self.gl.get_parameter_string(glow::RENDERER),
                self.gl.get_parameter_string(glow::VERSION)
            )
        }
    }

    /// Whether the context offers a GL extension.
    pub fn has_extension(&self, name: &str) -> bool {
        self.gl.supported_extensions().contains(name)
    }

    /// An integer limit, such as `glow::MAX_DRAW_BUFFERS`.
    pub fn limit(&self, parameter: u32) -> i32 {
        // SAFETY: a plain query on the current context.
        unsafe { self.gl.get_parameter_i32(parameter) }
    }

    /// Compiles and links a fullscreen-triangle vertex shader with `fragment`; the error holds
    /// the driver's log and the numbered source.
    pub fn program(&self, fragment: &str) -> Result<glow::Program, String> {
        let version = fragment.lines().next().unwrap_or("#version 300 es");
        let vertex = crate::fullscreen::fullscreen_vertex_glsl(version, false);
        self.link(&vertex, fragment)
    }

    /// Compiles and links a program of `vertex` and `fragment`; the error holds the driver's
    /// log and the numbered source of the shader it concerns.
    pub fn link(&self, vertex: &str, fragment: &str) -> Result<glow::Program, String> {
        // SAFETY: GL objects of the current context, deleted on every path.
        unsafe {
            let gl = &self.gl;
            let program = gl.create_program()?;
            let mut shaders = Vec::new();
            for (stage, source) in [
                (glow::VERTEX_SHADER, vertex),
                (glow::FRAGMENT_SHADER, fragment),
            ] {
                let shader = gl.create_shader(stage)?;
                gl.shader_source(shader, source);
                gl.compile_shader(shader);
                if !gl.get_shader_compile_status(shader) {
                    let log = gl.get_shader_info_log(shader);
                    gl.delete_shader(shader);
                    shaders
                        .into_iter()
                        .for_each(|shader| gl.delete_shader(shader));
                    gl.delete_program(program);
                    return Err(format!("{log}\n{}", crate::tools::numbered(source)));
                }
                gl.attach_shader(program, shader);
                shaders.push(shader);
            }
            gl.link_program(program);
            for shader in shaders {
                gl.delete_shader(shader);
            }
            if !gl.get_program_link_status(program) {
                let log = gl.get_program_info_log(program);
                gl.delete_program(program);
                return Err(format!("link: {log}\n{}", crate::tools::numbered(fragment)));
            }
            Ok(program)
        }
    }

    /// The GL error flag, as an error naming `what` was being done.
    pub fn check(&self, what: &str) -> Result<(), String> {
        // SAFETY: a plain query on the current context.
        match unsafe { self.gl.get_error() } {
            glow::NO_ERROR => Ok(()),
            error => Err(format!("GL error {error:#x} while {what}")),
        }
    }
}

impl Drop for Gles {
    fn drop(&mut self) {
        let _ = self.egl.make_current(self.display, None, None, None);
        let _ = self.egl.destroy_context(self.display, self.context);
        // The display is not terminated: EGL hands every context of the process the same
        // surfaceless display, and terminating it under another thread's current context
        // crashed Mesa (a SIGSEGV in the GLES tests, which run contexts on parallel threads).
        // It lives until the process ends.
    }
}

/// A framebuffer of colour attachments (and perhaps a depth attachment), each a texture or a
/// renderbuffer of one internal format.
pub struct Framebuffer {
    /// The framebuffer object.
    pub framebuffer: glow::Framebuffer,
    /// The colour attachments, in location order.
    pub colours: Vec<Attachment>,
    /// The depth attachment, where one was asked for.
    pub depth: Option<Attachment>,
    /// Width, pixels.
    pub width: i32,
    /// Height, pixels.
    pub height: i32,
}

/// One attachment of a [`Framebuffer`]: a texture where it is sampled, a renderbuffer where
/// nothing reads it but the render pass (on a tiler it may then never reach memory).
#[derive(Clone, Copy, Debug)]
pub enum Attachment {
    /// A texture with one level, filtered NEAREST (an integer texture is incomplete otherwise).
    Texture(glow::Texture),
    /// A renderbuffer.
    Renderbuffer(glow::Renderbuffer),
}

impl Attachment {
    /// The texture, where the attachment is one.
    pub fn texture(self) -> Option<glow::Texture> {
        match self {
            Attachment::Texture(texture) => Some(texture),
            Attachment::Renderbuffer(_) => None,
        }
    }

    /// Deletes the texture or renderbuffer.
    ///
    /// # Safety
    /// `gl` must be current and own the attachment, which is not used again.
    pub unsafe fn delete(self, gl: &glow::Context) {
        match self {
            Attachment::Texture(texture) => gl.delete_texture(texture),
            Attachment::Renderbuffer(buffer) => gl.delete_renderbuffer(buffer),
        }
    }
}

/// How a framebuffer's attachments are backed ([`Attachment`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backing {
    /// Textures, which later passes can sample.
    Textures,
    /// Renderbuffers, which only the render pass reads.
    Renderbuffers,
}

impl Gles {
    /// A framebuffer with one colour texture per internal format, all drawn to, and its
    /// viewport set.
    pub fn framebuffer(
        &self,
        formats: &[u32],
        width: i32,
        height: i32,
    ) -> Result<Framebuffer, String> {
        self.framebuffer_of(formats, None, width, height, Backing::Textures)
    }

    /// A framebuffer with one colour attachment per internal format, all drawn to, a depth
    /// attachment of `depth`'s format where it is given, each backed as `backing` says, and its
    /// viewport set. An incomplete framebuffer is an error naming the formats.
    pub fn framebuffer_of(
        &self,
        formats: &[u32],
        depth: Option<u32>,
        width: i32,
        height: i32,
        backing: Backing,
    ) -> Result<Framebuffer, String> {
        // SAFETY: GL objects of the current context.
        unsafe {
            let gl = &self.gl;
            let framebuffer = gl.create_framebuffer()?;
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(framebuffer));
            // The textures are made on the active unit; what it had bound is bound again below,
            // so a caller's inputs stay where it put them.
            let bound = gl.get_parameter_texture(glow::TEXTURE_BINDING_2D);
            let attach = |format: u32, attachment: u32| -> Result<Attachment, String> {
                Ok(match backing {
                    Backing::Textures => {
                        let texture = gl.create_texture()?;
                        gl.bind_texture(glow::TEXTURE_2D, Some(texture));
                        gl.tex_storage_2d(glow::TEXTURE_2D, 1, format, width, height);
                        for filter in [glow::TEXTURE_MIN_FILTER, glow::TEXTURE_MAG_FILTER] {
                            gl.tex_parameter_i32(glow::TEXTURE_2D, filter, glow::NEAREST as i32);
                        }
                        gl.framebuffer_texture_2d(
                            glow::FRAMEBUFFER,
                            attachment,
                            glow::TEXTURE_2D,
                            Some(texture),
                            0,
                        );
                        Attachment::Texture(texture)
                    }
                    Backing::Renderbuffers => {
                        let renderbuffer = gl.create_renderbuffer()?;
                        gl.bind_renderbuffer(glow::RENDERBUFFER, Some(renderbuffer));
                        gl.renderbuffer_storage(glow::RENDERBUFFER, format, width, height);
                        gl.framebuffer_renderbuffer(
                            glow::FRAMEBUFFER,
                            attachment,
                            glow::RENDERBUFFER,
                            Some(renderbuffer),
                        );
                        Attachment::Renderbuffer(renderbuffer)
                    }
                })
            };
            let mut colours = Vec::new();
            for (index, &format) in formats.iter().enumerate() {
                colours.push(attach(format, glow::COLOR_ATTACHMENT0 + index as u32)?);
            }
            let depth = match depth {
                Some(format) => Some(attach(format, glow::DEPTH_ATTACHMENT)?),
                None => None,
            };
            gl.bind_texture(glow::TEXTURE_2D, bound);
            let buffers: Vec<u32> = (0..formats.len() as u32)
                .map(|index| glow::COLOR_ATTACHMENT0 + index)
                .collect();
            gl.draw_buffers(&buffers);
            let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
            self.check("creating the framebuffer")?;
            if status != glow::FRAMEBUFFER_COMPLETE {
                let depth = depth.map_or(String::new(), |_| " with a depth attachment".into());
                return Err(format!(
                    "the driver cannot render to attachments of formats {formats:#x?}{depth} \
                     (framebuffer status {status:#x})"
                ));
            }
            gl.viewport(0, 0, width, height);
            Ok(Framebuffer {
                framebuffer,
                colours,
                depth,
                width,
                height,
            })
        }
    }

    /// Deletes a framebuffer and its attachments.
    pub fn delete(&self, framebuffer: Framebuffer) {
        // SAFETY: objects of the current context, not used again.
        unsafe {
            self.gl.delete_framebuffer(framebuffer.framebuffer);
            for attachment in framebuffer.colours.into_iter().chain(framebuffer.depth) {
                attachment.delete(&self.gl);
            }
        }
    }

    /// An `R32UI` texture of `width` x `height` holding `values` row by row, bound to unit 0.
    pub fn uint_texture(
        &self,
        values: &[u32],
        width: i32,
        height: i32,
    ) -> Result<glow::Texture, String> {
        assert_eq!(values.len(), (width * height) as usize);
        // SAFETY: GL objects of the current context; the slice outlives the upload.
        unsafe {
            let gl = &self.gl;
            let texture = gl.create_texture()?;
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            gl.tex_storage_2d(glow::TEXTURE_2D, 1, glow::R32UI, width, height);
            // An integer texture is incomplete, and reads as zero, under linear filtering.
            for filter in [glow::TEXTURE_MIN_FILTER, glow::TEXTURE_MAG_FILTER] {
                gl.tex_parameter_i32(glow::TEXTURE_2D, filter, glow::NEAREST as i32);
            }
            gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 4);
            gl.tex_sub_image_2d(
                glow::TEXTURE_2D,
                0,
                0,
                0,
                width,
                height,
                glow::RED_INTEGER,
                glow::UNSIGNED_INT,
                glow::PixelUnpackData::Slice(Some(bytemuck::cast_slice(values))),
            );
            self.check("uploading the inputs")?;
            Ok(texture)
        }
    }

    /// A zeroed shader storage buffer of `words` u32, bound at binding 0.
    pub fn storage_buffer(&self, words: usize) -> Result<glow::Buffer, String> {
        // SAFETY: GL objects of the current context.
        unsafe {
            let gl = &self.gl;
            let buffer = gl.create_buffer()?;
            gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(buffer));
            gl.buffer_data_u8_slice(
                glow::SHADER_STORAGE_BUFFER,
                &vec![0u8; words * 4],
                glow::DYNAMIC_READ,
            );
            gl.bind_buffer_base(glow::SHADER_STORAGE_BUFFER, 0, Some(buffer));
            self.check("creating the storage buffer")?;
            Ok(buffer)
        }
    }

    /// Reads a storage buffer back after the draws that wrote it.
    pub fn read_storage_buffer(
        &self,
        buffer: glow::Buffer,
        words: usize,
    ) -> Result<Vec<u32>, String> {
        // SAFETY: the mapping is read within its bounds and unmapped before returning.
        unsafe {
            let gl = &self.gl;
            gl.memory_barrier(glow::BUFFER_UPDATE_BARRIER_BIT);
            gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(buffer));
            let pointer = gl.map_buffer_range(
                glow::SHADER_STORAGE_BUFFER,
                0,
                (words * 4) as i32,
                glow::MAP_READ_BIT,
            );
            if pointer.is_null() {
                return Err("cannot map the storage buffer".into());
            }
            let values = std::slice::from_raw_parts(pointer as *const u32, words).to_vec();
            gl.unmap_buffer(glow::SHADER_STORAGE_BUFFER);
            self.check("reading the storage buffer")?;
            Ok(values)
        }
    }

    /// Draws one fullscreen triangle with `program` into the bound framebuffer.
    pub fn draw_fullscreen(&self, program: glow::Program) -> Result<(), String> {
        // SAFETY: GL objects of the current context.
        unsafe {
            let gl = &self.gl;
            let vertex_array = gl.create_vertex_array()?;
            gl.bind_vertex_array(Some(vertex_array));
            gl.use_program(Some(program));
            if let Some(location) = gl.get_uniform_location(program, "harness_inputs") {
                gl.uniform_1_i32(Some(&location), 0);
            }
            gl.draw_arrays(glow::TRIANGLES, 0, 3);
            gl.delete_vertex_array(vertex_array);
            self.check("drawing")
        }
    }

    /// Reads colour attachment `index` with the given pixel format and type into `bytes`.
    pub fn read_attachment(
        &self,
        framebuffer: &Framebuffer,
        index: u32,
        format: u32,
        ty: u32,
        bytes: &mut [u8],
    ) -> Result<(), String> {
        // SAFETY: `bytes` is large enough for the rectangle at this format and type (the
        // caller sizes it), and the pack alignment is 1.
        unsafe {
            let gl = &self.gl;
            gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(framebuffer.framebuffer));
            gl.read_buffer(glow::COLOR_ATTACHMENT0 + index);
            gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
            gl.read_pixels(
                0,
                0,
                framebuffer.width,
                framebuffer.height,
                format,
                ty,
                glow::PixelPackData::Slice(Some(bytes)),
            );
            self.check(&format!(
                "reading attachment {index} as format {format:#x}, type {ty:#x}"
            ))
        }
    }
}
