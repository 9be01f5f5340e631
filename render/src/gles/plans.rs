//! The GLES backend's plans: the fused paths' one framebuffer and five programs (after the
//! checks that name what the driver lacks), the two-pass path's two, and the framebuffers and
//! programs they are made of.

use gbuffer_core::Named;
use glow::HasContext as _;

use gbuffer_codegen::emit::glsl::Include;

use crate::fused_programs::{fused_programs, FusedDialect, FusedPrograms};
use gbuffer_gpu::gles::Backing;

use super::{GlesRenderer, Plan, Target, FETCH};
use crate::gbuffers::PackedLayout;
use crate::glsl::{self, Dialect};
use crate::on_tile::{tile_layout, Path, Stage, TileOptions};
use crate::options::Options;

impl GlesRenderer {
    /// The programs and framebuffers of a configuration, after checking what it needs.
    pub(super) fn plan(&self, tile: &TileOptions) -> Result<Plan, String> {
        let options = &tile.options;
        let layout = tile_layout(options)?;
        let (width, height) = (options.width as i32, options.height as i32);
        match tile.path {
            Path::FetchNative | Path::FetchPacked => {
                if !self.gles.has_extension(FETCH) {
                    return Err(format!(
                        "the GLES driver ({}) lacks {FETCH}, which --path {} needs",
                        self.gles.describe(),
                        tile.path.name()
                    ));
                }
                self.fused_plan(options, layout, tile.path, (width, height))
            }
            Path::TwoPass => self.two_pass_plan(options, (width, height)),
            Path::Subpass | Path::LocalRead | Path::LocalReadOrdered => Err(format!(
                "--path {} is Vulkan's: use --backend vulkan",
                tile.path.name()
            )),
        }
    }

    /// The fused paths: one framebuffer of the G-buffer, the output and depth, five programs.
    pub(super) fn fused_plan(
        &self,
        options: &Options,
        layout: PackedLayout,
        path: Path,
        (width, height): (i32, i32),
    ) -> Result<Plan, String> {
        let dialect = FusedDialect::of(path).ok_or("the two-pass path is not fused")?;
        let FusedPrograms {
            include: kind,
            interface,
            programs: sources,
            ..
        } = fused_programs(options, dialect)?;
        let colour_attachments = interface.attachments.len() as i32 + 1;
        let draw_buffers = self.gles.limit(glow::MAX_DRAW_BUFFERS);
        let attachments_limit = self.gles.limit(glow::MAX_COLOR_ATTACHMENTS);
        if colour_attachments > draw_buffers.min(attachments_limit) {
            return Err(format!(
                "layout `{}` on --path {} needs {} colour attachments ({} for the G-buffer, 1 for \
                 the output), but the driver offers GL_MAX_DRAW_BUFFERS = {draw_buffers} and \
                 GL_MAX_COLOR_ATTACHMENTS = {attachments_limit}",
                layout.name(),
                path.name(),
                colour_attachments,
                interface.attachments.len()
            ));
        }
        let words_per_attachment = if kind == Include::FetchPacked { 4 } else { 1 };
        let writes: Vec<_> = Stage::ALL
            .iter()
            .map(|stage| stage.writes(layout, interface.attachments.len(), words_per_attachment))
            .collect();
        let mut programs = Vec::new();
        for source in sources {
            let linked = source
                .glsl_vertex()
                .and_then(|vertex| self.gles.link(vertex, &source.fragment));
            match linked {
                Ok(program) => programs.push((source.stage.name(), program)),
                Err(error) => {
                    // SAFETY: programs of the current context.
                    unsafe {
                        programs
                            .iter()
                            .for_each(|(_, p)| self.gles.gl.delete_program(*p))
                    };
                    return Err(format!("the {} program: {error}", source.stage.name()));
                }
            }
        }
        let formats: Vec<(u32, u32)> = interface
            .attachments
            .iter()
            .map(|attachment| {
                let bytes = if kind == Include::FetchPacked { 16 } else { 4 };
                (attachment.format.gl.internal_format, bytes)
            })
            .chain([(glow::RGBA8, 4)])
            .collect();
        // SAFETY: objects of the current context.
        let (framebuffer, mut colours, depth) =
            unsafe { self.framebuffer(&formats, width, height, false)? };
        for (index, target) in colours.iter_mut().enumerate() {
            target.name = if index < interface.attachments.len() {
                format!("gbuffer{index}")
            } else {
                "output".into()
            };
        }
        Ok(Plan {
            path,
            width,
            height,
            programs,
            writes,
            framebuffers: vec![framebuffer],
            targets: vec![colours],
            depth: depth.into_iter().collect(),
        })
    }

    /// The two-pass path: wgpu's G-buffer and lighting passes, translated, over two
    /// framebuffers; the second samples the first's G-buffer and depth.
    pub(super) fn two_pass_plan(
        &self,
        options: &Options,
        (width, height): (i32, i32),
    ) -> Result<Plan, String> {
        let gbuffer_wgsl = crate::shaders::gbuffer_wgsl(options, -1.0);
        let lighting_wgsl =
            crate::shaders::lighting_pass_wgsl(options, crate::shaders::Positions::Texel)?;
        let program = |wgsl: &str, vertex: &str, fragment: &str| -> Result<glow::Program, String> {
            let vertex = glsl::write_stage(wgsl, naga::ShaderStage::Vertex, vertex, Dialect::Gles)?;
            let fragment =
                glsl::write_stage(wgsl, naga::ShaderStage::Fragment, fragment, Dialect::Gles)?;
            self.gles.link(&vertex.text, &fragment.text)
        };
        let gbuffer = program(&gbuffer_wgsl, "geometry_vertex", "gbuffer_main")?;
        let lighting = program(&lighting_wgsl, "full_screen", "lighting_resolve_main")?;
        let formats: Vec<(u32, u32)> = options
            .gbuffer
            .packed_targets()?
            .into_iter()
            .map(|target| {
                let target = target.target();
                (target.gl.internal_format, target.webgpu.byte_cost)
            })
            .collect();
        // SAFETY: objects of the current context.
        unsafe {
            let (first, mut gbuffer_targets, depth) =
                self.framebuffer(&formats, width, height, true)?;
            for (index, target) in gbuffer_targets.iter_mut().enumerate() {
                target.name = format!("gbuffer{index}");
            }
            let (second, mut output, _) =
                self.framebuffer(&[(glow::RGBA8, 4)], width, height, false)?;
            output[0].name = "output".into();
            Ok(Plan {
                path: Path::TwoPass,
                width,
                height,
                programs: vec![("gbuffer", gbuffer), ("lighting and resolve", lighting)],
                writes: vec![vec![true; formats.len()], vec![true]],
                framebuffers: vec![first, second],
                targets: vec![gbuffer_targets, output],
                depth: depth.into_iter().collect(),
            })
        }
    }

    /// A framebuffer of colour attachments (internal format, bytes per pixel) and a 32-bit
    /// float depth: renderbuffers where nothing samples them, textures where `sampled`.
    ///
    /// # Safety
    /// The context must be current.
    pub(super) unsafe fn framebuffer(
        &self,
        formats: &[(u32, u32)],
        width: i32,
        height: i32,
        sampled: bool,
    ) -> Result<(glow::Framebuffer, Vec<Target>, Option<Target>), String> {
        let backing = if sampled {
            Backing::Textures
        } else {
            Backing::Renderbuffers
        };
        let internal_formats: Vec<u32> = formats.iter().map(|(format, _)| *format).collect();
        let depth_format = glow::DEPTH_COMPONENT32F;
        let made = self.gles.framebuffer_of(
            &internal_formats,
            Some(depth_format),
            width,
            height,
            backing,
        )?;
        let colours = made
            .colours
            .iter()
            .zip(formats)
            .map(|(&attachment, &(format, bytes_per_pixel))| Target {
                name: String::new(),
                attachment,
                format,
                bytes_per_pixel,
            })
            .collect();
        let depth = made.depth.map(|attachment| Target {
            name: "depth".into(),
            attachment,
            format: depth_format,
            bytes_per_pixel: 4,
        });
        Ok((made.framebuffer, colours, depth))
    }
}
