//! WGSL in: the one place it is taken in, by every package (the codegen's compile step, the
//! validator, the renderer, the cost model). naga parses it and validates it with every flag
//! and the capabilities a caller asks for; generated code needs
//! [`GENERATED_CODE_CAPABILITIES`]. A whole stage of the module then becomes GLSL through
//! [`crate::glsl_stage`], and declarations through [`crate::printer`].

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
