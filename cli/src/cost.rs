//! `gbuffer cost`: what a shader costs on real GPU compilers (Mali, Adreno, AMD, NVIDIA), run
//! through Mesa's drm-shim with no GPU present.

use std::path::PathBuf;
use std::process::ExitCode;

use gbuffer_cost::{measure, Api, Measurement, Shader, Stage, Target, DEFAULT_TARGETS, TARGETS};
use gbuffer_validator::include::resolve_file;

/// Compiles a shader with the compilers of the GPUs users ship on and prints what each
/// reports: instructions, estimated cycles (Mali, split by unit; ACO's latency and inverse
/// throughput), registers, occupancy and spills.
///
/// A `.wgsl` file is translated by naga as a backend would see it: to GLSL ES 3.10 for GL
/// targets, to SPIR-V for Vulkan ones (`#include`s resolved as `gbuffer validate` does). Any
/// other file is GLSL ES (with its `#version` line) and is costed on GL targets only. A fragment
/// shader is linked with a vertex shader that writes its inputs, each from a vertex attribute
/// of its own (on Vulkan, from a buffer): for WGSL built from naga's IR; for GLSL ES from its
/// `in` declarations, read one a line (a declaration split over lines, or two on one line,
/// is not seen: write one a line, or give WGSL).
///
/// The compilers are Mesa's (panfrost, freedreno, turnip, RADV/ACO, nouveau), run through
/// Mesa's drm-shim, the arm64 ones under qemu-user: `scripts/cost-setup.sh` installs them (the
/// folder is $GBUFFER_COST_ROOT, default /opt/gbuffer-cost). A driver that falls back to
/// software is refused.
///
/// Exit status: 0 when every target reported, 1 when a shader or a target failed (a missing
/// setup, a fallback, a shader that does not compile: one line each on standard error), 2 on a
/// usage error.
#[derive(clap::Args, Debug)]
pub struct Arguments {
    /// The shader: WGSL (`.wgsl`) or GLSL ES (any other name).
    #[arg(value_name = "SHADER")]
    file: PathBuf,
    /// The WGSL entry point (default: the module's only fragment or compute entry point).
    #[arg(long, value_name = "NAME")]
    entry: Option<String>,
    /// The GLSL ES shader's stage (default: compute for `.comp`, fragment otherwise).
    #[arg(long, value_parser = ["fragment", "compute"])]
    stage: Option<String>,
    /// A target, repeatable (default: mali-g52, mali-g610, adreno-630, adreno-740, their
    /// Vulkan forms, amd-navi21 and nvidia-tu102; GL ones only for GLSL ES). Every target:
    /// mali-g52, mali-g57, mali-g610, adreno-630, adreno-660, adreno-740, adreno-750,
    /// adreno-630-vulkan, adreno-740-vulkan, amd-navi21, amd-navi31, nvidia-tu102.
    #[arg(long = "target", value_name = "TARGET")]
    targets: Vec<String>,
    /// Vulkan colour attachment formats by location (r32ui, rgba8, rgb10a2, rgba16f, ...)
    /// where the default (32-bit integers, rgba16f floats) is not what the renderer binds.
    #[arg(long = "color", value_name = "FORMAT")]
    colors: Vec<String>,
    /// Print every value each compiler reported, by its own name, after the table.
    #[arg(long)]
    all: bool,
    /// Print each compiler's listing of the shader after the table (in JSON, a field).
    #[arg(long)]
    disassembly: bool,
    /// Print the results as JSON on standard output.
    #[arg(long)]
    json: bool,
}

pub fn run(arguments: Arguments) -> ExitCode {
    let shader = match shader(&arguments) {
        Ok(shader) => shader,
        Err(message) => {
            say!("gbuffer cost: {message}");
            return ExitCode::from(1);
        }
    };
    let is_wgsl = arguments
        .file
        .extension()
        .is_some_and(|extension| extension == "wgsl");
    let names: Vec<&str> = if arguments.targets.is_empty() {
        DEFAULT_TARGETS.to_vec()
    } else {
        arguments.targets.iter().map(String::as_str).collect()
    };
    let mut targets = Vec::new();
    for name in names {
        match Target::named(name) {
            Ok(target) if is_wgsl || target.api == Api::Gles => targets.push(target),
            Ok(target) if !arguments.targets.is_empty() => {
                say!(
                    "gbuffer cost: {}: GLSL ES is costed on GL targets only; give WGSL for Vulkan",
                    target.name
                );
                return ExitCode::from(2);
            }
            Ok(_) => {}
            Err(message) => {
                say!("gbuffer cost: {message}");
                return ExitCode::from(2);
            }
        }
    }

    let mut measurements = Vec::new();
    let mut failed = false;
    for target in &targets {
        match measure(std::slice::from_ref(&shader), target, arguments.disassembly) {
            Ok(results) => {
                for result in results {
                    match result {
                        Ok(measurement) => measurements.push(measurement),
                        Err(message) => {
                            say!("gbuffer cost: {}: {message}", target.name);
                            failed = true;
                        }
                    }
                }
            }
            Err(error) => {
                say!("gbuffer cost: {error}");
                failed = true;
            }
        }
    }
    let output = if arguments.json {
        json(&arguments, &measurements)
    } else {
        table(&measurements, arguments.all, arguments.disassembly)
    };
    if crate::output::print(&output).is_err() {
        return ExitCode::from(1);
    }
    ExitCode::from(u8::from(failed))
}

fn shader(arguments: &Arguments) -> Result<Shader, String> {
    let file = &arguments.file;
    let is_wgsl = file
        .extension()
        .is_some_and(|extension| extension == "wgsl");
    if is_wgsl {
        let resolved = resolve_file(file, &[]).map_err(|problem| problem.to_string())?;
        gbuffer_validator::expression_size::check(&resolved.source).map_err(|problem| {
            let (line, column) = problem.location.unwrap_or((1, 1));
            format!("{}:{line}:{column}: {}", file.display(), problem.message)
        })?;
        let shader = match &arguments.entry {
            Some(entry) => Shader::wgsl(&resolved.source, entry),
            None => Shader::wgsl_only_entry_point(&resolved.source),
        };
        return shader.map_err(|message| format!("{}: {message}", file.display()));
    }
    let text = gbuffer_files::input::read_input(file)
        .map_err(|error| format!("{}: cannot read: {error}", file.display()))?;
    let stage = match arguments.stage.as_deref() {
        Some("compute") => Stage::Compute,
        Some(_) => Stage::Fragment,
        None if file
            .extension()
            .is_some_and(|extension| extension == "comp") =>
        {
            Stage::Compute
        }
        None => Stage::Fragment,
    };
    Ok(Shader::glsl(stage, &text))
}

fn optional(value: Option<u64>) -> String {
    value.map_or_else(|| "-".to_string(), |value| value.to_string())
}

fn table(measurements: &[Measurement], all: bool, disassembly: bool) -> String {
    let mut rows = vec![[
        "target".to_string(),
        "instructions".to_string(),
        "cycles".to_string(),
        "registers".to_string(),
        "occupancy".to_string(),
        "spills".to_string(),
    ]];
    for measurement in measurements {
        let statistics = &measurement.statistics;
        let cycles = match (
            &statistics.cycles,
            statistics.latency_cycles,
            statistics.inverse_throughput_cycles,
        ) {
            (Some(cycles), _, _) => {
                let parts: Vec<String> = cycles
                    .parts
                    .iter()
                    .filter(|part| part.value != 0.0)
                    .map(|part| format!("{} {}", part.name, part.value))
                    .collect();
                format!("{} ({})", cycles.total, parts.join(", "))
            }
            (None, Some(latency), Some(throughput)) => {
                format!("latency {latency}, inverse throughput {throughput}")
            }
            _ => "-".to_string(),
        };
        rows.push([
            measurement.target.to_string(),
            statistics.instructions.to_string(),
            cycles,
            optional(statistics.registers),
            optional(statistics.occupancy),
            optional(statistics.spills),
        ]);
    }
    let widths: Vec<usize> = (0..6)
        .map(|column| rows.iter().map(|row| row[column].len()).max().unwrap_or(0))
        .collect();
    let mut text = String::new();
    for row in &rows {
        let cells: Vec<String> = row
            .iter()
            .zip(&widths)
            .map(|(cell, width)| format!("{cell:<width$}"))
            .collect();
        text.push_str(cells.join("  ").trim_end());
        text.push('\n');
    }
    text.push_str("\ncompilers:\n");
    for measurement in measurements {
        text.push_str(&format!(
            "  {}: {}\n",
            measurement.target, measurement.device
        ));
    }
    if all {
        for measurement in measurements {
            text.push_str(&format!("\n{} reported:\n", measurement.target));
            for statistic in &measurement.statistics.raw {
                text.push_str(&format!("  {} = {}\n", statistic.name, statistic.value));
            }
        }
    }
    if disassembly {
        for measurement in measurements {
            if let Some(listing) = &measurement.disassembly {
                text.push_str(&format!("\n{}:\n{listing}\n", measurement.target));
            }
        }
    }
    text
}

fn json(arguments: &Arguments, measurements: &[Measurement]) -> String {
    let value = serde_json::json!({
        "shader": arguments.file.display().to_string(),
        "targets": TARGETS.iter().filter(|target| measurements.iter().any(|m| m.target == target.name)).collect::<Vec<_>>(),
        "measurements": measurements,
    });
    let mut text = serde_json::to_string_pretty(&value).expect("the results are JSON");
    text.push('\n');
    text
}
