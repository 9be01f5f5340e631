//! The frame table's Vulkan paths: for each layout the on-tile paths keep, the frame time of
//! every Vulkan path (two-pass, and the fused subpass, local-read and local-read-ordered
//! paths) at the table's size, by the same protocol as the wgpu frames: the bench's Vulkan rows
//! at 1280x720, beside the layout's traffic. A path the device does not draw (local read without
//! `VK_KHR_dynamic_rendering_local_read`, rasterization order without its extension) has no
//! time, and the report says why.

use gbuffer_core::Named;
use gbuffer_gpu::timing::{time_items, Protocol, Spread};
use gbuffer_render::on_tile::{tile_layout, Path as TilePath, TileOptions};
use gbuffer_render::options::Options;
use gbuffer_render::vulkan::VulkanRenderer;

use crate::stdout::report_line;

/// The Vulkan paths the table times, in its columns' order.
pub const PATHS: [TilePath; 4] = [
    TilePath::TwoPass,
    TilePath::Subpass,
    TilePath::LocalRead,
    TilePath::LocalReadOrdered,
];

/// One layout's Vulkan frame times, milliseconds, a [`PATHS`] entry each: `None` where the
/// device does not draw the path.
pub type PathTimes = Vec<(TilePath, Option<Spread>)>;

/// Times the Vulkan paths of the layout `options` renders, if the on-tile paths keep it
/// (`None` otherwise): every path it draws, each once a round after warm-up rounds
/// ([`time_items`]), so that no clock change falls on one path. A path the device cannot draw
/// is reported through `progress` with the reason; any other failure is the error.
pub fn time_paths(
    vulkan: &VulkanRenderer,
    options: &Options,
    protocol: &Protocol,
    progress: &dyn Fn(&str),
) -> Result<Option<PathTimes>, String> {
    if tile_layout(options).is_err() {
        return Ok(None);
    }
    let mut frames = Vec::new();
    let mut drawn = Vec::new();
    for path in PATHS {
        let tile = TileOptions {
            options: options.clone(),
            path,
        };
        if let Some(reason) = vulkan.cannot_draw(path) {
            progress(&format!("frame table: no {} frames: {reason}", path.name()));
            continue;
        }
        frames.push(vulkan.timed_frame(&tile, &[])?);
        drawn.push(path);
    }
    let (warm, times) = time_items(protocol, frames.len(), &mut |index| frames[index].seconds())?;
    if !warm.settled {
        progress(&format!(
            "frame table: the Vulkan frame times did not settle in {} warm-up rounds",
            warm.runs
        ));
    }
    // `drawn` is in `PATHS`' order, and `times` in `drawn`'s.
    let mut times = times
        .into_iter()
        .map(|time| time.map(|seconds| seconds * 1e3));
    Ok(Some(
        (PATHS.iter())
            .map(|path| (*path, drawn.contains(path).then(|| times.next()).flatten()))
            .collect(),
    ))
}

/// A time's median in ms, followed by `unit`, or `-` where there is none.
fn median(time: &Option<Spread>, unit: &str) -> String {
    time.map_or_else(
        || "-".to_string(),
        |time| format!("{:.2}{unit}", time.median),
    )
}

/// The layouts' rows: name and times, for those the on-tile paths keep.
type Rows<'a> = Vec<(&'a str, &'a PathTimes)>;

/// The table as printed on stdout.
pub fn print(rows: &Rows, device: &str) {
    if rows.is_empty() {
        return;
    }
    report_line!(
        "\nVulkan frames of the layouts the on-tile paths keep, at the same size and by the same \
         protocol, median ms on {device} (`-`: the device does not draw the path):"
    );
    let names = PATHS.iter().map(|path| path.name().to_string());
    report_line!("{:<28} {}", "layout", columns(names));
    for (layout, times) in rows {
        report_line!(
            "{layout:<28} {}",
            columns(times.iter().map(|(_, time)| median(time, "")))
        );
    }
}

/// `cells` right-aligned in columns as wide as the widest path's name.
fn columns(cells: impl Iterator<Item = String>) -> String {
    cells
        .map(|cell| format!("{cell:>18}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The table in `report.md`, each time with its unit, by which the guide's copy of the table is
/// held to it within a tolerance (a CPU's frame times follow its load).
pub fn markdown(rows: &Rows, device: &str) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let names: Vec<&str> = PATHS.iter().map(|path| path.name()).collect();
    let mut out = format!(
        "\nThe layouts the on-tile paths keep, on each Vulkan path at the same size and by the same \
         protocol: the median frame ms on {device} (`report.json`'s `vulkan_frame_ms` has each \
         one's min and max; `-` where the device does not draw the path).\n\n\
         | layout | {} |\n| --- |{}\n",
        names.join(" | "),
        " --: |".repeat(PATHS.len())
    );
    for (layout, times) in rows {
        let cells: Vec<String> = times.iter().map(|(_, time)| median(time, " ms")).collect();
        out.push_str(&format!("| {layout} | {} |\n", cells.join(" | ")));
    }
    out
}

/// A layout's times as `report.json` holds them: each path's median, min and max (ms), `null`
/// where the device does not draw it.
pub fn json(times: &PathTimes) -> serde_json::Value {
    let mut object = serde_json::Map::new();
    for (path, time) in times {
        let value = match time {
            Some(time) => serde_json::json!({
                "median": time.median,
                "min": time.min,
                "max": time.max,
            }),
            None => serde_json::Value::Null,
        };
        object.insert(path.name().to_string(), value);
    }
    serde_json::Value::Object(object)
}
