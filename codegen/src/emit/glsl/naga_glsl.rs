//! The one way WGSL is taken in here and a whole stage becomes GLSL: naga parses and
//! validates the WGSL with the capabilities generated code needs, and its GLSL writer
//! translates one entry point. The includes' emitter, the validator's portability check and
//! the renderer's on-tile backends all call it, so they translate alike; what a hand-written
//! `main` or an include declares is printed from the module instead ([`super::printer`]).

use naga::back::glsl;
use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};

/// The naga capabilities the generated WGSL needs beyond the defaults: the exact decode of
/// half-float words calls `unpack2x16float`, which naga gates behind
/// `SHADER_FLOAT16_IN_FLOAT32` (wgpu grants it on every adapter but Mesa's without
/// shader-f16).
pub const GENERATED_CODE_CAPABILITIES: Capabilities = Capabilities::SHADER_FLOAT16_IN_FLOAT32;

/// Why WGSL was refused: naga's parse error or its validation error, whole, for a caller that
/// reports them in its own form (the validator's diagnostics).
#[derive(Debug)]
pub enum WgslError {
    /// The WGSL front end's error.
    Parse(naga::front::wgsl::ParseError),
    /// The validator's error, with its spans, and the module it refused (for the names its
    /// handles stand for).
    Validate(Box<(naga::Module, naga::WithSpan<naga::valid::ValidationError>)>),
}

impl WgslError {
    /// naga's message with the source lines it points at.
    pub fn emit_to_string(&self, wgsl: &str) -> String {
        match self {
            WgslError::Parse(error) => error.emit_to_string(wgsl),
            WgslError::Validate(refused) => refused.1.emit_to_string(wgsl),
        }
    }
}

/// Parses and validates `wgsl` with every validation flag, the default capabilities and
/// `extra`: the one place WGSL is taken in.
pub fn parse_and_validate(
    wgsl: &str,
    extra: Capabilities,
) -> Result<(naga::Module, ModuleInfo), WgslError> {
    let module = naga::front::wgsl::parse_str(wgsl).map_err(WgslError::Parse)?;
    match Validator::new(ValidationFlags::all(), Capabilities::default() | extra).validate(&module)
    {
        Ok(info) => Ok((module, info)),
        Err(error) => Err(WgslError::Validate(Box::new((module, error)))),
    }
}

/// [`parse_and_validate`], the error as naga's message with the source.
pub fn validate(wgsl: &str, extra: Capabilities) -> Result<(naga::Module, ModuleInfo), String> {
    parse_and_validate(wgsl, extra).map_err(|error| error.emit_to_string(wgsl))
}

/// Options for naga's GLSL writer: `version`, clip space left as the WGSL writes it (no
/// coordinate adjustment), and every resource keeping its WGSL binding number (GLSL ES 3.10
/// and GLSL 450 declare bindings in the shader; a host binds by those numbers).
pub fn options_keeping_bindings(module: &naga::Module, version: glsl::Version) -> glsl::Options {
    let mut binding_map = glsl::BindingMap::default();
    for (_, global) in module.global_variables.iter() {
        if let Some(binding) = &global.binding {
            binding_map.insert(*binding, binding.binding as u8);
        }
    }
    glsl::Options {
        version,
        writer_flags: glsl::WriterFlags::empty(),
        binding_map,
        ..glsl::Options::default()
    }
}

/// naga's GLSL of entry point `entry` (of `stage`) of a validated module, and the reflection
/// that says which uniform samples which texture. `options` says the version, the writer's
/// flags (naga's default adjusts clip space to GL's) and the bindings.
pub fn write(
    (module, info): (&naga::Module, &ModuleInfo),
    stage: naga::ShaderStage,
    entry: &str,
    options: &glsl::Options,
) -> Result<(String, glsl::ReflectionInfo), String> {
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
        options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )
    .and_then(|mut writer| writer.write())
    .map_err(|error| format!("naga cannot translate `{entry}` to GLSL: {error}"))?;
    Ok((text, reflection))
}
