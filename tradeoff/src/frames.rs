//! The frame table: what each layout costs the picture, beside its bits, its traffic and its
//! time. Every shipped layout (the seed layouts, the engines', the layouts solved for the scene
//! presets) and a deliberately coarse one render the reference scene through the reference
//! renderer, and each frame is held against the lossless G-buffer's frame of the same scene
//! (every quantity an f32, the same passes): the difference is what the layout's storage
//! loses, apart from the renderer's own error against the CPU reference.
//!
//! Per layout: bits and words; the bandwidth units (width x height x 4 bytes) its frame moves
//! on wgpu (the G-buffer through memory) and, for the layouts the on-tile paths keep, on
//! Vulkan's two-pass and fused (subpass) paths; PSNR, largest error and the share of pixels
//! more than one 8-bit step off against the lossless frame; the frame time on the adapter (the
//! median of `gbuffer_gpu::timing`'s rounds, every layout timed once a round after warm-up
//! rounds, as the renderer's bench times them); and a heat map of where the error sits. For the
//! solved presets, also what the solver predicted for each quantity. For the layouts the
//! on-tile paths keep, each Vulkan path's frame time beside (`crate::vulkan_frames`).

use crate::stdout::report_line;
use std::path::Path;
use std::sync::Arc;

use gbuffer_core::Named;
use gbuffer_gpu::timing::{time_items, Protocol, Spread};
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::image::{compare, heatmap, write_png, Comparison};
use gbuffer_render::on_tile::{Path as TilePath, TileOptions};
use gbuffer_render::options::{Frame, IblForm, Options, SunForm};
use gbuffer_render::vulkan::VulkanRenderer;
use gbuffer_render::wgpu::Renderer;
use gbuffer_solver::presets::{solve_preset, PRESETS};
use gbuffer_solver::Solution;

use crate::vulkan_frames::{self, PathTimes};

/// The frame size of the table.
pub const SIZE: (u32, u32) = (1280, 720);

/// One layout's row.
#[derive(Clone, Debug)]
pub struct FrameRow {
    /// The layout's name: a packed layout's command-line name, or `preset <name>`.
    pub layout: String,
    /// What it is: `seed`, `engine`, `solved` or `coarse`.
    pub kind: &'static str,
    /// Bits the layout takes (its words x 32).
    pub bits: u32,
    /// Its 32-bit words.
    pub words: usize,
    /// Bandwidth units of the wgpu frame.
    pub wgpu_bandwidth_units: f64,
    /// Bandwidth units of Vulkan's two-pass path, where the on-tile paths keep the layout.
    pub two_pass_bandwidth_units: Option<f64>,
    /// Bandwidth units of Vulkan's fused (subpass) path, where it keeps the layout.
    pub fused_bandwidth_units: Option<f64>,
    /// Against the lossless frame of the same scene.
    pub comparison: Comparison,
    /// Frame times on the wgpu adapter over the protocol's rounds, milliseconds ([`measure_all`]
    /// times every layout's together).
    pub frame_ms: Spread,
    /// The heat map's file name, beside the report.
    pub heatmap: String,
    /// For a solved preset, each quantity's predicted error as the solver words it
    /// (`normal: 0.25 degrees`).
    pub predicted: Vec<String>,
    /// Each Vulkan path's frame times, milliseconds, where the on-tile paths keep the layout
    /// and Vulkan is there.
    pub vulkan_frame_ms: Option<PathTimes>,
}

/// The frame table: its rows, and the Vulkan device that drew the on-tile paths (none without
/// Vulkan).
#[derive(Clone, Debug)]
pub struct FrameTable {
    /// One a layout.
    pub rows: Vec<FrameRow>,
    /// The Vulkan device's name, API and driver versions.
    pub vulkan: Option<String>,
}

/// The packed layouts of the table, with their kind.
pub(crate) fn packed_layouts() -> Vec<(PackedLayout, &'static str)> {
    let seeds = PackedLayout::SEEDS.map(|layout| (layout, "seed"));
    let engines = PackedLayout::ENGINES.map(|layout| (layout, "engine"));
    seeds
        .into_iter()
        .chain(engines)
        .chain([(PackedLayout::CoarseNormals, "coarse")])
        .collect()
}

/// The table's options for `gbuffer`: GGX sun, LUT environment, [`SIZE`].
pub(crate) fn options(gbuffer: GBuffer) -> Options {
    Options {
        gbuffer,
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width: SIZE.0,
        height: SIZE.1,
    }
}

/// The renderers the table uses: wgpu always, Vulkan for the on-tile paths' traffic when it is
/// there (its absence leaves those columns empty, said once).
struct Renderers {
    wgpu: Renderer,
    vulkan: Option<VulkanRenderer>,
}

/// Measures one G-buffer, named `name` in the table, against `lossless`, with its frame times
/// (`frame_ms`, timed with every other layout's); writes its heat map into `folder`.
fn measure(
    renderers: &Renderers,
    (name, kind): (String, &'static str),
    gbuffer: GBuffer,
    (lossless, frame_ms): (&Frame, Spread),
    folder: &Path,
) -> Result<FrameRow, String> {
    let layout = gbuffer
        .layout()
        .ok_or_else(|| format!("`{name}` is not a packed G-buffer"))?;
    let options = options(gbuffer);
    let (frame, recording) = renderers.wgpu.render_recorded(&options)?;
    let comparison = compare(&frame, lossless);
    let tile_bandwidth = |path: TilePath| -> Result<Option<f64>, String> {
        let Some(vulkan) = &renderers.vulkan else {
            return Ok(None);
        };
        if gbuffer_render::on_tile::tile_layout(&options).is_err() {
            return Ok(None);
        }
        let tile = TileOptions {
            options: options.clone(),
            path,
        };
        let (_, recording) = vulkan.render(&tile)?;
        Ok(Some(
            recording
                .traffic(SIZE.0, SIZE.1)
                .bandwidth_units(SIZE.0, SIZE.1),
        ))
    };
    let file_stem = name.replace(|c: char| !c.is_ascii_alphanumeric(), "-");
    let heatmap_name = format!("frame-{file_stem}-heatmap.png");
    let heatmap_path = folder.join(&heatmap_name);
    write_png(&heatmap_path, &heatmap(&frame, lossless))
        .map_err(|error| format!("cannot write {}: {error}", heatmap_path.display()))?;
    Ok(FrameRow {
        layout: name,
        kind,
        bits: layout.bits(),
        words: layout.words(),
        wgpu_bandwidth_units: recording
            .traffic(SIZE.0, SIZE.1)
            .bandwidth_units(SIZE.0, SIZE.1),
        two_pass_bandwidth_units: tile_bandwidth(TilePath::TwoPass)?,
        fused_bandwidth_units: tile_bandwidth(TilePath::Subpass)?,
        comparison,
        frame_ms,
        heatmap: heatmap_name,
        predicted: Vec::new(),
        vulkan_frame_ms: None,
    })
}

impl FrameRow {
    /// The table's cells, as both the printed and the markdown table show them.
    fn cells(&self) -> [String; 11] {
        [
            self.layout.clone(),
            self.kind.to_string(),
            self.bits.to_string(),
            self.words.to_string(),
            format!("{:.2}", self.wgpu_bandwidth_units),
            bandwidth(self.two_pass_bandwidth_units),
            bandwidth(self.fused_bandwidth_units),
            format!("{:.2}", self.comparison.psnr),
            self.comparison.max_error.to_string(),
            format!("{:.3}%", self.comparison.share_over_one_step * 100.0),
            format!("{:.2}", self.frame_ms.median),
        ]
    }
}

/// The solver's predicted error of each quantity of a solution, as `gbuffer solve` words it.
fn predictions(solution: &Solution) -> Vec<String> {
    solution
        .placements
        .iter()
        .map(|placement| {
            format!(
                "{}: {}",
                placement.quantity.name(),
                gbuffer_solver::solver::describe_error(
                    placement.quantity,
                    placement.predicted_error
                )
            )
        })
        .collect()
}

/// Times every layout's frame together by the protocol (`gbuffer_gpu::timing::time_items`:
/// warm-up rounds, then each layout once a round, so that no clock change falls on one
/// layout), then renders each and measures it, writing the heat maps into `folder`, and times
/// the Vulkan paths of those the on-tile paths keep. The error says what is missing (the wgpu
/// adapter) or what failed.
pub fn measure_all(
    folder: &Path,
    protocol: &Protocol,
    progress: &dyn Fn(&str),
) -> Result<FrameTable, String> {
    let renderers = Renderers {
        wgpu: Renderer::new(progress)?,
        vulkan: match VulkanRenderer::new(progress) {
            Ok(vulkan) => Some(vulkan),
            Err(reason) => {
                progress(&format!(
                    "frame table: no Vulkan, so no two-pass and fused traffic ({reason})"
                ));
                None
            }
        },
    };
    // The table's layouts: each one's name, kind, G-buffer and, for a solved preset, its
    // solution.
    let mut layouts: Vec<(String, &'static str, GBuffer, Option<Arc<Solution>>)> = packed_layouts()
        .into_iter()
        .map(|(layout, kind)| {
            (
                layout.name().to_string(),
                kind,
                GBuffer::Packed(layout),
                None,
            )
        })
        .collect();
    for (preset, _) in PRESETS {
        let solution = Arc::new(solve_preset(preset)?);
        layouts.push((
            format!("preset {preset}"),
            "solved",
            GBuffer::Solved(solution.clone()),
            Some(solution),
        ));
    }
    progress(&format!(
        "frame table: timing {} frames in rounds",
        layouts.len()
    ));
    let frames = layouts
        .iter()
        .map(|(_, _, gbuffer, _)| renderers.wgpu.timed_frame(&options(gbuffer.clone())))
        .collect::<Result<Vec<_>, String>>()?;
    let (warm, times) = time_items(protocol, frames.len(), &mut |index| frames[index].seconds())?;
    drop(frames);
    if !warm.settled {
        progress(&format!(
            "frame table: the frame times did not settle in {} warm-up rounds",
            warm.runs
        ));
    }
    let packed_lossless = renderers
        .wgpu
        .render(&options(GBuffer::Packed(PackedLayout::Lossless)))?;
    let mut rows = Vec::new();
    for ((name, kind, gbuffer, solution), time) in layouts.into_iter().zip(times) {
        progress(&format!("frame table: {name}"));
        // A solved preset against the lossless G-buffer of its own scene.
        let scene_lossless = solution
            .as_ref()
            .map(|solution| {
                let features = solution.scene.features;
                renderers
                    .wgpu
                    .render(&options(GBuffer::LosslessScene(features)))
            })
            .transpose()?;
        let lossless = scene_lossless.as_ref().unwrap_or(&packed_lossless);
        let frame_ms = time.map(|seconds| seconds * 1e3);
        let tile_options = options(gbuffer.clone());
        let mut row = measure(
            &renderers,
            (name, kind),
            gbuffer,
            (lossless, frame_ms),
            folder,
        )?;
        if let Some(solution) = &solution {
            row.predicted = predictions(solution);
        }
        if let Some(vulkan) = &renderers.vulkan {
            row.vulkan_frame_ms =
                vulkan_frames::time_paths(vulkan, &tile_options, protocol, progress)?;
        }
        rows.push(row);
    }
    Ok(FrameTable {
        rows,
        vulkan: (renderers.vulkan.as_ref()).map(|vulkan| vulkan.describe().to_string()),
    })
}

/// The rows the Vulkan paths were timed for, with their times.
fn vulkan_rows(table: &FrameTable) -> Vec<(&str, &PathTimes)> {
    (table.rows.iter())
        .filter_map(|row| Some((row.layout.as_str(), row.vulkan_frame_ms.as_ref()?)))
        .collect()
}

fn bandwidth(units: Option<f64>) -> String {
    units.map_or_else(|| "-".to_string(), |units| format!("{units:.2}"))
}

/// The table as printed on stdout.
pub fn print(table: &FrameTable, adapter: &str) {
    let rows = &table.rows;
    report_line!(
        "\nframes at {}x{} against the lossless G-buffer (PSNR, largest error and share of \
         pixels over one 8-bit step), bandwidth units (width x height x 4 bytes) on wgpu and \
         Vulkan's two-pass and fused paths, median frame ms on {adapter}:",
        SIZE.0,
        SIZE.1
    );
    report_line!(
        "{:<28} {:<7} {:>4} {:>5} {:>6} {:>8} {:>6} {:>8} {:>8} {:>9} {:>9}",
        "layout",
        "kind",
        "bits",
        "words",
        "wgpu",
        "two-pass",
        "fused",
        "PSNR dB",
        "largest",
        "> 1 step",
        "frame ms"
    );
    for row in rows {
        let [layout, kind, bits, words, wgpu, two_pass, fused, psnr, largest, share, frame_ms] =
            row.cells();
        report_line!(
            "{layout:<28} {kind:<7} {bits:>4} {words:>5} {wgpu:>6} {two_pass:>8} {fused:>6} {psnr:>8} {largest:>8} {share:>9} {frame_ms:>9}"
        );
    }
    for row in rows.iter().filter(|row| !row.predicted.is_empty()) {
        report_line!(
            "{}: the solver predicted {}",
            row.layout,
            row.predicted.join("; ")
        );
    }
    if let Some(device) = &table.vulkan {
        vulkan_frames::print(&vulkan_rows(table), device);
    }
}

/// The rows as `report.json`'s `frames`.
pub fn json(table: &FrameTable) -> serde_json::Value {
    let rows: Vec<serde_json::Value> = (table.rows.iter())
        .map(|row| {
            serde_json::json!({
                "layout": row.layout,
                "kind": row.kind,
                "bits": row.bits,
                "words": row.words,
                "width": SIZE.0,
                "height": SIZE.1,
                "wgpu_bandwidth_units": row.wgpu_bandwidth_units,
                "two_pass_bandwidth_units": row.two_pass_bandwidth_units,
                "fused_bandwidth_units": row.fused_bandwidth_units,
                "psnr_db": row.comparison.psnr,
                "largest_error_steps": row.comparison.max_error,
                "share_over_one_step": row.comparison.share_over_one_step,
                "frame_ms_median": row.frame_ms.median,
                "frame_ms_min": row.frame_ms.min,
                "frame_ms_max": row.frame_ms.max,
                "heatmap": row.heatmap,
                "predicted_errors": row.predicted,
                "vulkan_frame_ms": row.vulkan_frame_ms.as_ref().map(vulkan_frames::json),
            })
        })
        .collect();
    serde_json::json!(rows)
}

/// The table in `report.md`, with each heat map linked.
pub fn markdown(table: &FrameTable, adapter: &str, protocol: &Protocol) -> String {
    let rows = &table.rows;
    let mut out = format!(
        "\n## Frames: what each layout costs the picture\n\n\
         The reference scene at {}x{}, each layout's frame against the lossless G-buffer's \
         (every quantity an f32, the same passes; for a solved preset, the lossless G-buffer of \
         its scene). Bandwidth in units of width x height x 4 bytes, from the passes' load and \
         store operations; `-` where the on-tile paths do not keep the layout or no Vulkan \
         was there. Frame time: the median of {} rounds on {adapter}, every layout's frame timed once \
         a round after warm-up rounds (`report.json` has each one's min and max; compare ratios, \
         not absolute times).\n\n\
         | layout | kind | bits | words | BU wgpu | BU two-pass | BU fused | PSNR dB | largest error (steps) | pixels > 1 step | frame ms | heat map |\n\
         | --- | --- | --: | --: | --: | --: | --: | --: | --: | --: | --: | --- |\n",
        SIZE.0,
        SIZE.1,
        protocol.rounds
    );
    for row in rows {
        let cells = row.cells().join(" | ");
        out.push_str(&format!("| {cells} | [png]({}) |\n", row.heatmap));
    }
    for row in rows.iter().filter(|row| !row.predicted.is_empty()) {
        out.push_str(&format!(
            "\n{}: the solver predicted {}.",
            row.layout,
            row.predicted.join("; ")
        ));
    }
    out.push('\n');
    if let Some(device) = &table.vulkan {
        out.push_str(&vulkan_frames::markdown(&vulkan_rows(table), device));
    }
    out
}
