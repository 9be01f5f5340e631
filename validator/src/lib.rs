//! Validates WGSL with naga and checks that it translates to every backend a user ships to:
//! SPIR-V (Vulkan), MSL (Metal), HLSL (DirectX) and GLSL ES (OpenGL ES and WebGL2).
//!
//! The stages mirror naga's own: parse (front), validate, translate (back). Each problem is a
//! [`Problem`] that names the stage and, where the source has one, the line and column.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

pub mod cost;
pub mod diagnostic;
pub mod expression_size;
pub mod include;

use std::fmt;
use std::path::{Path, PathBuf};

use gbuffer_core::Named;
pub use gbuffer_translate::wgsl::GENERATED_CODE_CAPABILITIES;
use gbuffer_translate::{glsl_stage, wgsl};
use naga::back::{hlsl, msl, spv};
use naga::valid::{Capabilities, ModuleInfo};

use diagnostic::{Handles, Label};

/// A parsed and validated module.
pub struct Validated {
    /// The parsed module.
    pub module: naga::Module,
    /// What naga's validator learned of it (types of expressions, uses).
    pub info: ModuleInfo,
}

/// Where a problem was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Resolving `#include` lines.
    Include,
    /// Parsing the WGSL.
    Parse,
    /// naga's validation of the parsed module.
    Validate,
    /// Translating the valid module to a backend's language.
    Translate(Backend),
}

/// A target language of naga's backends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// SPIR-V, for Vulkan.
    SpirV,
    /// The Metal Shading Language.
    Msl,
    /// HLSL, for DirectX.
    Hlsl,
    /// GLSL ES 3.00 (WebGL2) for vertex and fragment entry points, 3.10 for compute ones.
    GlslEs,
}

// Every backend the validator translates to.
gbuffer_core::named!(
    /// The backend's usual name: `SPIR-V`, `MSL`, `HLSL`, `GLSL ES`.
    Backend {
        SpirV => "SPIR-V",
        Msl => "MSL",
        Hlsl => "HLSL",
        GlslEs => "GLSL ES",
    }
);

/// One problem with a shader.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    /// The stage that found it.
    pub stage: Stage,
    /// 1-based line and column in the WGSL source, where known.
    pub location: Option<(u32, u32)>,
    /// One line: what is wrong, with naga's handles named.
    pub message: String,
    /// The spans naga points at, with what it says of each (the first is the primary one).
    pub labels: Vec<Label>,
    /// What naga adds: the causes of a validation error, the hints of a parse error.
    pub notes: Vec<String>,
    /// naga's own report, as it prints it.
    pub detail: String,
}

impl fmt::Display for Problem {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let stage = match self.stage {
            Stage::Include => "include error".to_string(),
            Stage::Parse => "parse error".to_string(),
            Stage::Validate => "validation error".to_string(),
            Stage::Translate(backend) => format!("{} translation error", backend.name()),
        };
        if let Some((line, column)) = self.location {
            write!(out, "{line}:{column}: ")?;
        }
        write!(out, "{stage}: {}", self.message)?;
        for note in &self.notes {
            write!(out, ": {note}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Problem {}

/// Parses and validates WGSL, a user's shader: f16 arithmetic (`enable f16`) and the f16 pack
/// builtins are optional in WebGPU (wgpu's SHADER_F16 feature and SHADER_F16_IN_F32 downlevel
/// flag), accepted here, and named by the shaders that need them.
pub fn validate_wgsl(source: &str) -> Result<Validated, Problem> {
    validate_with(
        source,
        Capabilities::SHADER_FLOAT16 | GENERATED_CODE_CAPABILITIES,
    )
}

/// Parses and validates generated WGSL with exactly the capabilities its header names and no
/// more ([`GENERATED_CODE_CAPABILITIES`]): what a naga user needs for it.
pub fn validate_generated(source: &str) -> Result<Validated, Problem> {
    validate_with(source, GENERATED_CODE_CAPABILITIES)
}

/// Parses and validates WGSL with the default capabilities and `extra`.
fn validate_with(source: &str, extra: Capabilities) -> Result<Validated, Problem> {
    // Before naga, whose recursion a huge statement would overflow.
    expression_size::check(source)?;
    match wgsl::parse_and_validate(source, extra) {
        Ok((module, info)) => Ok(Validated { module, info }),
        Err(wgsl::WgslError::Parse(error)) => Err(parse_problem(&error, source)),
        Err(wgsl::WgslError::Validate(refused)) => {
            let (module, error) = *refused;
            Err(validation_problem(&module, &error, source))
        }
    }
}

/// naga's parse error as a [`Problem`] at its line and column.
fn parse_problem(error: &naga::front::wgsl::ParseError, source: &str) -> Problem {
    Problem {
        stage: Stage::Parse,
        location: error
            .location(source)
            .map(|at| (at.line_number, at.line_position)),
        message: error.message().to_string(),
        labels: error
            .labels()
            .filter_map(|(span, text)| {
                Some(Label {
                    span: span.to_range()?,
                    text: text.to_string(),
                })
            })
            .collect(),
        notes: error.notes().map(str::to_string).collect(),
        detail: error.emit_to_string(source),
    }
}

/// naga's validation error as a [`Problem`] at its innermost label, the handles it names
/// described by what they stand for in `module`.
fn validation_problem(
    module: &naga::Module,
    error: &naga::WithSpan<naga::valid::ValidationError>,
    source: &str,
) -> Problem {
    let handles = Handles {
        module,
        source,
        function: diagnostic::function_of(module, error.as_inner()),
    };
    let mut notes = Vec::new();
    let mut cause = std::error::Error::source(error.as_inner());
    while let Some(inner) = cause {
        notes.push(handles.describe(&inner.to_string()));
        cause = inner.source();
    }
    let labels: Vec<Label> = error
        .spans()
        .filter_map(|(span, text)| {
            Some(Label {
                span: span.to_range()?,
                text: handles.describe(text),
            })
        })
        .collect();
    let innermost =
        innermost_label(&labels).map(|index| line_and_column(source, labels[index].span.start));
    Problem {
        stage: Stage::Validate,
        location: innermost.or_else(|| {
            error
                .location(source)
                .map(|at| (at.line_number, at.line_position))
        }),
        message: handles.describe(&error.as_inner().to_string()),
        labels,
        notes,
        detail: error.emit_to_string(source),
    }
}

/// Writes a validated module in `backend`'s language and returns the text (for SPIR-V, a line
/// with the binary's word count). GLSL needs an entry point: each one is written in turn and
/// the outputs concatenated; a module without entry points has no GLSL.
pub fn write_backend(validated: &Validated, backend: Backend) -> Result<String, Problem> {
    let problem = |message: String| Problem {
        stage: Stage::Translate(backend),
        location: None,
        message,
        labels: Vec::new(),
        notes: Vec::new(),
        detail: String::new(),
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
                // WebGL 2's GLSL ES 3.00, but for compute, which arrived in 3.10 (GLES 3.1).
                let dialect = if entry_point.stage == naga::ShaderStage::Compute {
                    glsl_stage::Dialect::Gles
                } else {
                    glsl_stage::Dialect::WebGl
                };
                let (text, _) = glsl_stage::write(
                    (module, info),
                    entry_point.stage,
                    &entry_point.name,
                    dialect,
                )
                .map_err(problem)?;
                all.push_str(&text);
            }
            Ok(all)
        }
    }
}

/// The 1-based line and column (in bytes, as naga counts them) of byte `offset` of `source`.
fn line_and_column(source: &str, offset: usize) -> (u32, u32) {
    let before = &source[..offset.min(source.len())];
    let line = before.matches('\n').count() + 1;
    let column = offset - before.rfind('\n').map_or(0, |newline| newline + 1) + 1;
    (line as u32, column as u32)
}

/// The index of the label with the narrowest span (the last of equals): naga labels a problem
/// from the outside in, a function before the expression in it.
fn innermost_label(labels: &[Label]) -> Option<usize> {
    labels
        .iter()
        .enumerate()
        .min_by_key(|(index, label)| (label.span.len(), std::cmp::Reverse(*index)))
        .map(|(index, _)| index)
}

/// A problem in a shader file, placed in the file (or module) it comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileProblem {
    /// The file, `<gbuffer/NAME>` or `<generated from PATH>`.
    pub origin: String,
    /// 1-based line and column in the origin, where known.
    pub location: Option<(usize, usize)>,
    /// The stage that found it.
    pub stage: Stage,
    /// What is wrong, with naga's handles named.
    pub message: String,
    /// naga's labelled spans, each placed in its own file.
    pub labels: Vec<PlacedLabel>,
    /// naga's notes: the causes of the error, the hints of a parse error.
    pub notes: Vec<String>,
}

/// A labelled span, placed in the file it comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PlacedLabel {
    /// The file (or library module) the span is in.
    pub origin: String,
    /// 1-based line and column of the span's start.
    pub line: usize,
    /// 1-based column of the span's start, in characters.
    pub column: usize,
    /// Its length on that line, in characters (at least 1).
    pub length: usize,
    /// The line's text.
    pub source_line: String,
    /// What naga says of the span.
    pub text: String,
}

impl fmt::Display for FileProblem {
    /// `file:line:col: error: message`, then each label under its source line (with its own
    /// `--> file:line:col` when it is in another file) and the notes.
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let stage = match self.stage {
            Stage::Translate(backend) => format!(" ({} translation)", backend.name()),
            _ => String::new(),
        };
        match self.location {
            Some((line, column)) => write!(
                out,
                "{}:{line}:{column}: error{stage}: {}",
                self.origin, self.message
            )?,
            None => write!(out, "{}: error{stage}: {}", self.origin, self.message)?,
        }
        let gutter = self
            .labels
            .iter()
            .map(|label| label.line.to_string().len())
            .max()
            .unwrap_or(1);
        for label in &self.labels {
            if label.origin != self.origin {
                write!(
                    out,
                    "\n{:gutter$}--> {}:{}:{}",
                    "", label.origin, label.line, label.column
                )?;
            }
            let caret = " ".repeat(label.column.saturating_sub(1));
            let underline = "^".repeat(label.length.max(1));
            write!(
                out,
                "\n{:gutter$} |\n{:>gutter$} | {}\n{:gutter$} | {caret}{underline} {}",
                "", label.line, label.source_line, "", label.text
            )?;
        }
        for note in &self.notes {
            write!(out, "\n{:gutter$} = note: {note}", "")?;
        }
        Ok(())
    }
}

/// The stack of the thread that parses, validates and translates a shader: naga walks an
/// expression tree recursively, and a chain of [`expression_size::MAX_OPERATORS`] operators
/// is that deep.
const CHECK_STACK_BYTES: usize = 256 << 20;

/// Checks a WGSL file: resolves its includes (confined to its folder, the current folder and
/// `include_dirs`), validates it with naga, and (with `portability`) translates it to every
/// backend. Returns every problem found; empty when the file is valid.
pub fn check_file(path: &Path, portability: bool, include_dirs: &[PathBuf]) -> Vec<FileProblem> {
    let resolved = match include::resolve_file(path, include_dirs) {
        Ok(resolved) => resolved,
        Err(problem) => return vec![*problem],
    };
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name("gbuffer-validate".into())
            .stack_size(CHECK_STACK_BYTES)
            .spawn_scoped(scope, || check_resolved(path, &resolved, portability))
            .map(|thread| {
                thread
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
            })
            .unwrap_or_else(|error| {
                vec![FileProblem {
                    origin: path.display().to_string(),
                    location: None,
                    stage: Stage::Parse,
                    message: format!("cannot start the checking thread: {error}"),
                    labels: Vec::new(),
                    notes: Vec::new(),
                }]
            })
    })
}

/// [`check_file`]'s checks of a resolved file.
fn check_resolved(
    path: &Path,
    resolved: &include::Resolved,
    portability: bool,
) -> Vec<FileProblem> {
    // Places a problem of the combined source in the file it came from.
    let place = |problem: Problem| {
        let labels: Vec<PlacedLabel> = problem
            .labels
            .iter()
            .filter_map(|label| place_label(resolved, label))
            .collect();
        // The problem sits at the most specific place naga gives: its innermost label (the
        // expression rather than the function around it); the others stay as context.
        let innermost = innermost_label(&problem.labels)
            .and_then(|index| place_label(resolved, &problem.labels[index]));
        let (origin, location) = match innermost.as_ref().or(labels.first()) {
            Some(label) => (label.origin.clone(), Some((label.line, label.column))),
            None => {
                let combined = problem
                    .location
                    .map(|(line, column)| (line as usize, column as usize));
                let origin = combined.and_then(|(line, _)| resolved.origin_of(line));
                (
                    origin.map_or_else(
                        || path.display().to_string(),
                        |(origin, _)| origin.to_string(),
                    ),
                    origin
                        .zip(combined)
                        .map(|((_, line), (_, column))| (line, column)),
                )
            }
        };
        FileProblem {
            origin,
            location,
            stage: problem.stage,
            message: problem.message,
            labels,
            notes: problem.notes,
        }
    };
    let validated = match validate_wgsl(&resolved.source) {
        Ok(validated) => validated,
        Err(problem) => return vec![place(problem)],
    };
    if !portability {
        return Vec::new();
    }
    Backend::ALL
        .iter()
        .copied()
        .filter_map(|backend| write_backend(&validated, backend).err())
        .map(place)
        .collect()
}

/// A label of the combined source, placed in its file: line, column and length there.
fn place_label(resolved: &include::Resolved, label: &Label) -> Option<PlacedLabel> {
    let source = &resolved.source;
    let before = source.get(..label.span.start)?;
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |at| at + 1);
    let source_line = source[line_start..].lines().next().unwrap_or("");
    let column = before[line_start..].chars().count() + 1;
    let on_line = source
        .get(label.span.clone())?
        .lines()
        .next()
        .unwrap_or("")
        .chars()
        .count();
    let (origin, origin_line) = resolved.origin_of(line)?;
    Some(PlacedLabel {
        origin: origin.to_string(),
        line: origin_line,
        column,
        length: on_line,
        source_line: source_line.to_string(),
        text: label.text.clone(),
    })
}

/// Validates `source` and translates it to every backend; the first problem, if any.
pub fn validate_everywhere(source: &str) -> Result<Validated, Problem> {
    let validated = validate_wgsl(source)?;
    for &backend in Backend::ALL {
        write_backend(&validated, backend)?;
    }
    Ok(validated)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Parse errors come with their position, validation errors from the validator.
    #[test]
    fn reports_parse_and_validation_errors() {
        let problem = |source: &str| validate_wgsl(source).err().unwrap();
        let parse = problem("fn f() -> u32 {\n    return 1.5 +;\n}\n");
        assert_eq!(parse.stage, Stage::Parse);
        assert_eq!(parse.location.map(|(line, _)| line), Some(2));
        let validation = problem("fn f() -> u32 {\n    if true { return 1u; }\n}\n");
        assert_eq!(validation.stage, Stage::Validate);
    }

    #[test]
    fn translates_a_fragment_shader_everywhere() {
        let source = "@fragment fn main() -> @location(0) vec4<u32> { return vec4<u32>(1u); }";
        let validated = validate_everywhere(source).unwrap();
        assert!(write_backend(&validated, Backend::GlslEs)
            .unwrap()
            .contains("#version 300 es"));
    }
}
