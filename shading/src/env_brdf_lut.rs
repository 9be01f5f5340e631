//! The split-sum environment BRDF as a lookup table: baked at a chosen size from the f64
//! reference integration, and sampled bilinearly as a GPU's linear sampler would.

use glam::Vec2;

use super::reference::environment::integrate_env_brdf;

/// A `size` x `size` table of (scale, bias): column i is n.v = (i + 0.5) / size, row j is
/// roughness = (j + 0.5) / size (texel centres, as a texture addresses them).
#[derive(Clone, Debug, PartialEq)]
pub struct EnvBrdfLut {
    /// Texels per side.
    pub size: usize,
    /// Row-major, `size * size` entries.
    pub texels: Vec<[f32; 2]>,
}

impl EnvBrdfLut {
    /// Integrates every texel with `sample_count` importance samples in f64.
    pub fn bake(size: usize, sample_count: u32) -> Self {
        let centre = |index: usize| (index as f64 + 0.5) / size as f64;
        let texels = (0..size * size)
            .map(|index| {
                let scale_bias =
                    integrate_env_brdf(centre(index / size), centre(index % size), sample_count);
                [scale_bias.x as f32, scale_bias.y as f32]
            })
            .collect();
        EnvBrdfLut { size, texels }
    }

    /// Bilinear lookup with clamp-to-edge addressing at (n.v, roughness) in [0, 1]^2.
    pub fn sample(&self, roughness: f32, n_dot_v: f32) -> Vec2 {
        let last = self.size as f32 - 1.0;
        let coordinate =
            |value: f32| (value.clamp(0.0, 1.0) * self.size as f32 - 0.5).clamp(0.0, last);
        let (column, row) = (coordinate(n_dot_v), coordinate(roughness));
        let (column0, row0) = (column.floor() as usize, row.floor() as usize);
        let (column1, row1) = (
            (column0 + 1).min(self.size - 1),
            (row0 + 1).min(self.size - 1),
        );
        let (across, down) = (column - column0 as f32, row - row0 as f32);
        let texel = |row: usize, column: usize| Vec2::from(self.texels[row * self.size + column]);
        let top = texel(row0, column0).lerp(texel(row0, column1), across);
        let bottom = texel(row1, column0).lerp(texel(row1, column1), across);
        top.lerp(bottom, down)
    }
}
