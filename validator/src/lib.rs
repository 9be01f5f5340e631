//! Validates WGSL with naga and checks that it translates to every backend a user ships to:
//! SPIR-V (Vulkan), MSL (Metal), HLSL (DirectX) and GLSL ES (OpenGL ES and WebGL2).
//!
//! The stages mirror naga's own: parse (front), validate, translate (back). Each problem is a
//! [`Problem`] that names the stage and, where the source has one, the line and column.

use std::fmt;

use naga::back::{glsl, hlsl, msl, spv};
use naga::valid::{Capabilities, ModuleInfo, ValidationFlags, Validator};

/// A parsed and validated module.
pub struct Validated {
    pub module: naga::Module,
    pub info: ModuleInfo,
}

/// Where a problem was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    Parse,
    Validate,
    Translate(Backend),
}

/// A target language of naga's backends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    SpirV,
    Msl,
    Hlsl,
    /// GLSL ES 3.00 (WebGL2) for vertex and fragment entry points, 3.10 for compute ones.
    GlslEs,
}

impl Backend {
    pub const ALL: [Backend; 4] = [Backend::SpirV, Backend::Msl, Backend::Hlsl, Backend::GlslEs];

    pub fn name(self) -> &'static str {
        match self {
            Backend::SpirV => "SPIR-V",
            Backend::Msl => "MSL",
            Backend::Hlsl => "HLSL",
            Backend::GlslEs => "GLSL ES",
        }
    }
}

/// One problem with a shader.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    pub stage: Stage,
    /// 1-based line and column in the WGSL source, where known.
    pub location: Option<(u32, u32)>,
    /// naga's message; for parse and validation errors, its full report with the source line.
    pub message: String,
}

impl fmt::Display for Problem {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let stage = match self.stage {
            Stage::Parse => "parse error".to_string(),
            Stage::Validate => "validation error".to_string(),
            Stage::Translate(backend) => format!("{} translation error", backend.name()),
        };
        match self.location {
            Some((line, column)) => write!(out, "{line}:{column}: {stage}: {}", self.message),
            None => write!(out, "{stage}: {}", self.message),
        }
    }
}

impl std::error::Error for Problem {}

/// Parses and validates WGSL.
pub fn validate_wgsl(source: &str) -> Result<Validated, Problem> {
    let module = naga::front::wgsl::parse_str(source).map_err(|error| Problem {
        stage: Stage::Parse,
        location: error
            .location(source)
            .map(|at| (at.line_number, at.line_position)),
        message: error.emit_to_string(source),
    })?;
    let info = Validator::new(ValidationFlags::all(), Capabilities::default())
        .validate(&module)
        .map_err(|error| Problem {
            stage: Stage::Validate,
            location: error
                .location(source)
                .map(|at| (at.line_number, at.line_position)),
            message: error.emit_to_string(source),
        })?;
    Ok(Validated { module, info })
}

/// Translates a validated module to `backend` and returns the text (for SPIR-V, a line with
/// the binary's word count). GLSL needs an entry point: each one is translated in turn and
/// the outputs concatenated; a module without entry points has no GLSL.
pub fn translate(validated: &Validated, backend: Backend) -> Result<String, Problem> {
    let problem = |message: String| Problem {
        stage: Stage::Translate(backend),
        location: None,
        message,
    };
    let Validated { module, info } = validated;
    match backend {
        Backend::SpirV => {
            let words = spv::write_vec(module, info, &spv::Options::default(), None)
                .map_err(|error| problem(error.to_string()))?;
            Ok(format!("{} SPIR-V words", words.len()))
        }
        Backend::Msl => {
            let pipeline = msl::PipelineOptions::default();
            let (text, _) = msl::write_string(module, info, &msl::Options::default(), &pipeline)
                .map_err(|error| problem(error.to_string()))?;
            Ok(text)
        }
        Backend::Hlsl => {
            let mut text = String::new();
            let options = hlsl::Options::default();
            let pipeline = hlsl::PipelineOptions::default();
            hlsl::Writer::new(&mut text, &options, &pipeline)
                .write(module, info, None)
                .map_err(|error| problem(error.to_string()))?;
            Ok(text)
        }
        Backend::GlslEs => {
            let mut all = String::new();
            for entry_point in &module.entry_points {
                let version = if entry_point.stage == naga::ShaderStage::Compute {
                    310
                } else {
                    300
                };
                let options = glsl::Options {
                    version: glsl::Version::new_gles(version),
                    ..glsl::Options::default()
                };
                let pipeline = glsl::PipelineOptions {
                    shader_stage: entry_point.stage,
                    entry_point: entry_point.name.clone(),
                    multiview: None,
                };
                let mut text = String::new();
                glsl::Writer::new(
                    &mut text,
                    module,
                    info,
                    &options,
                    &pipeline,
                    naga::proc::BoundsCheckPolicies::default(),
                )
                .and_then(|mut writer| writer.write())
                .map_err(|error| problem(format!("entry point `{}`: {error}", entry_point.name)))?;
                all.push_str(&text);
            }
            Ok(all)
        }
    }
}

/// Validates `source` and translates it to every backend; the first problem, if any.
pub fn validate_everywhere(source: &str) -> Result<Validated, Problem> {
    let validated = validate_wgsl(source)?;
    for backend in Backend::ALL {
        translate(&validated, backend)?;
    }
    Ok(validated)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reports_parse_errors_with_their_position() {
        let problem = validate_wgsl("fn f() -> u32 {\n    return 1.5 +;\n}\n")
            .err()
            .unwrap();
        assert_eq!(problem.stage, Stage::Parse);
        assert_eq!(problem.location.map(|(line, _)| line), Some(2));
    }

    #[test]
    fn reports_validation_errors() {
        let problem = validate_wgsl("fn f() -> u32 {\n    if true { return 1u; }\n}\n")
            .err()
            .unwrap();
        assert_eq!(problem.stage, Stage::Validate);
    }

    #[test]
    fn translates_a_fragment_shader_everywhere() {
        let source = "@fragment fn main() -> @location(0) vec4<u32> { return vec4<u32>(1u); }";
        let validated = validate_everywhere(source).unwrap();
        assert!(translate(&validated, Backend::GlslEs)
            .unwrap()
            .contains("#version 300 es"));
    }
}
