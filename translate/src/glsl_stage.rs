//! A whole stage of a validated module as GLSL, by naga's GLSL writer: the validator's
//! portability check, the renderer's vertex and two-pass stages and the cost model's GLSL ES
//! all write stages here, with the same options, so they translate alike. What a hand-written
//! `main` or an include declares is printed from the module instead ([`crate::printer`]).

use naga::back::glsl;
use naga::valid::ModuleInfo;

/// Which GLSL a stage is written in: the three the project's shaders target.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    /// GLSL ES 3.10: GLES 3.1 and 3.2 (panfrost, whose compiler the cost model runs, offers
    /// 3.10 at most; the shaders need nothing of 3.20).
    Gles,
    /// GLSL 450 for Vulkan (compiled to SPIR-V by glslang).
    Vulkan,
    /// GLSL ES 3.00, WebGL 2's: no binding qualifiers (a host sets each sampler uniform's
    /// texture unit by name) and no locations on varyings.
    WebGl,
}

impl Dialect {
    /// naga's name of the version.
    pub fn version(self) -> glsl::Version {
        match self {
            Dialect::Gles => glsl::Version::new_gles(310),
            Dialect::Vulkan => glsl::Version::Desktop(450),
            Dialect::WebGl => glsl::Version::new_gles(300),
        }
    }

    /// The `#version` line a shader of the dialect starts with.
    pub fn version_line(self) -> &'static str {
        match self {
            Dialect::Gles => "#version 310 es",
            Dialect::Vulkan => "#version 450",
            Dialect::WebGl => "#version 300 es",
        }
    }

    /// The declaration that runs a fragment shader's depth test before the shader, where the
    /// dialect has it (GLSL ES 3.10 and GLSL 450; GLSL ES 3.00 does not), else nothing.
    pub fn early_fragment_tests(self) -> &'static str {
        match self {
            Dialect::Gles | Dialect::Vulkan => "layout(early_fragment_tests) in;\n",
            Dialect::WebGl => "",
        }
    }
}

/// Options for naga's GLSL writer: the dialect's version, clip space left as the WGSL writes it
/// (no coordinate adjustment), and every resource keeping its WGSL binding number (GLSL ES 3.10
/// and GLSL 450 declare bindings in the shader; a host binds by those numbers; GLSL ES 3.00
/// has no binding qualifiers, and naga writes none there).
fn options(module: &naga::Module, dialect: Dialect) -> glsl::Options {
    let mut binding_map = glsl::BindingMap::default();
    for (_, global) in module.global_variables.iter() {
        if let Some(binding) = &global.binding {
            binding_map.insert(*binding, binding.binding as u8);
        }
    }
    glsl::Options {
        version: dialect.version(),
        writer_flags: glsl::WriterFlags::empty(),
        binding_map,
        ..glsl::Options::default()
    }
}

/// naga's GLSL of entry point `entry` (of `stage`) of a validated module in `dialect` (clip
/// space as the WGSL writes it, bindings kept), and the reflection that says which uniform
/// samples which texture.
pub fn write(
    (module, info): (&naga::Module, &ModuleInfo),
    stage: naga::ShaderStage,
    entry: &str,
    dialect: Dialect,
) -> Result<(String, glsl::ReflectionInfo), String> {
    let options = options(module, dialect);
    let pipeline = glsl::PipelineOptions {
        shader_stage: stage,
        entry_point: entry.to_string(),
        multiview: None,
    };
    let mut text = String::new();
    let reflection = glsl::Writer::new(
        &mut text,
        module,
        info,
        &options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )
    .and_then(|mut writer| writer.write())
    .map_err(|error| format!("naga cannot translate `{entry}` to GLSL: {error}"))?;
    Ok((text, reflection))
}
