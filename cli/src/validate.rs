//! `gbuffer validate`: validates WGSL files, with their includes resolved, through naga, and checks
//! that each translates to SPIR-V, MSL, HLSL and GLSL ES.

use std::path::PathBuf;
use std::process::ExitCode;

use gbuffer_core::Named;
use gbuffer_validator::{check_file, FileProblem, Stage};

use crate::json::Json;
use crate::output;

/// Validates WGSL shaders with naga and checks that they translate to SPIR-V, MSL, HLSL and
/// GLSL ES. Lines `#include <gbuffer/MODULE>` pull in a module of the shading library with
/// its dependencies; `#include "layout.toml"` the generated WGSL of a layout file;
/// `#include "other.wgsl"` another shader. Paths are relative to the including file and must
/// stay inside the include roots: the folder of the shader named here, the current folder and
/// each `--include-dir`.
///
/// Problems print as `file:line:col: error: message` with the source line and a caret.
///
/// Exit status: 0 when every shader is valid, 1 when any is invalid or unreadable, 2 on a
/// usage error (bad arguments).
#[derive(clap::Args, Debug)]
pub struct Arguments {
    /// WGSL files to check.
    #[arg(required = true, value_name = "SHADER.wgsl")]
    files: Vec<PathBuf>,
    /// Print the results as JSON on standard output.
    #[arg(long)]
    json: bool,
    /// Only validate; skip the translation to every backend.
    #[arg(long)]
    no_portability: bool,
    /// A folder included files may also come from (repeatable), beside the shader's own.
    #[arg(long, short = 'I', value_name = "DIR")]
    include_dir: Vec<PathBuf>,
}

fn stage_name(stage: Stage) -> String {
    match stage {
        Stage::Include => "include".into(),
        Stage::Parse => "parse".into(),
        Stage::Validate => "validate".into(),
        Stage::Translate(backend) => format!("translate {}", backend.name()),
    }
}

fn problem_json(problem: &FileProblem) -> Json {
    let labels = problem.labels.iter().map(|label| {
        Json::Object(vec![
            ("origin", Json::string(&label.origin)),
            ("line", Json::unsigned(Some(label.line))),
            ("column", Json::unsigned(Some(label.column))),
            ("length", Json::unsigned(Some(label.length))),
            ("text", Json::string(&label.text)),
        ])
    });
    Json::Object(vec![
        ("origin", Json::string(&problem.origin)),
        (
            "line",
            Json::unsigned(problem.location.map(|(line, _)| line)),
        ),
        (
            "column",
            Json::unsigned(problem.location.map(|(_, column)| column)),
        ),
        ("stage", Json::string(stage_name(problem.stage))),
        ("message", Json::string(&problem.message)),
        ("labels", Json::Array(labels.collect())),
        (
            "notes",
            Json::Array(problem.notes.iter().map(Json::string).collect()),
        ),
    ])
}

pub fn run(arguments: Arguments) -> ExitCode {
    let mut any_invalid = false;
    let mut results = Vec::new();
    let mut valid_lines = String::new();
    for file in &arguments.files {
        let problems = check_file(file, !arguments.no_portability, &arguments.include_dir);
        any_invalid |= !problems.is_empty();
        if arguments.json {
            results.push(Json::Object(vec![
                ("file", Json::string(file.display().to_string())),
                ("valid", Json::Bool(problems.is_empty())),
                (
                    "problems",
                    Json::Array(problems.iter().map(problem_json).collect()),
                ),
            ]));
        } else if problems.is_empty() {
            valid_lines.push_str(&format!("{}: valid\n", file.display()));
        } else {
            for problem in &problems {
                say!("{problem}\n");
            }
        }
    }
    let text = if arguments.json {
        let json = Json::Object(vec![("files", Json::Array(results))]);
        format!("{}\n", json.pretty())
    } else {
        valid_lines
    };
    if output::print(&text).is_err() || any_invalid {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
