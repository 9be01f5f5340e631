//! The plots the report writes beside `report.md` (transfer curves, error heat maps, time
//! against error) and their captions; the drawing itself is `plot.rs`'s.

use std::path::Path;

use gbuffer_core::Named;

use crate::measured::Measured;
use crate::plot::{self, Plot};
use crate::rows::Row;
use crate::timing;

/// A written plot: its file name and what the report says about it.
pub(crate) struct WrittenPlot {
    pub(crate) file: String,
    pub(crate) caption: String,
}

/// A file name's stem from a row's or family's name: lower case, runs of other characters as
/// one `_`.
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

/// The transfer curves' chart and each heat map a row has.
pub(crate) fn write_plots(folder: &Path, rows: &[Row]) -> std::io::Result<Vec<WrittenPlot>> {
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
pub(crate) fn write_time_plots(
    folder: &Path,
    rows: &[Row],
    measured: &[Measured],
) -> std::io::Result<Vec<WrittenPlot>> {
    let mut written = Vec::new();
    let mut families: Vec<&str> = rows.iter().map(|row| row.family).collect();
    families.dedup();
    for family in families {
        for &stage in timing::Stage::ALL {
            let members: Vec<(&Row, f64)> = rows
                .iter()
                .zip(measured)
                .filter(|(row, _)| row.family == family)
                .filter_map(|(row, measured)| {
                    let time = measured.gpu.get(stage).filter(timing::GpuTime::resolved)?;
                    Some((row, time.ns.median))
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
