//! What a shader costs on the GPUs users ship on, without the GPUs: Mesa's production
//! compilers for Mali (panfrost), Adreno (freedreno and turnip), AMD (RADV/ACO) and NVIDIA
//! (nouveau) run here because Mesa's drm-shim fakes each GPU's kernel driver; the arm64-only
//! drivers run under qemu-user from Debian's arm64 packages. A small C helper
//! (`cost/helper/shader_stats.c`) compiles the shader inside the driver and prints what the
//! compiler reports; this crate prepares the shader as a backend would see it ([`Shader`]),
//! runs the helper for each [`Target`] and reads the statistics into [`Statistics`].
//!
//! `scripts/cost-setup.sh` installs what it needs on Debian 12. No Mesa driver offers
//! `GL_EXT_shader_pixel_local_storage`, so the PLS includes cannot be costed here; freedreno and
//! panfrost offer `GL_EXT_shader_framebuffer_fetch`, so the fetch includes can, as shipped.
//!
//! ```no_run
//! use gbuffer_cost::{measure, Shader, Stage, Target};
//!
//! let shader = Shader::glsl(Stage::Fragment, "#version 310 es\n\
//!     precision highp float;\n\
//!     in vec4 colour;\n\
//!     layout(location = 0) out highp uint word;\n\
//!     void main() { word = packUnorm4x8(colour); }\n");
//! let target = Target::named("mali-g610")?;
//! for measurement in measure(&[shader], &target, false)? {
//!     let measurement = measurement?;
//!     println!("{}: {} instructions", measurement.device, measurement.statistics.instructions);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

mod run;
mod shader;
mod statistics;
mod target;

use std::fmt;

use gbuffer_core::Named;
use serde::Serialize;

pub use run::{Setup, DEFAULT_ROOT};
pub use shader::{GlesForm, Rendering, Shader, ShaderError, VulkanForm};
pub use statistics::{parse, parse_vertex, Cycles, Statistic, Statistics};
pub use target::{Api, Architecture, Compiler, Target, DEFAULT_TARGETS, TARGETS};

use run::Scratch;

/// The stages whose cost is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Stage {
    /// A fragment shader: per pixel.
    Fragment,
    /// A compute shader: per invocation.
    Compute,
}

gbuffer_core::named!(
    /// `fragment` or `compute`, as the helper takes it.
    Stage {
        Fragment => "fragment",
        Compute => "compute",
    }
);

/// Why a target could not cost anything.
#[derive(Clone, Debug, PartialEq)]
pub enum CostError {
    /// Something the target needs is not installed: names it and the setup script.
    NotSetUp(String),
    /// The driver answered as another device: the shim failed and Mesa fell back to software
    /// (llvmpipe, lavapipe), whose numbers would be a CPU's.
    Fallback {
        /// The target asked for.
        target: &'static str,
        /// What the driver called itself.
        device: String,
    },
    /// The driver did not start or did not finish.
    Driver(String),
}

impl fmt::Display for CostError {
    fn fmt(&self, formatter: &mut fmt::Formatter) -> fmt::Result {
        match self {
            CostError::NotSetUp(message) | CostError::Driver(message) => {
                formatter.write_str(message)
            }
            CostError::Fallback { target, device } => write!(
                formatter,
                "{target}: the driver answered as `{device}`, not the GPU asked for (the drm-shim \
                 failed and Mesa fell back); its numbers are refused"
            ),
        }
    }
}

impl std::error::Error for CostError {}

/// One shader's cost on one target.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Measurement {
    /// The target's name.
    pub target: &'static str,
    /// The driver's own name for the device and its version (`Mali-G610 (Panfrost), OpenGL ES
    /// 3.1 Mesa 25.0.7-2~bpo12+1`).
    pub device: String,
    /// What the compiler reported: the shader's stage (a Vulkan pipeline's fragment stage).
    pub statistics: Statistics,
    /// A Vulkan pipeline's vertex stage, where the shader had one and the driver reports
    /// pipeline executables (turnip, RADV); `None` otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vertex: Option<Statistics>,
    /// The compiler's listing, when asked for (Vulkan's internal representations; on GL, what
    /// the compiler printed with its debug flags).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub disassembly: Option<String>,
}

/// Compiles each shader on `target` (in one run of the driver) and reads what its compiler
/// reports. The outer error is the target's (not set up, fallen back, failed); each inner one
/// is a shader's (does not translate, compile or link).
pub fn measure(
    shaders: &[Shader],
    target: &Target,
    disassembly: bool,
) -> Result<Vec<Result<Measurement, String>>, CostError> {
    let setup = Setup::find();
    setup.check(target)?;
    // GL compilers print their listings on standard error, all shaders together, and
    // panfrost's listing flag silences its statistics: with a listing asked for, each shader
    // gets a run for its statistics and one for its listing.
    if disassembly && target.api == Api::Gles {
        let mut all = Vec::new();
        for shader in shaders {
            let mut results = measure(std::slice::from_ref(shader), target, false)?;
            if let Some(Ok(measurement)) = results.first_mut() {
                measurement.disassembly = gl_listing(&setup, shader, target)?;
            }
            all.extend(results);
        }
        return Ok(all);
    }
    let scratch = Scratch::new()?;
    let mut arguments = Vec::new();
    let mut prepared = Vec::new();
    for (index, shader) in shaders.iter().enumerate() {
        match prepare(shader, target, &scratch, index, disassembly) {
            Ok(shader_arguments) => {
                if !arguments.is_empty() {
                    arguments.push("--".to_string());
                }
                arguments.extend(shader_arguments);
                prepared.push(Ok(()));
            }
            Err(error) => prepared.push(Err(error)),
        }
    }
    let mut sections = Vec::new();
    let mut device = String::new();
    if !arguments.is_empty() {
        let mode = match target.api {
            Api::Gles => "gl",
            Api::Vulkan => "vulkan",
        };
        arguments.insert(0, mode.to_string());
        let (stdout, _) = setup.run(target, &arguments, disassembly)?;
        device = device_of(&stdout, target)?;
        sections = split_sections(&stdout);
    }
    let mut sections = sections.into_iter();
    Ok(shaders
        .iter()
        .zip(prepared)
        .map(|(shader, prepared)| {
            prepared?;
            let section = sections
                .next()
                .ok_or_else(|| "the driver stopped before this shader".to_string())?;
            if let Some(error) = section.error {
                return Err(error);
            }
            let lines: Vec<&str> = section.lines.iter().map(String::as_str).collect();
            let statistics = parse(target.compiler, shader.stage(), &lines).ok_or_else(|| {
                format!(
                    "{} printed no statistics for the {} shader",
                    target.name,
                    shader.stage().name()
                )
            })?;
            let vertex = (target.api == Api::Vulkan)
                .then(|| parse_vertex(target.compiler, &lines))
                .flatten();
            Ok(Measurement {
                target: target.name,
                device: device.clone(),
                statistics,
                vertex,
                disassembly: section.disassembly,
            })
        })
        .collect())
}

/// What a GL compiler prints of `shader` with its listing flag (`None` where it prints
/// nothing: nouveau lists only in Mesa's debug builds). Freedreno and nouveau print it on
/// standard error; panfrost on standard output, after the helper's own lines (`renderer:`,
/// `version:`, `shader: 0`), which are left out.
fn gl_listing(
    setup: &Setup,
    shader: &Shader,
    target: &Target,
) -> Result<Option<String>, CostError> {
    let scratch = Scratch::new()?;
    let Ok(mut arguments) = prepare(shader, target, &scratch, 0, true) else {
        return Ok(None);
    };
    arguments.insert(0, "gl".to_string());
    let (stdout, stderr) = setup.run(target, &arguments, true)?;
    let helper_line = |line: &&str| {
        line.starts_with("renderer: ") || line.starts_with("version: ") || *line == "shader: 0"
    };
    let listing: String = stdout
        .lines()
        .skip_while(helper_line)
        .chain(stderr.lines())
        .map(|line| format!("{line}\n"))
        .collect();
    Ok((!listing.trim().is_empty()).then_some(listing))
}

/// Writes `shader`'s files for `target` and returns the helper's arguments for it.
fn prepare(
    shader: &Shader,
    target: &Target,
    scratch: &Scratch,
    index: usize,
    disassembly: bool,
) -> Result<Vec<String>, String> {
    let scratch_error = |error: CostError| error.to_string();
    let mut arguments = vec![shader.stage().name().to_string()];
    match target.api {
        Api::Gles => {
            let form = shader.gles()?;
            arguments.push(
                scratch
                    .write(&format!("{index}.glsl"), form.shader.as_bytes())
                    .map_err(scratch_error)?,
            );
            if let Some(vertex) = form.vertex {
                arguments.push(
                    scratch
                        .write(&format!("{index}.vert.glsl"), vertex.as_bytes())
                        .map_err(scratch_error)?,
                );
            }
        }
        Api::Vulkan => {
            let form = shader.vulkan()?;
            let bytes = bytemuck::cast_slice::<u32, u8>;
            arguments.push(
                scratch
                    .write(&format!("{index}.spv"), bytes(&form.shader))
                    .map_err(scratch_error)?,
            );
            if let Some(vertex) = form.vertex {
                arguments.push(
                    scratch
                        .write(&format!("{index}.vert.spv"), bytes(&vertex))
                        .map_err(scratch_error)?,
                );
            }
            arguments.extend(["--entry".to_string(), form.entry]);
            if let Some(entry) = form.vertex_entry {
                arguments.extend(["--vertex-entry".to_string(), entry]);
            }
            for descriptor in form.descriptors {
                arguments.extend(["--descriptor".to_string(), descriptor]);
            }
            for color in form.colors {
                arguments.extend(["--color".to_string(), color]);
            }
            for attribute in form.attributes {
                arguments.extend(["--attribute".to_string(), attribute]);
            }
            if form.push_constant_bytes > 0 {
                arguments.extend([
                    "--push-constants".to_string(),
                    form.push_constant_bytes.to_string(),
                ]);
            }
            if form.rendering != Rendering::RenderPass {
                arguments.extend(["--rendering".to_string(), form.rendering.name().to_string()]);
            }
            if disassembly {
                arguments.push("--disassembly".to_string());
            }
        }
    }
    Ok(arguments)
}

/// The driver's name for the device and its version, from the helper's first lines; a device
/// that is not the target's is a fallback.
fn device_of(stdout: &str, target: &Target) -> Result<String, CostError> {
    let value = |key: &str| {
        stdout
            .lines()
            .find_map(|line| line.strip_prefix(key))
            .map(str::trim)
    };
    let (name, version) = match target.api {
        Api::Gles => (value("renderer: "), value("version: ")),
        Api::Vulkan => (value("device: "), value("driver: ")),
    };
    let name = name.ok_or_else(|| {
        CostError::Driver(format!("{}: the helper printed no device", target.name))
    })?;
    if !name.contains(target.expected_device) {
        return Err(CostError::Fallback {
            target: target.name,
            device: name.to_string(),
        });
    }
    Ok(match version {
        Some(version) => format!("{name}, {version}"),
        None => name.to_string(),
    })
}

/// One shader's part of the helper's output.
struct Section {
    lines: Vec<String>,
    error: Option<String>,
    disassembly: Option<String>,
}

/// The helper's output cut at its `shader: N` lines; Vulkan listings (`representation:` to
/// `end-representation`) are taken out of the lines into the section's disassembly.
fn split_sections(stdout: &str) -> Vec<Section> {
    let mut sections: Vec<Section> = Vec::new();
    let mut listing: Option<String> = None;
    for line in stdout.lines() {
        if let Some(text) = listing.as_mut() {
            if line == "end-representation" {
                let text = listing.take().unwrap_or_default();
                if let Some(section) = sections.last_mut() {
                    section
                        .disassembly
                        .get_or_insert_with(String::new)
                        .push_str(&text);
                }
            } else {
                text.push_str(line);
                text.push('\n');
            }
            continue;
        }
        if line.starts_with("shader: ") {
            sections.push(Section {
                lines: Vec::new(),
                error: None,
                disassembly: None,
            });
        } else if let Some(section) = sections.last_mut() {
            if let Some(name) = line.strip_prefix("representation: ") {
                listing = Some(format!("; {name}\n"));
            } else if let Some(error) = line.strip_prefix("error: ") {
                section.error = Some(error.to_string());
            } else {
                section.lines.push(line.to_string());
            }
        }
    }
    sections
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_driver_that_answers_as_another_device_is_refused() {
        let mali = Target::named("mali-g610").unwrap();
        let fallback =
            "renderer: llvmpipe (LLVM 15.0.6, 256 bits)\nversion: OpenGL ES 3.2 Mesa 25.0.7\n";
        assert_eq!(
            device_of(fallback, &mali),
            Err(CostError::Fallback {
                target: "mali-g610",
                device: "llvmpipe (LLVM 15.0.6, 256 bits)".into()
            })
        );
        let right = "renderer: Mali-G610 (Panfrost)\nversion: OpenGL ES 3.1 Mesa 25.0.7\n";
        assert_eq!(
            device_of(right, &mali).unwrap(),
            "Mali-G610 (Panfrost), OpenGL ES 3.1 Mesa 25.0.7"
        );
        let navi = Target::named("amd-navi21").unwrap();
        let lavapipe = "device: llvmpipe (LLVM 15.0.6, 256 bits)\ndriver: llvmpipe Mesa 25.0.7\n";
        assert!(device_of(lavapipe, &navi).is_err());
    }

    #[test]
    fn output_splits_into_one_section_a_shader() {
        let stdout = "device: X\nshader: 0\nexecutable: fragment\nstatistic: Instructions = 3\n\
                      representation: ACO\n  v_mov_b32 v0, 0\nend-representation\n\
                      shader: 1\nerror: vkCreateGraphicsPipelines failed (VkResult -3)\n";
        let sections = split_sections(stdout);
        assert_eq!(sections.len(), 2);
        assert_eq!(
            sections[0].lines,
            ["executable: fragment", "statistic: Instructions = 3"]
        );
        assert_eq!(
            sections[0].disassembly.as_deref(),
            Some("; ACO\n  v_mov_b32 v0, 0\n")
        );
        assert_eq!(
            sections[1].error.as_deref(),
            Some("vkCreateGraphicsPipelines failed (VkResult -3)")
        );
    }
}
