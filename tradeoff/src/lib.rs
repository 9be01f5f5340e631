//! The speed/accuracy trade of every approximation and encoding, side by side.
//!
//! Run with `cargo run --release -p gbuffer-cli --features report -- report`. Prints a table and writes
//! `target/tradeoff/report.md`, `report.json` and PNG plots (or into `--out DIR`). Each row's error is measured
//! against the f64 references over the stated domain; its cost is counted in naga IR
//! expressions and SPIR-V instructions; its time is measured on the adapter at hand, in a
//! compute dispatch and in a fullscreen draw's fragment shader (a dependent chain of
//! evaluations grown until a run lasts 10 ms, median of 7 runs, less the harness's own time,
//! an upper bound `<X` where that does not stand clear of the runs' spread, and nowhere printed when the
//! times contradict the order the instruction counts predict) and for its f32 mirror on the
//! CPU. The packing conversions get their own table: per format, exact and
//! fast, their instructions, branches, error in codes and time per million texels.

pub mod compilers;
pub mod frame_shaders;
pub mod frames;
pub mod furnace;
pub mod packing;
pub mod packing_cost;
mod plot;
mod rows;
mod stdout;
mod timing;

use std::fmt::Write as _;
use std::path::Path;

use gbuffer::shading::env_brdf_lut::EnvBrdfLut;
use gbuffer_gpu::adapter::{Gpu, Request};
use plot::Plot;
use rows::Row;
use stdout::report_line;

/// Each seed layout's largest error over the study's surfaces, in 8-bit sRGB steps (its "whole
/// layout" row), by the row's name (`Listing 2.2 (MobileMetallic)`): what the study predicts a
/// layout costs the picture.
pub fn layout_errors() -> Vec<(String, f64)> {
    rows::layout_rows()
        .into_iter()
        .map(|row| (row.name, row.errors.max))
        .collect()
}

/// A row's measurements besides its error.
struct Measured {
    naga_expressions: usize,
    spirv_instructions: usize,
    /// The adapter's times in both stages, less the harness's.
    gpu: timing::StageTimes,
    cpu_ns_per_eval: f64,
    /// Per [`ROW_TARGETS`] column, what the row adds to the fragment harness: Mali's cycles,
    /// the others' instructions (`None` where it failed or the compilers are not set up).
    compilers: Vec<Option<f64>>,
}

/// The GPU compilers the rows are costed on.
const ROW_TARGETS: [&str; 3] = ["mali-g610", "adreno-740", "amd-navi21"];

/// Each row's fragment harness (one evaluation, after the baseline's) on [`ROW_TARGETS`].
fn compile_rows(rows: &[Row]) -> compilers::Compiled {
    let shaders: Vec<Result<gbuffer_cost::Shader, String>> = std::iter::once(timing::BASELINE_ROW)
        .chain(rows.iter().map(|row| row.wgsl.as_str()))
        .map(|wgsl| gbuffer_cost::Shader::wgsl(&timing::fragment_harness(wgsl), "bench_fragment"))
        .collect();
    compilers::compile(&shaders, &ROW_TARGETS, compilers::MaliCycles::Total)
}

/// The SPIR-V of a row's timing harness, without the library functions the row does not
/// reach (naga writes every function of a module), and its naga module.
fn compile(row_wgsl: &str) -> Result<(naga::Module, Vec<u32>), String> {
    gbuffer_validator::cost::compile_compacted(&timing::harness(row_wgsl))
}

/// Measures every row on the adapter at hand, prints the table and writes `report.md`,
/// `report.json` and the PNG plots into `folder` (created if missing). The error says what was
/// missing (an adapter) or names the file that could not be written.
pub fn run(folder: &Path) -> Result<(), String> {
    std::fs::create_dir_all(folder)
        .map_err(|error| format!("cannot create {}: {error}", folder.display()))?;
    let gpu = Gpu::open(&Request {
        label: "trade-off study",
        limits: None,
        features: wgpu::Features::TIMESTAMP_QUERY,
        backends: None,
    })?;
    let adapter = gpu.describe();
    eprintln!("timing on {adapter}");
    eprintln!("measuring errors against the f64 references...");
    let rows = rows::rows();

    let (_, baseline_spirv) = compile(timing::BASELINE_ROW).expect("the baseline harness compiles");
    let baseline_instructions = gbuffer_validator::cost::spirv_instructions(&baseline_spirv);
    let baseline_gpu = timing::StageTimes::measure(
        &gpu,
        timing::BASELINE_ROW,
        &[],
        1,
        &timing::StageTimes::default(),
    );
    let luts: Vec<(usize, Vec<[f32; 2]>)> = [16, 32]
        .into_iter()
        .map(|size| (size, EnvBrdfLut::bake(size, 1024).texels))
        .collect();

    let row_compilers = compile_rows(&rows);
    let mut measured = Vec::new();
    for (index, row) in rows.iter().enumerate() {
        eprintln!(
            "[{}/{}] {}: {}",
            index + 1,
            rows.len(),
            row.family,
            row.name
        );
        let (module, spirv) =
            compile(&row.wgsl).unwrap_or_else(|error| panic!("{}: {error}", row.name));
        let (lut_size, lut) = match row.lut_size {
            Some(size) => luts
                .iter()
                .find(|(lut_size, _)| *lut_size == size)
                .map(|(size, texels)| (*size, texels.as_slice()))
                .unwrap_or((1, &[])),
            None => (1, &[][..]),
        };
        let gpu_time = timing::StageTimes::measure(&gpu, &row.wgsl, lut, lut_size, &baseline_gpu);
        measured.push(Measured {
            naga_expressions: gbuffer_validator::cost::naga_expressions(&module, "row_eval"),
            spirv_instructions: gbuffer_validator::cost::spirv_instructions(&spirv)
                .saturating_sub(baseline_instructions),
            gpu: gpu_time,
            cpu_ns_per_eval: timing::cpu_ns_per_eval(&row.cpu),
            compilers: ROW_TARGETS
                .iter()
                .map(|target| {
                    let column = row_compilers
                        .columns()
                        .iter()
                        .find(|column| column.target == *target)?;
                    Some(column.figure(index + 1)? - column.figure(0)?)
                })
                .collect(),
        });
    }

    let mut packing = packing::measure(&gpu, &baseline_gpu)?;
    let inconsistencies = check_consistency(&rows, &mut measured, &mut packing);
    print_table(&rows, &measured, &adapter, &row_compilers);
    packing::print(&packing, &gpu);
    let compiled_packing = packing::compile_on_compilers();
    report_line!("{}", compiled_packing.markdown());
    if !inconsistencies.is_empty() {
        report_line!(
            "\nthe timing did not resolve on {adapter}, so no time is printed: {}",
            inconsistencies.join("; ")
        );
    }
    let furnace = white_furnace();
    print_furnace(&furnace);
    let frames = frames::measure_all(folder, &|message| eprintln!("{message}"))?;
    frames::print(&frames, &adapter);
    let frame_shaders = frame_shaders::compile_frames();
    report_line!("{}", frame_shaders.markdown());
    let mut plots =
        write_plots(folder, &rows).map_err(|error| format!("writing plots: {error}"))?;
    plots.extend(
        write_time_plots(folder, &rows, &measured)
            .map_err(|error| format!("writing plots: {error}"))?,
    );
    let mut json = json_report(&rows, &measured, &adapter);
    json["packing"] = packing::json(&packing);
    json["packing_on_compilers"] = compiled_packing.json();
    json["compilers"] = row_compilers.provenance_json();
    json["timing_consistent"] = serde_json::json!(inconsistencies.is_empty());
    json["timing_inconsistencies"] = serde_json::json!(inconsistencies);
    json["frames"] = frames::json(&frames);
    json["frames_on_compilers"] = frame_shaders.json();
    json["white_furnace"] = serde_json::json!(furnace
        .iter()
        .map(|energy| serde_json::json!({"roughness": energy.roughness, "metal_head_on": energy.metal_head_on, "metal_grazing": energy.metal_grazing, "white_dielectric_max": energy.dielectric_max}))
        .collect::<Vec<_>>());
    let mut markdown = markdown_report(&rows, &measured, &adapter, &plots, &row_compilers);
    markdown.push_str(&packing::markdown(&packing, &gpu));
    markdown.push_str(&compiled_packing.markdown());
    if !inconsistencies.is_empty() {
        let _ = writeln!(
            markdown,
            "\n**The timing did not resolve on {adapter}**, so no time is printed: {}.",
            inconsistencies.join("; ")
        );
    }
    markdown.push_str(&furnace_markdown(&furnace));
    markdown.push_str(&frames::markdown(&frames, &adapter));
    markdown.push_str(&frame_shaders.markdown());
    for (name, contents) in [
        (
            "report.json",
            serde_json::to_string_pretty(&json).unwrap_or_default(),
        ),
        ("report.md", markdown),
    ] {
        let path = folder.join(name);
        std::fs::write(&path, contents)
            .map_err(|error| format!("cannot write {}: {error}", path.display()))?;
    }
    eprintln!("wrote {}", folder.display());
    match stdout::failure() {
        Some(error) => Err(format!("cannot write standard output: {error}")),
        None => Ok(()),
    }
}

/// Checks the adapter's times against the order the instruction counts predict, within each
/// family of rows and each format's two packing modes, in each stage; where they disagree,
/// every time is marked untrusted (and printed as n/r). The disagreements, a line each.
fn check_consistency(
    rows: &[Row],
    measured: &mut [Measured],
    packing: &mut [packing::PackingRow],
) -> Vec<String> {
    let mut families: Vec<&str> = rows.iter().map(|row| row.family).collect();
    families.dedup();
    let mut found = Vec::new();
    for stage in timing::Stage::ALL {
        let times: Vec<Option<timing::GpuTime>> = measured
            .iter()
            .map(|measured| measured.gpu.get(stage))
            .collect();
        for family in &families {
            let group: Vec<timing::Timed> = rows
                .iter()
                .zip(measured.iter())
                .zip(&times)
                .filter(|((row, _), _)| row.family == *family)
                .map(|((row, measured), time)| timing::Timed {
                    name: format!("{} ({})", row.name, stage.name()),
                    instructions: measured.spirv_instructions,
                    time: time.as_ref(),
                })
                .collect();
            found.extend(timing::inconsistencies(&group));
        }
        let packing_times: Vec<Option<timing::GpuTime>> =
            packing.iter().map(|row| row.time(stage)).collect();
        for group in packing::timed_groups(packing, &packing_times, stage) {
            found.extend(timing::inconsistencies(&group));
        }
    }
    if !found.is_empty() {
        for measured in measured.iter_mut() {
            measured.gpu.distrust();
        }
        packing::distrust(packing);
    }
    found
}

/// A time with three significant digits; `<X` where it is below the harness's resolution (X
/// the upper bound), "n/r" where the run's times were not trusted, "n/a" where it could not be
/// measured.
fn format_time(time: Option<timing::GpuTime>) -> String {
    match time {
        None => "n/a".to_string(),
        Some(time) if time.resolved() => significant(time.median_ns),
        Some(time) => match time.upper_bound_ns() {
            Some(bound) => format!("<{}", significant(bound)),
            None => "n/r".to_string(),
        },
    }
}

/// `value` with three significant digits.
fn significant(value: f64) -> String {
    let digits = (2 - value.abs().log10().floor() as i32).max(0) as usize;
    format!("{value:.digits$}")
}

/// The report's timing objects of a row: one per stage measured.
fn timings_json(times: &timing::StageTimes) -> serde_json::Value {
    let objects: Vec<serde_json::Value> = timing::Stage::ALL
        .into_iter()
        .filter_map(|stage| times.get(stage))
        .map(|time| {
            // A time below the harness's resolution has no median of its own (less the
            // harness's, it may read negative): only its upper bound is written.
            let resolved = time.resolved();
            let bound = time.upper_bound_ns();
            serde_json::json!({
                "stage": time.stage.name(),
                "clock": time.clock.name(),
                "evaluations_per_second": resolved.then(|| time.evaluations_per_second()),
                "evaluations_per_second_at_least": bound.map(|bound| 1e9 / bound),
                "evaluations_per_run": time.evaluations_per_run(),
                "run_ms": time.run_ms,
                "median_ns": resolved.then_some(time.median_ns),
                "min_ns": resolved.then_some(time.min_ns),
                "max_ns": resolved.then_some(time.max_ns),
                "upper_bound_ns": bound,
                "resolved": resolved,
            })
        })
        .collect();
    serde_json::json!(objects)
}

fn print_table(rows: &[Row], measured: &[Measured], adapter: &str, compiled: &compilers::Compiled) {
    report_line!("adapter: {adapter}");
    report_line!("{}", compiled.provenance());
    report_line!(
        "{:<17} {:<34} {:>4} {:>11} {:>11} {:<24} {:>5} {:>5} {:>8} {:>8} {:>8} {:>7} {:>6} {:>6}",
        "family",
        "row",
        "bits",
        "max error",
        "rms error",
        "unit",
        "naga",
        "spirv",
        "gpu ns",
        "frag ns",
        "cpu ns",
        "G610 cy",
        "A740",
        "navi21"
    );
    for (row, measured) in rows.iter().zip(measured) {
        report_line!(
            "{:<17} {:<34} {:>4} {:>11.3e} {:>11.3e} {:<24} {:>5} {:>5} {:>8} {:>8} {:>8.2} {:>7} {:>6} {:>6}",
            row.family,
            row.name,
            row.bits
                .map_or_else(|| "-".to_string(), |bits| bits.to_string()),
            row.errors.max,
            row.errors.rms,
            row.unit,
            measured.naga_expressions,
            measured.spirv_instructions,
            format_time(measured.gpu.compute),
            format_time(measured.gpu.fragment),
            measured.cpu_ns_per_eval,
            compilers::format_figure(measured.compilers[0]),
            compilers::format_figure(measured.compilers[1]),
            compilers::format_figure(measured.compilers[2]),
        );
    }
}

/// The report's JSON: `{"adapter", "rows": [...]}` with the schema of the issue.
fn json_report(rows: &[Row], measured: &[Measured], adapter: &str) -> serde_json::Value {
    let rows: Vec<serde_json::Value> = rows
        .iter()
        .zip(measured)
        .map(|(row, measured)| {
            let mut entry = serde_json::json!({
                "family": row.family,
                "name": row.name,
                "domain": row.domain,
                "unit": row.unit,
                "max_error": row.errors.max,
                "rms_error": row.errors.rms,
                "naga_expressions": measured.naga_expressions,
                "spirv_instructions": measured.spirv_instructions,
                "gpu_ns_per_eval": measured.gpu.compute.filter(timing::GpuTime::resolved).map(|time| time.median_ns),
                "timings": timings_json(&measured.gpu),
                "cpu_ns_per_eval": measured.cpu_ns_per_eval,
                "compilers": ROW_TARGETS.iter().zip(&measured.compilers).map(|(target, figure)| (target.to_string(), serde_json::json!(figure))).collect::<serde_json::Map<_, _>>(),
            });
            if let Some(bits) = row.bits {
                entry["bits"] = serde_json::json!(bits);
            }
            entry
        })
        .collect();
    serde_json::json!({ "adapter": adapter, "rows": rows })
}

/// A written plot: its file name and what the report says about it.
struct WrittenPlot {
    file: String,
    caption: String,
}

fn file_stem(name: &str) -> String {
    name.chars()
        .map(|character| {
            if character.is_ascii_alphanumeric() {
                character.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect::<String>()
        .split('_')
        .filter(|part| !part.is_empty())
        .collect::<Vec<_>>()
        .join("_")
}

fn write_plots(folder: &Path, rows: &[Row]) -> std::io::Result<Vec<WrittenPlot>> {
    let mut written = Vec::new();
    // The transfer curves share one chart.
    let mut labels = ("", "");
    let transfer: Vec<(&Row, &[(f64, f64)])> = rows
        .iter()
        .filter_map(|row| match &row.plot {
            Some(Plot::Curve {
                points,
                x_label,
                y_label,
            }) => {
                labels = (x_label, y_label);
                Some((row, points.as_slice()))
            }
            _ => None,
        })
        .collect();
    if !transfer.is_empty() {
        let file = "transfer_curves.png".to_string();
        let series: Vec<&[(f64, f64)]> = transfer.iter().map(|(_, points)| *points).collect();
        let (x_max, y_max) = plot::curves(&folder.join(&file), &series)?;
        let legend: Vec<String> = transfer
            .iter()
            .zip(plot::CURVE_COLOURS)
            .map(|((row, _), colour)| format!("{} ({colour})", row.name))
            .collect();
        written.push(WrittenPlot {
            file,
            caption: format!(
                "{} (0 to {y_max:.2}) against {} (0 to {x_max}): {}.",
                labels.1,
                labels.0,
                legend.join(", ")
            ),
        });
    }
    for row in rows {
        if let Some(Plot::Heatmap {
            width,
            height,
            values,
            x_label,
            y_label,
        }) = &row.plot
        {
            let file = format!("{}_{}.png", file_stem(row.family), file_stem(&row.name));
            let scale = if *width >= 256 { 2 } else { 6 };
            let maximum = plot::heatmap(&folder.join(&file), *width, *height, values, scale)?;
            written.push(WrittenPlot {
                file,
                caption: format!(
                    "{}, {}: error over {x_label} (left to right) and {y_label} (bottom to top), from dark blue (0) to yellow ({maximum:.3e} {}).",
                    row.family, row.name, row.unit
                ),
            });
        }
    }
    Ok(written)
}

/// Per family and stage, its rows' resolved times against their largest errors, on log-log
/// axes; none where no time resolved (a time the report cannot trust is not drawn either).
fn write_time_plots(
    folder: &Path,
    rows: &[Row],
    measured: &[Measured],
) -> std::io::Result<Vec<WrittenPlot>> {
    let mut written = Vec::new();
    let mut families: Vec<&str> = rows.iter().map(|row| row.family).collect();
    families.dedup();
    for family in families {
        for stage in timing::Stage::ALL {
            let members: Vec<(&Row, f64)> = rows
                .iter()
                .zip(measured)
                .filter(|(row, _)| row.family == family)
                .filter_map(|(row, measured)| {
                    let time = measured.gpu.get(stage).filter(timing::GpuTime::resolved)?;
                    Some((row, time.median_ns))
                })
                .collect();
            if members.len() < 2 {
                continue;
            }
            let file = format!("time_{}_{}.png", file_stem(family), stage.name());
            let points: Vec<(f64, f64)> = members
                .iter()
                .map(|(row, time)| (*time, row.errors.max))
                .collect();
            let ((x_low, x_high), (y_low, y_high)) =
                plot::log_scatter(&folder.join(&file), &points)?;
            let legend: Vec<String> = members
                .iter()
                .zip(plot::CURVE_COLOURS.iter().cycle())
                .map(|((row, _), colour)| format!("{} ({colour})", row.name))
                .collect();
            written.push(WrittenPlot {
                file,
                caption: format!(
                    "{family}, {} stage: largest error ({y_low:.2e} to {y_high:.2e} {}, log, bottom to top) against GPU ns per evaluation ({x_low:.3} to {x_high:.3}, log, left to right): {}.",
                    stage.name(),
                    members[0].0.unit,
                    legend.join(", ")
                ),
            });
        }
    }
    Ok(written)
}

fn markdown_report(
    rows: &[Row],
    measured: &[Measured],
    adapter: &str,
    plots: &[WrittenPlot],
    compiled: &compilers::Compiled,
) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# Speed and accuracy of every approximation and encoding\n"
    );
    let _ = writeln!(out, "Generated by `gbuffer report` on **{adapter}**. Errors are measured against the f64 references");
    let _ = writeln!(out, "of `gbuffer::shading::reference` over each row's domain; costs are naga IR expressions reachable from the row's");
    let _ = writeln!(out, "WGSL and the SPIR-V instructions it adds to a compute shader; GPU time (`median_ns` in report.json) is the median run's time divided by the run's evaluations, in nanoseconds: device ns per evaluation; runs are a dependent");
    let _ = writeln!(out, "chain whose length grows until a run lasts 10 ms (median of {} runs, wall clock around a synchronised submit, less the", timing::GPU_RUNS);
    let _ = writeln!(out, "harness's own time; `<X` where the median is within the runs' spread: the row is below the harness's resolution and X, the median plus the spread, bounds its time; n/r where the times were not trusted); CPU time is the f32 mirror's.");
    let _ = writeln!(out, "The last three columns are what one evaluation adds to a fragment shader (the GPU time's harness with a chain of one, less the same harness around an identity), compiled by the GPUs' own compilers: Mali-G610's estimated cycles per pixel, Adreno 740's and navi21's (ACO) instructions. {}\n", compiled.provenance());
    let mut family = "";
    for (row, measured) in rows.iter().zip(measured) {
        if row.family != family {
            family = row.family;
            let _ = writeln!(
                out,
                "\n## {family}\n\nDomain: {}. Unit: {}.\n",
                row.domain, row.unit
            );
            let _ = writeln!(out, "| row | bits | max error | RMS error | naga expressions | SPIR-V instructions | GPU ns/eval (compute) | GPU ns/eval (fragment) | CPU ns/eval | Mali-G610 cycles | Adreno 740 instructions | navi21 instructions |");
            let _ = writeln!(
                out,
                "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
            );
        }
        let _ = writeln!(
            out,
            "| {} | {} | {:.3e} | {:.3e} | {} | {} | {} | {} | {:.2} | {} | {} | {} |",
            row.name,
            row.bits
                .map_or_else(|| "-".to_string(), |bits| bits.to_string()),
            row.errors.max,
            row.errors.rms,
            measured.naga_expressions,
            measured.spirv_instructions,
            format_time(measured.gpu.compute),
            format_time(measured.gpu.fragment),
            measured.cpu_ns_per_eval,
            compilers::format_figure(measured.compilers[0]),
            compilers::format_figure(measured.compilers[1]),
            compilers::format_figure(measured.compilers[2]),
        );
    }
    let _ = writeln!(out, "\n## Plots\n");
    for plot in plots {
        let _ = writeln!(out, "![{}]({})\n\n{}\n", plot.file, plot.file, plot.caption);
    }
    out
}

/// The energy `shade_directional` reflects under a uniform white environment at one roughness.
struct FurnaceEnergy {
    roughness: f64,
    /// A white metal (f0 = 1) seen head on: what single scattering keeps.
    metal_head_on: f64,
    /// The same at n.v = 0.25.
    metal_grazing: f64,
    /// A white dielectric (albedo 1, f0 0.04), the largest over n.v in {0.1, 0.5, 1}.
    dielectric_max: f64,
}

fn white_furnace() -> Vec<FurnaceEnergy> {
    eprintln!("white furnace...");
    [0.045, 0.25, 0.5, 0.75, 1.0]
        .into_iter()
        .map(|roughness| FurnaceEnergy {
            roughness,
            metal_head_on: crate::furnace::accurate(roughness, 0.0, 1.0, 1.0),
            metal_grazing: crate::furnace::accurate(roughness, 0.0, 1.0, 0.25),
            dielectric_max: [0.1, 0.5, 1.0]
                .into_iter()
                .map(|n_dot_v| crate::furnace::accurate(roughness, 1.0, 0.04, n_dot_v))
                .fold(0.0, f64::max),
        })
        .collect()
}

fn print_furnace(furnace: &[FurnaceEnergy]) {
    report_line!("\nwhite furnace (energy reflected of 1 received):");
    report_line!(
        "{:>9} {:>14} {:>14} {:>16}",
        "roughness",
        "metal n.v=1",
        "metal n.v=0.25",
        "white dielectric"
    );
    for energy in furnace {
        report_line!(
            "{:>9} {:>14.4} {:>14.4} {:>16.4}",
            energy.roughness,
            energy.metal_head_on,
            energy.metal_grazing,
            energy.dielectric_max
        );
    }
}

fn furnace_markdown(furnace: &[FurnaceEnergy]) -> String {
    let mut out = String::from("\n## White furnace\n\nThe energy `shade_directional` reflects under a uniform white environment (1 received). A white dielectric (albedo 1, f0 0.04; largest over n.v 0.1, 0.5, 1) stays at 1: its diffuse takes what the specular lobe leaves. A white metal (f0 1) shows what single-scattering GGX loses to the light that would bounce between microfacets.\n\n| roughness | metal, n.v = 1 | metal, n.v = 0.25 | white dielectric | single scattering loses (n.v = 1) |\n| ---: | ---: | ---: | ---: | ---: |\n");
    for energy in furnace {
        let _ = writeln!(
            out,
            "| {} | {:.4} | {:.4} | {:.4} | {:.1}% |",
            energy.roughness,
            energy.metal_head_on,
            energy.metal_grazing,
            energy.dielectric_max,
            100.0 * (1.0 - energy.metal_head_on)
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row, every packing harness and every frame shader the report costs compiles on
    /// each GPU compiler and gives a figure (outside CI, a missing setup skips).
    #[test]
    fn the_report_compiles_everything_it_costs_on_the_gpu_compilers() {
        if !gbuffer_testkit::compilers_set_up() {
            return;
        }
        let rows = rows::rows();
        let compiled = compile_rows(&rows);
        assert_eq!(
            compiled.columns().len(),
            ROW_TARGETS.len(),
            "{}",
            compiled.provenance()
        );
        for column in compiled.columns() {
            for index in 0..=rows.len() {
                assert!(
                    column.figure(index).is_some(),
                    "{}: shader {index}",
                    column.target
                );
            }
        }
        let packing = packing::compile_on_compilers();
        let markdown = packing.markdown();
        assert!(!markdown.contains("| - |"), "{markdown}");
        // The guide's excerpt of the table is the report's lines, to the digit.
        let section = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../book/src/gpu-compilers.md"
        ))
        .expect("the guide's chapter on the GPUs' own compilers");
        let excerpt: Vec<&str> = section
            .lines()
            .filter(|line| line.starts_with("| ") && !line.starts_with("| format or layout"))
            .filter(|line| !line.starts_with("| ---"))
            .collect();
        assert!(excerpt.len() >= 10, "the guide's packing excerpt");
        for line in excerpt {
            assert!(
                markdown.lines().any(|report| report == line),
                "the guide's line\n{line}\nis not the report's; the report's table:\n{markdown}"
            );
        }
        let frames = frame_shaders::compile_frames();
        let markdown = frames.markdown();
        assert!(
            markdown.contains("mobile-metallic | fused native |"),
            "{markdown}"
        );
        assert!(markdown.contains("costs least on Mali-G610"), "{markdown}");
        // The guide quotes the report's line for mobile-metallic.
        let line = markdown
            .lines()
            .find(|line| line.starts_with("- mobile-metallic: "))
            .expect("a line for mobile-metallic");
        assert!(
            section.contains(line.trim_start_matches("- ")),
            "the guide does not quote the report's line:\n{line}"
        );
    }
}
