//! The speed/accuracy trade of every approximation and encoding, side by side.
//!
//! Run with `cargo run --release -p gbuffer-cli --features report -- report`. Prints a table and writes
//! `target/tradeoff/report.md`, `report.json` and PNG plots (or into `--out DIR`). Each row's error is measured
//! against the f64 references over the stated domain; its cost is counted in naga IR
//! expressions and SPIR-V instructions; its time is measured on the adapter at hand, in a
//! compute dispatch and in a fullscreen draw's fragment shader (four dependent chains of
//! evaluations side by side, grown until a run lasts 10 ms and twice the chain takes twice the
//! time, every row timed once in each of 7 rounds after a warm-up, `gbuffer_gpu::timing`'s
//! protocol; the median round less the harness's own time, an upper bound `<X` where the
//! doubling failed or the time does not stand clear of the rounds' spread; pairs whose times
//! contradict the order the instruction counts predict are listed) and for its f32 mirror on
//! the CPU. The packing conversions get their own table: per format, exact and fast, their
//! instructions, branches, error in codes and time per million texels.
//!
//! # Where things are
//!
//! - the run: `lib.rs`; every approximation's and encoding's error in `rows/` (the row and its
//!   shared WGSL in `mod.rs`, the error statistics, the encodings', the shading
//!   approximations' and whole layouts' rows a file each);
//! - cost and time: `measured.rs`; the timing harness, its calibration and the rows timed
//!   together in `timing/`; the test that holds the packing rows to an independent round-trip
//!   chain in `independent_harness.rs`; the check that lists times out of the instruction
//!   counts' order in `consistency.rs`; packing costs; the GPU compilers' columns
//!   (`compilers.rs`);
//! - the white furnace (`furnace.rs`); the frame table (`frames.rs`: every layout's frame
//!   against the lossless G-buffer's, with its traffic, time and heat map; `vulkan_frames.rs`:
//!   each Vulkan path's frame time of the layouts the on-tile paths keep);
//! - the outputs: `table.rs` on standard output, `json.rs`, `markdown.rs`, the plots in
//!   `report_plots.rs`, drawn by `plot.rs`.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

pub mod compilers;
mod consistency;
pub mod frame_shaders;
pub mod frames;
pub mod furnace;
#[cfg(test)]
mod independent_harness;
mod json;
mod markdown;
mod measured;
pub mod packing;
pub mod packing_cost;
mod plot;
mod report_plots;
mod rows;
mod stdout;
mod table;
mod timing;
pub mod vulkan_frames;

use std::fmt::Write as _;
use std::path::Path;

use consistency::check_consistency;
use furnace::{furnace_json, furnace_markdown, print_furnace, white_furnace};
use gbuffer_gpu::adapter::{Gpu, Request};
use gbuffer_gpu::timing::Protocol;
use json::json_report;
use markdown::markdown_report;
use measured::compile_rows;
use report_plots::{write_plots, write_time_plots};
use stdout::report_line;
use table::print_table;

/// Each seed layout's largest error over the study's surfaces, in 8-bit sRGB steps (its "whole
/// layout" row), by the row's name (`Listing 2.2 (MobileMetallic)`): what the study predicts a
/// layout costs the picture.
pub fn layout_errors() -> Vec<(String, f64)> {
    rows::layout_rows()
        .into_iter()
        .map(|row| (row.name, row.errors.max))
        .collect()
}

/// Measures every row on the adapter at hand, prints the table and writes `report.md`,
/// `report.json` and the PNG plots into `folder` (created if missing). The error says what was
/// missing (an adapter) or names the file that could not be written.
pub fn run(folder: &Path) -> Result<(), String> {
    std::fs::create_dir_all(folder)
        .map_err(|error| format!("cannot create {}: {error}", folder.display()))?;
    let protocol = Protocol::chosen()?;
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

    // Every row of both tables timed together: one warm-up, the same rounds.
    let mut timer = timing::Timer::new(&gpu, protocol);
    let row_indices = measured::time_rows(&mut timer, &rows);
    let packing_indices = packing::time_rows(&mut timer);
    let times = timer.run();
    let pick = |indices: &[usize]| -> Vec<timing::StageTimes> {
        indices.iter().map(|&index| times[index]).collect()
    };
    let row_compilers = compile_rows(&rows);
    let measured = measured::measure_rows(&rows, &pick(&row_indices), &row_compilers);
    let packing = packing::measure(&gpu, &pick(&packing_indices))?;
    let inconsistencies = check_consistency(&rows, &measured, &packing);
    print_table(&rows, &measured, &adapter, &row_compilers);
    packing::print(&packing, &gpu);
    let compiled_packing = packing::compile_on_compilers();
    report_line!("{}", compiled_packing.markdown());
    if !inconsistencies.is_empty() {
        report_line!(
            "\ntimes out of the order the instruction counts predict on {adapter}: {}",
            inconsistencies.join("; ")
        );
    }
    let furnace = white_furnace();
    print_furnace(&furnace);
    let frames = frames::measure_all(folder, &protocol, &|message| eprintln!("{message}"))?;
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
    json["frames_vulkan_device"] = serde_json::json!(frames.vulkan);
    json["frames_on_compilers"] = frame_shaders.json();
    json["white_furnace"] = furnace_json(&furnace);
    let mut markdown = markdown_report(
        &rows,
        &measured,
        &adapter,
        &plots,
        &row_compilers,
        &protocol,
    );
    markdown.push_str(&packing::markdown(&packing, &gpu));
    markdown.push_str(&compiled_packing.markdown());
    if !inconsistencies.is_empty() {
        let _ = writeln!(
            markdown,
            "\nTimes out of the order the instruction counts predict on {adapter}: {}.",
            inconsistencies.join("; ")
        );
    }
    markdown.push_str(&furnace_markdown(&furnace));
    markdown.push_str(&frames::markdown(&frames, &adapter, &protocol));
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

#[cfg(test)]
mod tests {
    use super::*;
    use measured::ROW_TARGETS;

    /// Held by the tests that time work on the CPU's Vulkan driver and by those that keep
    /// every core busy (the GPU compilers under qemu): a time taken while another test fills
    /// the two cores says nothing about the work.
    pub(crate) static CORES: std::sync::Mutex<()> = std::sync::Mutex::new(());

    /// Every row, every packing harness and every frame shader the report costs compiles on
    /// each GPU compiler and gives a figure (outside CI, a missing setup skips).
    #[test]
    fn the_report_compiles_everything_it_costs_on_the_gpu_compilers() {
        let _cores = CORES
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
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
