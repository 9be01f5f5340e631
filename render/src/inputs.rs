//! The renderer's baked inputs, computed once on the CPU and uploaded as they are by every
//! backend, so that the wgpu, GLES and Vulkan frames sample the same texels:
//!
//! - the split-sum LUT (32x32 `Rgba16Float`: scale, bias, 0, 1);
//! - the light map (128x128 `Rgba8Unorm`, RGBM squared, range 6, as GPU Pro 7 Listing 2.5);
//! - the prefiltered sky: an equirectangular RGBM mip chain (`Rgba8Unorm`), mip m integrating
//!   the GGX lobe of roughness m / ENVIRONMENT_MIPS (Karis's split sum: n = v = r) with
//!   PREFILTER_SAMPLES importance samples, as the seed stores its PMREM (Listing 2.6).

use gbuffer_core::codecs::half::half_from_f32;
use gbuffer_core::codecs::unorm::unorm_from_f32;
use gbuffer_shading::env_brdf_lut::EnvBrdfLut;
use gbuffer_shading::mirror as m;
use glam::DVec3;

use crate::reference::{prefiltered_sky, PREFILTER_SAMPLES};
use crate::scene::{self, ENVIRONMENT_MIPS, ENVIRONMENT_RANGE, LIGHT_MAP_EXTENT, LIGHT_MAP_RANGE};

/// The split-sum LUT's size.
pub const LUT_SIZE: u32 = 32;
/// The light map's size.
pub const LIGHT_MAP_SIZE: u32 = 128;
/// The prefiltered environment's width at mip 0 (its height is half).
pub const ENVIRONMENT_WIDTH: u32 = 512;

/// One texture's texels, row by row, and its size.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Texels {
    /// Width, texels.
    pub width: u32,
    /// Height, texels.
    pub height: u32,
    /// The texel bytes, tightly packed.
    pub bytes: Vec<u8>,
}

/// Everything the passes sample.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Inputs {
    /// The split-sum LUT, `Rgba16Float`.
    pub lut: Texels,
    /// The light map, `Rgba8Unorm` RGBM squared.
    pub light_map: Texels,
    /// The prefiltered environment's mips, largest first, `Rgba8Unorm` RGBM.
    pub environment: Vec<Texels>,
}

impl Inputs {
    /// Bakes the inputs (rows shared between the machine's threads).
    pub fn bake() -> Inputs {
        let lut = lut_texels(
            LUT_SIZE,
            &EnvBrdfLut::bake(LUT_SIZE as usize, PREFILTER_SAMPLES).texels,
        );
        let light_map = Texels {
            width: LIGHT_MAP_SIZE,
            height: LIGHT_MAP_SIZE,
            bytes: rows(LIGHT_MAP_SIZE, LIGHT_MAP_SIZE, |x, y| {
                let centre = |coordinate: u32| {
                    ((f64::from(coordinate) + 0.5) / f64::from(LIGHT_MAP_SIZE) * 2.0 - 1.0)
                        * LIGHT_MAP_EXTENT
                };
                let irradiance = scene::light_map(centre(x), centre(y));
                m::hdr::rgbm_squared_encode(irradiance.as_vec3(), LIGHT_MAP_RANGE as f32).to_array()
            }),
        };
        let environment = (0..=ENVIRONMENT_MIPS)
            .map(|mip| {
                let (width, height) = (ENVIRONMENT_WIDTH >> mip, (ENVIRONMENT_WIDTH / 2) >> mip);
                let roughness = f64::from(mip) / f64::from(ENVIRONMENT_MIPS);
                Texels {
                    width,
                    height,
                    bytes: rows(width, height, |x, y| {
                        let normal = equirectangular_direction(
                            (f64::from(x) + 0.5) / f64::from(width),
                            (f64::from(y) + 0.5) / f64::from(height),
                        );
                        let radiance = prefiltered_sky(normal, roughness);
                        m::hdr::rgbm_encode(radiance.as_vec3(), ENVIRONMENT_RANGE as f32).to_array()
                    }),
                }
            })
            .collect();
        Inputs {
            lut,
            light_map,
            environment,
        }
    }
}

/// A `size` x `size` split-sum LUT of (scale, bias) pairs, row by row, as the `Rgba16Float`
/// texels every backend samples (scale, bias, 0, 1): filterable everywhere, where a
/// two-channel float format is not. Missing pairs are zero.
pub fn lut_texels(size: u32, pairs: &[[f32; 2]]) -> Texels {
    Texels {
        width: size,
        height: size,
        bytes: (0..(size * size) as usize)
            .map(|index| pairs.get(index).copied().unwrap_or([0.0, 0.0]))
            .flat_map(|[scale, bias]| [scale, bias, 0.0, 1.0].map(half_from_f32))
            .flat_map(|half| (half as u16).to_le_bytes())
            .collect(),
    }
}

/// The direction an equirectangular texture holds at (u, v): u around the vertical from -z
/// through +x, v from the zenith (the inverse of the shaders' `equirectangular`).
fn equirectangular_direction(u: f64, v: f64) -> DVec3 {
    let phi = (u - 0.5) * std::f64::consts::TAU;
    let theta = v * std::f64::consts::PI;
    DVec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        theta.sin() * phi.cos(),
    )
}

/// `Rgba8Unorm` texels of a `width` x `height` texture whose texel (x, y) holds
/// `texel(x, y)` (four values in [0, 1]), rows computed on the machine's threads.
fn rows(width: u32, height: u32, texel: impl Fn(u32, u32) -> [f32; 4] + Sync) -> Vec<u8> {
    crate::parallel::rows(
        height,
        |y| {
            (0..width)
                .flat_map(|x| texel(x, y).map(|value| unorm_from_f32(value, 8) as u8))
                .collect()
        },
        |_| {},
    )
}
