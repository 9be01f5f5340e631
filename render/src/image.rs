//! Frames as PNG files, and how far two frames are apart.

use std::path::Path;

use crate::options::Frame;

/// Writes an sRGB frame as an 8-bit RGBA PNG.
pub fn write_png(path: &Path, frame: &Frame) -> std::io::Result<()> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut encoder = png::Encoder::new(file, frame.width, frame.height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    writer
        .write_image_data(bytemuck::cast_slice(&frame.pixels))
        .map_err(std::io::Error::other)
}

/// How two frames of the same size differ, over the 8-bit colour channels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// Peak signal-to-noise ratio in dB (infinite for identical frames).
    pub psnr: f64,
    /// The largest difference of one channel, in 8-bit steps.
    pub max_error: u8,
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
    for (pixel_a, pixel_b) in a.pixels.iter().zip(&b.pixels) {
        for channel in 0..3 {
            let difference = pixel_a[channel].abs_diff(pixel_b[channel]);
            max_error = max_error.max(difference);
            squares += f64::from(difference).powi(2);
        }
    }
    let mean_square = squares / (3 * a.pixels.len()) as f64;
    Comparison {
        psnr: 10.0 * (255.0 * 255.0 / mean_square).log10(),
        max_error,
    }
}

/// The absolute difference of two frames, amplified 8 times so small errors show.
pub fn difference(a: &Frame, b: &Frame) -> Frame {
    let pixels = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(pixel_a, pixel_b)| {
            let channel = |index: usize| pixel_a[index].abs_diff(pixel_b[index]).saturating_mul(8);
            [channel(0), channel(1), channel(2), 255]
        })
        .collect();
    Frame {
        width: a.width,
        height: a.height,
        pixels,
    }
}

/// Whether a frame has content: its channels vary.
pub fn is_blank(frame: &Frame) -> bool {
    let first = frame.pixels.first().copied().unwrap_or_default();
    frame.pixels.iter().all(|pixel| pixel[..3] == first[..3])
}
