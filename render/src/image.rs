//! Frames as PNG files, and how far two frames are apart.

use std::path::Path;

use crate::options::Frame;

/// Writes an sRGB frame as an 8-bit RGBA PNG.
pub fn write_png(path: &Path, frame: &Frame) -> std::io::Result<()> {
    let pixels = bytemuck::cast_slice(&frame.pixels);
    encode_png(
        path,
        frame.width,
        frame.height,
        png::ColorType::Rgba,
        pixels,
    )
}

/// Writes 8-bit sRGB pixels, three bytes each, row by row from the top, as an RGB PNG (the
/// trade-off study's plots).
pub fn write_rgb_png(path: &Path, width: u32, height: u32, rgb: &[u8]) -> std::io::Result<()> {
    encode_png(path, width, height, png::ColorType::Rgb, rgb)
}

fn encode_png(
    path: &Path,
    width: u32,
    height: u32,
    colour: png::ColorType,
    pixels: &[u8],
) -> std::io::Result<()> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut encoder = png::Encoder::new(file, width, height);
    encoder.set_color(colour);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    writer
        .write_image_data(pixels)
        .map_err(std::io::Error::other)
}

/// The colour ramp of every error image (frame heat maps, the study's error maps): a
/// perceptually ordered map, dark blue, purple, orange to yellow, at `t` in [0, 1] (NaN and
/// values past the ends clamp, NaN to the top).
pub fn colour_ramp(t: f64) -> [u8; 3] {
    #[rustfmt::skip] // five stops of a small table
    const STOPS: [[f64; 3]; 5] = [
        [13.0, 8.0, 135.0], [126.0, 3.0, 168.0], [204.0, 71.0, 120.0], [248.0, 149.0, 64.0],
        [240.0, 249.0, 33.0],
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        1.0
    } * (STOPS.len() - 1) as f64;
    let index = (t.floor() as usize).min(STOPS.len() - 2);
    let fraction = t - index as f64;
    let mix = |channel: usize| {
        (STOPS[index][channel] * (1.0 - fraction) + STOPS[index + 1][channel] * fraction).round()
            as u8
    };
    [mix(0), mix(1), mix(2)]
}

/// How two frames of the same size differ, over the 8-bit colour channels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// Peak signal-to-noise ratio in dB (infinite for identical frames).
    pub psnr: f64,
    /// The largest difference of one channel, in 8-bit steps.
    pub max_error: u8,
    /// The share of pixels (0 to 1) with a channel more than one 8-bit step off.
    pub share_over_one_step: f64,
}

/// How `b` differs from `a`. Panics unless the frames have the same size.
pub fn compare(a: &Frame, b: &Frame) -> Comparison {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "frames of different sizes"
    );
    let mut squares = 0.0;
    let mut max_error = 0;
    let mut over_one_step = 0usize;
    for (pixel_a, pixel_b) in a.pixels.iter().zip(&b.pixels) {
        let mut pixel_error = 0;
        for channel in 0..3 {
            let difference = pixel_a[channel].abs_diff(pixel_b[channel]);
            pixel_error = pixel_error.max(difference);
            squares += f64::from(difference).powi(2);
        }
        max_error = max_error.max(pixel_error);
        over_one_step += usize::from(pixel_error > 1);
    }
    let mean_square = squares / (3 * a.pixels.len()) as f64;
    Comparison {
        psnr: 10.0 * (255.0 * 255.0 / mean_square).log10(),
        max_error,
        share_over_one_step: over_one_step as f64 / a.pixels.len() as f64,
    }
}

/// Where two frames differ, as a heat map: a pixel with no difference is black, any other is
/// coloured by its largest channel difference on [`colour_ramp`], logarithmically: dark blue
/// at 1 step, magenta at 4, yellow at 16 steps or more, so one-step rounding and a broken
/// highlight both show.
pub fn heatmap(a: &Frame, b: &Frame) -> Frame {
    per_pixel(a, b, |pixel_a, pixel_b| {
        let error = (0..3)
            .map(|index| pixel_a[index].abs_diff(pixel_b[index]))
            .max()
            .unwrap_or(0);
        if error == 0 {
            return [0, 0, 0, 255];
        }
        // log2(error) / 4: 0 at 1 step, 1 at 16.
        let [red, green, blue] = colour_ramp(f64::from(error).log2() / 4.0);
        [red, green, blue, 255]
    })
}

/// The absolute difference of two frames, amplified 8 times so small errors show.
pub fn difference(a: &Frame, b: &Frame) -> Frame {
    per_pixel(a, b, |pixel_a, pixel_b| {
        let channel = |index: usize| pixel_a[index].abs_diff(pixel_b[index]).saturating_mul(8);
        [channel(0), channel(1), channel(2), 255]
    })
}

/// A frame of `a`'s size whose pixels are `pixel` of `a`'s and `b`'s.
fn per_pixel(a: &Frame, b: &Frame, pixel: impl Fn(&[u8; 4], &[u8; 4]) -> [u8; 4]) -> Frame {
    Frame {
        width: a.width,
        height: a.height,
        pixels: a
            .pixels
            .iter()
            .zip(&b.pixels)
            .map(|(pixel_a, pixel_b)| pixel(pixel_a, pixel_b))
            .collect(),
    }
}

/// Whether a frame has content: its channels vary.
pub fn is_blank(frame: &Frame) -> bool {
    let first = frame.pixels.first().copied().unwrap_or_default();
    frame.pixels.iter().all(|pixel| pixel[..3] == first[..3])
}
