//! What every backend renders from and to: the options of a frame (G-buffer, lighting forms,
//! size) and the frame itself.

use crate::gbuffers::GBuffer;

pub use gbuffer_solver::lighting::{IblForm, SunForm};

/// A frame size from the command line: `WIDTHxHEIGHT`, each between 1 and 8192.
pub fn parse_size(size: &str) -> Result<(u32, u32), String> {
    size.split_once('x')
        .and_then(|(width, height)| Some((width.parse::<u32>().ok()?, height.parse::<u32>().ok()?)))
        .filter(|&(width, height)| (1..=8192).contains(&width) && (1..=8192).contains(&height))
        .ok_or_else(|| {
            format!("bad size `{size}`: write WIDTHxHEIGHT, e.g. 1280x720 (at most 8192 each)")
        })
}

/// One configuration of the renderer. A solved G-buffer brings its scene description: the
/// scene shows its features, and the lighting pass is generated for them.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The G-buffer the frame goes through.
    pub gbuffer: GBuffer,
    /// The sun's specular form.
    pub sun: SunForm,
    /// The image-based light's form.
    pub ibl: IblForm,
    /// Frame width, pixels.
    pub width: u32,
    /// Frame height, pixels.
    pub height: u32,
}

/// A rendered frame: sRGB pixels, row by row.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// RGBA, 8 bits per channel, sRGB encoded.
    pub pixels: Vec<[u8; 4]>,
}

/// Exposure before tone mapping.
pub const EXPOSURE: f64 = 0.7;
