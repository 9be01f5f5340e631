//! PNG images of errors: heatmaps over a 2D domain, error-per-code curves, and time against
//! error per family. No text is drawn: the report names the axes, the ranges and the colour
//! scale beside each image.

use std::path::Path;

use gbuffer_render::image::{colour_ramp, write_rgb_png};

/// An image of a row's error.
pub enum Plot {
    /// A width x height grid of errors, row 0 at the bottom of the domain's y axis.
    Heatmap {
        width: usize,
        height: usize,
        values: Vec<f64>,
        x_label: &'static str,
        y_label: &'static str,
    },
    /// Errors at points (x, y).
    Curve {
        x_label: &'static str,
        y_label: &'static str,
        points: Vec<(f64, f64)>,
    },
}

/// A heatmap scaled to its maximum, each cell `scale` pixels wide, y up.
pub fn heatmap(
    path: &Path,
    width: usize,
    height: usize,
    values: &[f64],
    scale: usize,
) -> std::io::Result<f64> {
    let maximum = values
        .iter()
        .copied()
        .filter(|value| value.is_finite())
        .fold(0.0, f64::max);
    let (image_width, image_height) = (width * scale, height * scale);
    let mut rgb = vec![0u8; image_width * image_height * 3];
    for y in 0..image_height {
        for x in 0..image_width {
            let cell = (height - 1 - y / scale) * width + x / scale;
            let colour = colour_ramp(if maximum > 0.0 {
                values[cell] / maximum
            } else {
                0.0
            });
            rgb[(y * image_width + x) * 3..][..3].copy_from_slice(&colour);
        }
    }
    write_rgb_png(path, image_width as u32, image_height as u32, &rgb)?;
    Ok(maximum)
}

/// Curves of (x, y) points on one chart, y from 0 to the largest value, each series in its own
/// colour (in the order of `COLOURS`), with the axes drawn in grey.
pub fn curves(path: &Path, series: &[&[(f64, f64)]]) -> std::io::Result<(f64, f64)> {
    let (width, height, margin) = (768usize, 384usize, 16usize);
    let x_max = series
        .iter()
        .flat_map(|points| points.iter().map(|point| point.0))
        .fold(0.0, f64::max);
    let y_max = series
        .iter()
        .flat_map(|points| points.iter().map(|point| point.1))
        .fold(0.0, f64::max);
    let mut canvas = Canvas::with_axes(width, height, margin);
    let to_pixel = |(x, y): (f64, f64)| {
        let column = margin as f64 + x / x_max.max(f64::MIN_POSITIVE) * (width - 2 * margin) as f64;
        let row = (height - margin) as f64
            - y / y_max.max(f64::MIN_POSITIVE) * (height - 2 * margin) as f64;
        (column, row)
    };
    for (points, colour) in series.iter().zip(SERIES_COLOURS.iter().cycle()) {
        for pair in points.windows(2) {
            let (from, to) = (to_pixel(pair[0]), to_pixel(pair[1]));
            let steps = ((to.0 - from.0).abs().max((to.1 - from.1).abs()).ceil() as usize).max(1);
            for step in 0..=steps {
                let t = step as f64 / steps as f64;
                let (x, y) = (from.0 + (to.0 - from.0) * t, from.1 + (to.1 - from.1) * t);
                canvas.set(x.round() as usize, y.round() as usize, *colour);
                canvas.set(x.round() as usize, y.round() as usize + 1, *colour);
            }
        }
    }
    canvas.write(path)?;
    Ok((x_max, y_max))
}

/// The colours of a chart's series, in order; `CURVE_COLOURS` names them.
#[rustfmt::skip] // six colours of a small table
const SERIES_COLOURS: [[u8; 3]; 6] = [
    [0, 0, 0], [220, 50, 47], [38, 139, 210], [133, 153, 0], [211, 54, 130], [181, 137, 0],
];

/// The colour names of a chart's series (`curves`, `log_scatter`), for the report.
pub const CURVE_COLOURS: [&str; 6] = ["black", "red", "blue", "green", "magenta", "ochre"];

/// A white RGB image with grey axes along its left and bottom margins.
struct Canvas {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Canvas {
    fn with_axes(width: usize, height: usize, margin: usize) -> Canvas {
        let mut canvas = Canvas {
            width,
            height,
            rgb: vec![255; width * height * 3],
        };
        for x in margin..width - margin {
            canvas.set(x, height - margin, [160, 160, 160]);
        }
        for y in margin..height - margin {
            canvas.set(margin, y, [160, 160, 160]);
        }
        canvas
    }

    /// Colours pixel (x, y), y down; outside the image, nothing.
    fn set(&mut self, x: usize, y: usize, colour: [u8; 3]) {
        if x < self.width && y < self.height {
            self.rgb[(y * self.width + x) * 3..][..3].copy_from_slice(&colour);
        }
    }

    fn write(&self, path: &Path) -> std::io::Result<()> {
        write_rgb_png(path, self.width as u32, self.height as u32, &self.rgb)
    }
}

/// Points (x, y) on log-log axes spanning their ranges, a 7-pixel square each, in the colours
/// of `CURVE_COLOURS` by index, with the axes drawn in grey. Returns the ranges ((x low, x
/// high), (y low, y high)). Points that are not positive and finite are left out.
pub fn log_scatter(
    path: &Path,
    points: &[(f64, f64)],
) -> std::io::Result<((f64, f64), (f64, f64))> {
    let (width, height, margin) = (512usize, 384usize, 24usize);
    let shown: Vec<(usize, (f64, f64))> = points
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, (x, y))| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
        .collect();
    let range = |pick: fn(&(f64, f64)) -> f64| {
        let values = shown.iter().map(|(_, point)| pick(point).log10());
        let low = values.clone().fold(f64::INFINITY, f64::min);
        let high = values.fold(f64::NEG_INFINITY, f64::max);
        // A single value gets a decade around it.
        if high - low < 1e-9 {
            (low - 0.5, high + 0.5)
        } else {
            (low, high)
        }
    };
    let (x_range, y_range) = (range(|point| point.0), range(|point| point.1));
    let mut canvas = Canvas::with_axes(width, height, margin);
    for (index, (x, y)) in &shown {
        let column = margin as f64
            + (x.log10() - x_range.0) / (x_range.1 - x_range.0) * (width - 2 * margin) as f64;
        let row = (height - margin) as f64
            - (y.log10() - y_range.0) / (y_range.1 - y_range.0) * (height - 2 * margin) as f64;
        for dx in 0..7 {
            for dy in 0..7 {
                canvas.set(
                    (column.round() as usize + dx).saturating_sub(3),
                    (row.round() as usize + dy).saturating_sub(3),
                    SERIES_COLOURS[index % SERIES_COLOURS.len()],
                );
            }
        }
    }
    canvas.write(path)?;
    let power = |range: (f64, f64)| (10f64.powf(range.0), 10f64.powf(range.1));
    Ok((power(x_range), power(y_range)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_log_scatter_spans_its_points_and_leaves_out_the_unplottable() {
        let folder = std::env::temp_dir().join(format!("scatter-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let path = folder.join("scatter.png");
        let points = [(1.0, 0.5), (100.0, 0.005), (f64::NAN, 1.0), (0.0, 2.0)];
        let ((x_low, x_high), (y_low, y_high)) = log_scatter(&path, &points).unwrap();
        assert!((x_low - 1.0).abs() < 1e-9 && (x_high - 100.0).abs() < 1e-9);
        assert!((y_low - 0.005).abs() < 1e-12 && (y_high - 0.5).abs() < 1e-9);
        assert!(std::fs::metadata(&path).unwrap().len() > 100);
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
