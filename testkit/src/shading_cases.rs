//! Every function of the WGSL shading library as a test case: how to call it in WGSL, the
//! domain its arguments are sampled over, its f32 mirror, its f64 reference, and how close
//! the adapter must come to the mirror.

use gbuffer::glam::{DVec2, DVec3, DVec4, Vec2, Vec3, Vec4};
use gbuffer::shading::mirror as m;
use gbuffer::shading::reference as r;

use gbuffer_gpu::values::{fibonacci_sphere, halton};

/// How one argument is sampled.
#[derive(Clone, Copy, Debug)]
pub enum Argument {
    /// An f32 on a uniform grid over [low, high], both ends included.
    Scalar {
        /// The grid's first value.
        low: f32,
        /// Its last value.
        high: f32,
    },
    /// A vec3 from a fixed set of colours spanning [0, scale].
    Colour {
        /// The largest channel value.
        scale: f32,
    },
    /// A vec2 on a grid over [low, high]^2.
    Pair {
        /// The grid's first value on each axis.
        low: f32,
        /// Its last value.
        high: f32,
    },
    /// A unit vec3, spread over the sphere (a Fibonacci lattice).
    Direction,
    /// A vec4 tangent: a unit xyz and a sign in w.
    Tangent,
    /// A vec4 from a fixed set of RGBM texels.
    Rgbm,
    /// A u32 on a grid over [low, high].
    Unsigned {
        /// The grid's first value.
        low: u32,
        /// Its last value.
        high: u32,
    },
}

impl Argument {
    /// Components in the flattened argument list.
    pub fn components(self) -> usize {
        match self {
            Argument::Scalar { .. } | Argument::Unsigned { .. } => 1,
            Argument::Pair { .. } => 2,
            Argument::Colour { .. } | Argument::Direction => 3,
            Argument::Tangent | Argument::Rgbm => 4,
        }
    }

    /// The WGSL expression that reads this argument from `inputs[base + offset..]`.
    pub fn wgsl(self, offset: usize) -> String {
        let load = |index: usize| format!("inputs[base + {}u]", offset + index);
        let float = |index: usize| format!("bitcast<f32>({})", load(index));
        match self {
            Argument::Unsigned { .. } => load(0),
            Argument::Scalar { .. } => float(0),
            _ => {
                let count = self.components();
                let parts: Vec<String> = (0..count).map(float).collect();
                format!("vec{count}<f32>({})", parts.join(", "))
            }
        }
    }

    /// `count` sample values, each as its components' bits.
    pub fn samples(self, count: usize) -> Vec<Vec<u32>> {
        let steps =
            |count: usize| (0..count).map(move |index| index as f64 / (count.max(2) - 1) as f64);
        match self {
            Argument::Scalar { low, high } => steps(count)
                .map(|t| vec![lerp(low, high, t).to_bits()])
                .collect(),
            Argument::Unsigned { low, high } => steps(count)
                .map(|t| vec![(f64::from(low) + t * f64::from(high - low)).round() as u32])
                .collect(),
            Argument::Pair { low, high } => {
                let side = (count as f64).sqrt().ceil() as usize;
                let values: Vec<f32> = steps(side).map(|t| lerp(low, high, t)).collect();
                values
                    .iter()
                    .flat_map(|&x| values.iter().map(move |&y| vec![x.to_bits(), y.to_bits()]))
                    .collect()
            }
            // The named colours first, then a low-discrepancy spread over the cube.
            Argument::Colour { scale } => COLOURS
                .into_iter()
                .chain((1..).map(|index| [2, 3, 5].map(|base| halton(index, base) as f32)))
                .take(count.max(2))
                .map(|colour| colour.map(|c| (c * scale).to_bits()).to_vec())
                .collect(),
            Argument::Direction => fibonacci_sphere(count)
                .into_iter()
                .map(|d| d.to_array().map(f32::to_bits).to_vec())
                .collect(),
            Argument::Tangent => fibonacci_sphere(count)
                .into_iter()
                .enumerate()
                .map(|(index, d)| {
                    d.extend(if index % 2 == 0 { 1.0 } else { -1.0 })
                        .to_array()
                        .map(f32::to_bits)
                        .to_vec()
                })
                .collect(),
            Argument::Rgbm => RGBM_TEXELS
                .iter()
                .map(|texel| texel.map(f32::to_bits).to_vec())
                .collect(),
        }
    }
}

fn lerp(low: f32, high: f32, t: f64) -> f32 {
    (f64::from(low) + t * (f64::from(high) - f64::from(low))) as f32
}

/// Colours in [0, 1]: black, white, primaries, greys, a gold and a dark stone.
#[rustfmt::skip] // eight colours of a small table
const COLOURS: [[f32; 3]; 8] = [
    [0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0],
    [0.5, 0.5, 0.5], [1.0, 0.766, 0.336], [0.05, 0.04, 0.03],
];

const RGBM_TEXELS: [[f32; 4]; 6] = [
    [0.0, 0.0, 0.0, 0.0],
    [1.0, 1.0, 1.0, 1.0],
    [0.5, 0.25, 0.125, 0.2],
    [1.0, 0.0, 0.5, 0.003_921_569],
    [0.1, 0.9, 0.4, 0.75],
    [0.8, 0.8, 0.8, 0.5],
];

/// The function's values as f32 bits (floats) or raw u32 (integers).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// This many f32 components.
    Floats(usize),
    /// One u32.
    Unsigned,
}

/// An f64 reference over the widened arguments.
pub type Reference = fn(&[f64]) -> Vec<f64>;

/// One function under test.
pub struct Case {
    /// The WGSL module it lives in (composed with its dependencies).
    pub module: &'static str,
    /// The WGSL expression over the arguments `a0`, `a1`, ...
    pub call: &'static str,
    /// How each argument is sampled.
    pub arguments: &'static [Argument],
    /// What it returns.
    pub output: Output,
    /// The f32 mirror, over the arguments' bits.
    pub mirror: fn(&[u32]) -> Vec<u32>,
    /// The f64 reference, over the same arguments widened to f64 (None for integer-exact
    /// functions, which are their own reference).
    pub reference: Option<Reference>,
    /// The adapter may differ from the mirror by this many ulp...
    pub ulps: u32,
    /// ... or by this much absolutely (for results near zero, where ulps are tiny).
    pub absolute: f32,
}

impl Case {
    /// The function's name: the call up to its parenthesis.
    pub fn name(&self) -> &'static str {
        self.call.split('(').next().unwrap_or(self.call)
    }
}

// Argument helpers for the mirrors: the flattened bits to f32 values and glam vectors.
fn f(bits: &[u32], index: usize) -> f32 {
    f32::from_bits(bits[index])
}
fn v2(bits: &[u32], index: usize) -> Vec2 {
    Vec2::new(f(bits, index), f(bits, index + 1))
}
fn v3(bits: &[u32], index: usize) -> Vec3 {
    Vec3::new(f(bits, index), f(bits, index + 1), f(bits, index + 2))
}
fn v4(bits: &[u32], index: usize) -> Vec4 {
    Vec4::new(
        f(bits, index),
        f(bits, index + 1),
        f(bits, index + 2),
        f(bits, index + 3),
    )
}
fn out(values: &[f32]) -> Vec<u32> {
    values.iter().map(|value| value.to_bits()).collect()
}
fn d2(values: &[f64], index: usize) -> DVec2 {
    DVec2::new(values[index], values[index + 1])
}
fn d3(values: &[f64], index: usize) -> DVec3 {
    DVec3::new(values[index], values[index + 1], values[index + 2])
}
fn d4(values: &[f64], index: usize) -> DVec4 {
    DVec4::new(
        values[index],
        values[index + 1],
        values[index + 2],
        values[index + 3],
    )
}

use Argument::{Colour, Direction, Pair, Rgbm, Scalar, Tangent, Unsigned};

const UNIT: Argument = Scalar {
    low: 0.0,
    high: 1.0,
};
const ROUGHNESS: Argument = Scalar {
    low: 0.045,
    high: 1.0,
};
const COSINE: Argument = Scalar {
    low: 0.001,
    high: 1.0,
};
const HDR_COLOUR: Argument = Colour { scale: 6.0 };
const LIGHT_COLOUR: Argument = Colour { scale: 3.0 };
const COLOUR: Argument = Colour { scale: 1.0 };
/// A split-sum (scale, bias) pair: both in [0, 1] (their sum too, in the real LUT).
const ENV_BRDF: Argument = Pair {
    low: 0.0,
    high: 0.5,
};

/// Every function of the library.
pub fn cases() -> Vec<Case> {
    vec![
        // colour
        Case {
            module: "colour",
            call: "srgb_to_linear(a0)",
            arguments: &[COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::colour::srgb_to_linear(v3(a, 0)).to_array()),
            reference: Some(|a| r::colour::srgb_to_linear(d3(a, 0)).to_array().to_vec()),
            ulps: 16,
            absolute: 1e-6,
        },
        Case {
            module: "colour",
            call: "linear_to_srgb(a0)",
            arguments: &[COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::colour::linear_to_srgb(v3(a, 0)).to_array()),
            reference: Some(|a| r::colour::linear_to_srgb(d3(a, 0)).to_array().to_vec()),
            ulps: 16,
            absolute: 1e-6,
        },
        Case {
            module: "colour",
            call: "gamma_2_2_to_linear(a0)",
            arguments: &[COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::colour::gamma_2_2_to_linear(v3(a, 0)).to_array()),
            reference: Some(|a| r::colour::gamma_2_2_to_linear(d3(a, 0)).to_array().to_vec()),
            ulps: 16,
            absolute: 1e-6,
        },
        Case {
            module: "colour",
            call: "linear_to_gamma_2_2(a0)",
            arguments: &[COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::colour::linear_to_gamma_2_2(v3(a, 0)).to_array()),
            reference: Some(|a| r::colour::linear_to_gamma_2_2(d3(a, 0)).to_array().to_vec()),
            ulps: 16,
            absolute: 1e-6,
        },
        Case {
            module: "colour",
            call: "pseudo_gamma_to_linear(a0)",
            arguments: &[COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::colour::pseudo_gamma_to_linear(v3(a, 0)).to_array()),
            reference: Some(|a| {
                r::colour::pseudo_gamma_to_linear(d3(a, 0))
                    .to_array()
                    .to_vec()
            }),
            ulps: 1,
            absolute: 0.0,
        },
        Case {
            module: "colour",
            call: "linear_to_pseudo_gamma(a0)",
            arguments: &[COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::colour::linear_to_pseudo_gamma(v3(a, 0)).to_array()),
            reference: Some(|a| {
                r::colour::linear_to_pseudo_gamma(d3(a, 0))
                    .to_array()
                    .to_vec()
            }),
            ulps: 4,
            absolute: 0.0,
        },
        Case {
            module: "colour",
            call: "luminance(a0)",
            arguments: &[HDR_COLOUR],
            output: Output::Floats(1),
            mirror: |a| out(&[m::colour::luminance(v3(a, 0))]),
            reference: Some(|a| vec![r::colour::luminance(d3(a, 0))]),
            ulps: 4,
            absolute: 1e-7,
        },
        // hdr
        Case {
            module: "hdr",
            call: "rgbm_encode(a0, a1)",
            arguments: &[
                HDR_COLOUR,
                Scalar {
                    low: 1.0,
                    high: 8.0,
                },
            ],
            output: Output::Floats(4),
            mirror: |a| out(&m::hdr::rgbm_encode(v3(a, 0), f(a, 3)).to_array()),
            reference: Some(|a| r::hdr::rgbm_encode(d3(a, 0), a[3]).to_array().to_vec()),
            ulps: 8,
            absolute: 1e-6,
        },
        Case {
            module: "hdr",
            call: "rgbm_decode(a0, a1)",
            arguments: &[
                Rgbm,
                Scalar {
                    low: 1.0,
                    high: 8.0,
                },
            ],
            output: Output::Floats(3),
            mirror: |a| out(&m::hdr::rgbm_decode(v4(a, 0), f(a, 4)).to_array()),
            reference: Some(|a| r::hdr::rgbm_decode(d4(a, 0), a[4]).to_array().to_vec()),
            ulps: 2,
            absolute: 0.0,
        },
        Case {
            module: "hdr",
            call: "rgbm_squared_encode(a0, a1)",
            arguments: &[
                HDR_COLOUR,
                Scalar {
                    low: 1.0,
                    high: 8.0,
                },
            ],
            output: Output::Floats(4),
            mirror: |a| out(&m::hdr::rgbm_squared_encode(v3(a, 0), f(a, 3)).to_array()),
            reference: Some(|a| {
                r::hdr::rgbm_squared_encode(d3(a, 0), a[3])
                    .to_array()
                    .to_vec()
            }),
            ulps: 8,
            absolute: 1e-6,
        },
        Case {
            module: "hdr",
            call: "rgbm_squared_decode(a0, a1)",
            arguments: &[
                Rgbm,
                Scalar {
                    low: 1.0,
                    high: 8.0,
                },
            ],
            output: Output::Floats(3),
            mirror: |a| out(&m::hdr::rgbm_squared_decode(v4(a, 0), f(a, 4)).to_array()),
            reference: Some(|a| {
                r::hdr::rgbm_squared_decode(d4(a, 0), a[4])
                    .to_array()
                    .to_vec()
            }),
            ulps: 4,
            absolute: 0.0,
        },
        Case {
            module: "hdr",
            call: "scale_hdr_to_unit(a0, a1)",
            arguments: &[
                HDR_COLOUR,
                Scalar {
                    low: 1.0,
                    high: 16.0,
                },
            ],
            output: Output::Floats(3),
            mirror: |a| out(&m::hdr::scale_hdr_to_unit(v3(a, 0), f(a, 3)).to_array()),
            reference: Some(|a| {
                r::hdr::scale_hdr_to_unit(d3(a, 0), a[3])
                    .to_array()
                    .to_vec()
            }),
            ulps: 4,
            absolute: 0.0,
        },
        Case {
            module: "hdr",
            call: "scale_unit_to_hdr(a0, a1)",
            arguments: &[
                COLOUR,
                Scalar {
                    low: 1.0,
                    high: 16.0,
                },
            ],
            output: Output::Floats(3),
            mirror: |a| out(&m::hdr::scale_unit_to_hdr(v3(a, 0), f(a, 3)).to_array()),
            reference: Some(|a| {
                r::hdr::scale_unit_to_hdr(d3(a, 0), a[3])
                    .to_array()
                    .to_vec()
            }),
            ulps: 1,
            absolute: 0.0,
        },
        Case {
            module: "hdr",
            call: "rgb9e5_encode(a0)",
            arguments: &[Colour { scale: 70000.0 }],
            output: Output::Unsigned,
            mirror: |a| vec![m::hdr::rgb9e5_encode(v3(a, 0))],
            reference: None,
            ulps: 0,
            absolute: 0.0,
        },
        Case {
            module: "hdr",
            call: "rgb9e5_decode(a0)",
            arguments: &[Unsigned {
                low: 0,
                high: u32::MAX,
            }],
            output: Output::Floats(3),
            mirror: |a| out(&m::hdr::rgb9e5_decode(a[0]).to_array()),
            reference: None,
            ulps: 0,
            absolute: 0.0,
        },
        // microfacet
        Case {
            module: "microfacet",
            call: "d_ggx(a0, a1)",
            arguments: &[UNIT, ROUGHNESS],
            output: Output::Floats(1),
            mirror: |a| out(&[m::microfacet::d_ggx(f(a, 0), f(a, 1))]),
            reference: Some(|a| vec![r::microfacet::d_ggx(a[0], a[1])]),
            ulps: 8,
            absolute: 0.0,
        },
        Case {
            module: "microfacet",
            call: "v_smith_ggx_correlated(a0, a1, a2)",
            arguments: &[COSINE, COSINE, ROUGHNESS],
            output: Output::Floats(1),
            mirror: |a| {
                out(&[m::microfacet::v_smith_ggx_correlated(
                    f(a, 0),
                    f(a, 1),
                    f(a, 2),
                )])
            },
            reference: Some(|a| vec![r::microfacet::v_smith_ggx_correlated(a[0], a[1], a[2])]),
            ulps: 16,
            absolute: 0.0,
        },
        Case {
            module: "microfacet",
            call: "v_schlick_ggx(a0, a1, a2)",
            arguments: &[UNIT, UNIT, ROUGHNESS],
            output: Output::Floats(1),
            mirror: |a| out(&[m::microfacet::v_schlick_ggx(f(a, 0), f(a, 1), f(a, 2))]),
            reference: Some(|a| vec![r::microfacet::v_schlick_ggx(a[0], a[1], a[2])]),
            ulps: 8,
            absolute: 0.0,
        },
        Case {
            module: "microfacet",
            call: "schlick_weight(a0)",
            arguments: &[UNIT],
            output: Output::Floats(1),
            mirror: |a| out(&[m::microfacet::schlick_weight(f(a, 0))]),
            reference: Some(|a| vec![(1.0 - a[0]).powi(5)]),
            ulps: 8,
            absolute: 1e-7,
        },
        Case {
            module: "microfacet",
            call: "f_schlick(a0, a1)",
            arguments: &[COLOUR, UNIT],
            output: Output::Floats(3),
            mirror: |a| out(&m::microfacet::f_schlick(v3(a, 0), f(a, 3)).to_array()),
            reference: Some(|a| r::microfacet::f_schlick(d3(a, 0), a[3]).to_array().to_vec()),
            ulps: 8,
            absolute: 1e-7,
        },
        Case {
            module: "microfacet",
            call: "f_schlick_roughness(a0, a1, a2)",
            arguments: &[
                COLOUR,
                Scalar {
                    low: -0.5,
                    high: 1.0,
                },
                UNIT,
            ],
            output: Output::Floats(3),
            mirror: |a| {
                out(&m::microfacet::f_schlick_roughness(v3(a, 0), f(a, 3), f(a, 4)).to_array())
            },
            reference: Some(|a| {
                r::microfacet::f_schlick_roughness(d3(a, 0), a[3], a[4])
                    .to_array()
                    .to_vec()
            }),
            ulps: 8,
            absolute: 1e-7,
        },
        Case {
            module: "microfacet",
            call: "lambert_diffuse(a0)",
            arguments: &[COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::microfacet::lambert_diffuse(v3(a, 0)).to_array()),
            reference: Some(|a| r::microfacet::lambert_diffuse(d3(a, 0)).to_array().to_vec()),
            ulps: 1,
            absolute: 0.0,
        },
        // mobile
        Case {
            module: "mobile",
            call: "env_brdf_approx(a0, a1, a2)",
            arguments: &[COLOUR, UNIT, UNIT],
            output: Output::Floats(3),
            mirror: |a| out(&m::mobile::env_brdf_approx(v3(a, 0), f(a, 3), f(a, 4)).to_array()),
            reference: Some(|a| {
                r::mobile::env_brdf_approx(d3(a, 0), a[3], a[4])
                    .to_array()
                    .to_vec()
            }),
            ulps: 16,
            absolute: 1e-6,
        },
        Case {
            module: "mobile",
            call: "env_brdf_approx_nonmetal(a0, a1)",
            arguments: &[UNIT, UNIT],
            output: Output::Floats(1),
            mirror: |a| out(&[m::mobile::env_brdf_approx_nonmetal(f(a, 0), f(a, 1))]),
            reference: Some(|a| vec![r::mobile::env_brdf_approx_nonmetal(a[0], a[1])]),
            ulps: 16,
            absolute: 1e-6,
        },
        Case {
            module: "mobile",
            call: "fully_rough_diffuse_colour(a0, a1)",
            arguments: &[COLOUR, COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::mobile::fully_rough_diffuse_colour(v3(a, 0), v3(a, 3)).to_array()),
            reference: Some(|a| {
                r::mobile::fully_rough_diffuse_colour(d3(a, 0), d3(a, 3))
                    .to_array()
                    .to_vec()
            }),
            ulps: 2,
            absolute: 0.0,
        },
        Case {
            module: "mobile",
            call: "d_approx(a0, a1)",
            arguments: &[
                Scalar {
                    low: 0.0625,
                    high: 1.0,
                },
                Scalar {
                    low: -1.0,
                    high: 1.0,
                },
            ],
            output: Output::Floats(1),
            mirror: |a| out(&[m::mobile::d_approx(f(a, 0), f(a, 1))]),
            reference: Some(|a| vec![r::mobile::d_approx(a[0], a[1])]),
            ulps: 64,
            absolute: 1e-30,
        },
        // environment
        Case {
            module: "environment",
            call: "ibl_mip_level(a0, a1)",
            arguments: &[
                UNIT,
                Scalar {
                    low: 1.0,
                    high: 12.0,
                },
            ],
            output: Output::Floats(1),
            mirror: |a| out(&[m::environment::ibl_mip_level(f(a, 0), f(a, 1))]),
            reference: Some(|a| vec![r::environment::ibl_mip_level(a[0], a[1])]),
            ulps: 1,
            absolute: 0.0,
        },
        Case {
            module: "environment",
            call: "hammersley(a0, a1)",
            arguments: &[
                Unsigned { low: 0, high: 4095 },
                Unsigned {
                    low: 4096,
                    high: 4096,
                },
            ],
            output: Output::Floats(2),
            mirror: |a| out(&m::environment::hammersley(a[0], a[1]).to_array()),
            reference: Some(|a| {
                r::environment::hammersley(a[0] as u32, a[1] as u32)
                    .to_array()
                    .to_vec()
            }),
            ulps: 1,
            absolute: 0.0,
        },
        Case {
            module: "environment",
            call: "importance_sample_ggx(a0, a1)",
            arguments: &[
                Pair {
                    low: 0.0,
                    high: 0.999,
                },
                ROUGHNESS,
            ],
            output: Output::Floats(3),
            mirror: |a| out(&m::environment::importance_sample_ggx(v2(a, 0), f(a, 2)).to_array()),
            reference: Some(|a| {
                r::environment::importance_sample_ggx(d2(a, 0), a[2])
                    .to_array()
                    .to_vec()
            }),
            ulps: 64,
            absolute: 2e-6,
        },
        Case {
            module: "environment",
            call: "integrate_env_brdf(a0, a1, a2)",
            arguments: &[UNIT, COSINE, Unsigned { low: 64, high: 64 }],
            output: Output::Floats(2),
            mirror: |a| out(&m::environment::integrate_env_brdf(f(a, 0), f(a, 1), a[2]).to_array()),
            reference: Some(|a| {
                r::environment::integrate_env_brdf(a[0], a[1], a[2] as u32)
                    .to_array()
                    .to_vec()
            }),
            ulps: 256,
            absolute: 1e-5,
        },
        Case {
            module: "environment",
            call: "ibl_specular_seed(a0, a1, a2, a3)",
            arguments: &[HDR_COLOUR, COLOUR, UNIT, UNIT],
            output: Output::Floats(3),
            mirror: |a| {
                out(
                    &m::environment::ibl_specular_seed(v3(a, 0), v3(a, 3), f(a, 6), f(a, 7))
                        .to_array(),
                )
            },
            reference: Some(|a| {
                r::environment::ibl_specular_seed(d3(a, 0), d3(a, 3), a[6], a[7])
                    .to_array()
                    .to_vec()
            }),
            ulps: 8,
            absolute: 1e-6,
        },
        // material
        Case {
            module: "material",
            call: "metallic_workflow(a0, a1, a2).diffuse",
            arguments: &[
                COLOUR,
                UNIT,
                Scalar {
                    low: 0.0,
                    high: 0.08,
                },
            ],
            output: Output::Floats(3),
            mirror: |a| {
                out(&m::material::metallic_workflow(v3(a, 0), f(a, 3), f(a, 4))
                    .diffuse
                    .to_array())
            },
            reference: Some(|a| {
                r::material::metallic_workflow(d3(a, 0), a[3], a[4])
                    .diffuse
                    .to_array()
                    .to_vec()
            }),
            ulps: 2,
            absolute: 0.0,
        },
        Case {
            module: "material",
            call: "metallic_workflow(a0, a1, a2).f0",
            arguments: &[
                COLOUR,
                UNIT,
                Scalar {
                    low: 0.0,
                    high: 0.08,
                },
            ],
            output: Output::Floats(3),
            mirror: |a| {
                out(&m::material::metallic_workflow(v3(a, 0), f(a, 3), f(a, 4))
                    .f0
                    .to_array())
            },
            reference: Some(|a| {
                r::material::metallic_workflow(d3(a, 0), a[3], a[4])
                    .f0
                    .to_array()
                    .to_vec()
            }),
            ulps: 4,
            absolute: 1e-8,
        },
        Case {
            module: "material",
            call: "dielectric_f0_from_specular(a0)",
            arguments: &[UNIT],
            output: Output::Floats(1),
            mirror: |a| out(&[m::material::dielectric_f0_from_specular(f(a, 0))]),
            reference: Some(|a| vec![r::material::dielectric_f0_from_specular(a[0])]),
            ulps: 1,
            absolute: 0.0,
        },
        Case {
            module: "material",
            call: "specular_workflow(a0, a1).diffuse",
            arguments: &[COLOUR, COLOUR],
            output: Output::Floats(3),
            mirror: |a| {
                out(&m::material::specular_workflow(v3(a, 0), v3(a, 3))
                    .diffuse
                    .to_array())
            },
            reference: Some(|a| {
                r::material::specular_workflow(d3(a, 0), d3(a, 3))
                    .diffuse
                    .to_array()
                    .to_vec()
            }),
            ulps: 2,
            absolute: 0.0,
        },
        // normals
        Case {
            module: "normals",
            call: "reconstruct_tangent_z(a0)",
            arguments: &[Pair {
                low: -1.0,
                high: 1.0,
            }],
            output: Output::Floats(3),
            mirror: |a| out(&m::normals::reconstruct_tangent_z(v2(a, 0)).to_array()),
            reference: Some(|a| {
                r::normals::reconstruct_tangent_z(d2(a, 0))
                    .to_array()
                    .to_vec()
            }),
            ulps: 8,
            absolute: 1e-6,
        },
        Case {
            module: "normals",
            call: "tangent_to_world(a0, a1, a2)",
            arguments: &[Direction, Direction, Tangent],
            output: Output::Floats(3),
            mirror: |a| out(&m::normals::tangent_to_world(v3(a, 0), v3(a, 3), v4(a, 6)).to_array()),
            reference: Some(|a| {
                r::normals::tangent_to_world(d3(a, 0), d3(a, 3), d4(a, 6))
                    .to_array()
                    .to_vec()
            }),
            ulps: 64,
            absolute: 1e-5,
        },
        Case {
            module: "normals",
            call: "octahedral_encode(a0)",
            arguments: &[Direction],
            output: Output::Floats(2),
            mirror: |a| out(&m::normals::octahedral_encode(v3(a, 0)).to_array()),
            reference: Some(|a| r::normals::octahedral_encode(d3(a, 0)).to_array().to_vec()),
            ulps: 8,
            absolute: 1e-7,
        },
        Case {
            module: "normals",
            call: "octahedral_decode(a0)",
            arguments: &[Pair {
                low: -1.0,
                high: 1.0,
            }],
            output: Output::Floats(3),
            mirror: |a| out(&m::normals::octahedral_decode(v2(a, 0)).to_array()),
            reference: Some(|a| r::normals::octahedral_decode(d2(a, 0)).to_array().to_vec()),
            ulps: 16,
            absolute: 1e-6,
        },
        Case {
            module: "normals",
            call: "normal_to_unorm(a0)",
            arguments: &[Direction],
            output: Output::Floats(3),
            mirror: |a| out(&m::normals::normal_to_unorm(v3(a, 0)).to_array()),
            reference: Some(|a| r::normals::normal_to_unorm(d3(a, 0)).to_array().to_vec()),
            ulps: 2,
            absolute: 1e-7,
        },
        Case {
            module: "normals",
            call: "unorm_to_normal(a0)",
            arguments: &[Colour { scale: 1.0 }],
            output: Output::Floats(3),
            mirror: |a| out(&m::normals::unorm_to_normal(v3(a, 0)).to_array()),
            reference: Some(|a| r::normals::unorm_to_normal(d3(a, 0)).to_array().to_vec()),
            ulps: 16,
            absolute: 1e-6,
        },
        // tonemap
        Case {
            module: "tonemap",
            call: "tonemap_reinhard(a0)",
            arguments: &[HDR_COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::tonemap::tonemap_reinhard(v3(a, 0)).to_array()),
            reference: Some(|a| r::tonemap::tonemap_reinhard(d3(a, 0)).to_array().to_vec()),
            ulps: 4,
            absolute: 0.0,
        },
        Case {
            module: "tonemap",
            call: "tonemap_aces_fitted(a0)",
            arguments: &[HDR_COLOUR],
            output: Output::Floats(3),
            mirror: |a| out(&m::tonemap::tonemap_aces_fitted(v3(a, 0)).to_array()),
            reference: Some(|a| {
                r::tonemap::tonemap_aces_fitted(d3(a, 0))
                    .to_array()
                    .to_vec()
            }),
            ulps: 8,
            absolute: 1e-7,
        },
        // shading
        Case {
            module: "shading",
            call: "half_vector_of(a0, a1)",
            arguments: &[Direction, Direction],
            output: Output::Floats(3),
            mirror: |a| out(&m::shading::half_vector_of(v3(a, 0), v3(a, 3)).to_array()),
            reference: Some(|a| {
                r::shading::half_vector_of(d3(a, 0), d3(a, 3))
                    .to_array()
                    .to_vec()
            }),
            ulps: 8,
            absolute: 1e-6,
        },
        Case {
            module: "shading",
            call: "diffuse_share(a0)",
            arguments: &[Colour { scale: 1.5 }],
            output: Output::Floats(3),
            mirror: |a| out(&m::shading::diffuse_share(v3(a, 0)).to_array()),
            reference: Some(|a| r::shading::diffuse_share(d3(a, 0)).to_array().to_vec()),
            ulps: 1,
            absolute: 1e-7,
        },
        Case {
            module: "shading",
            call: "specular_albedo(a0, a1)",
            arguments: &[COLOUR, ENV_BRDF],
            output: Output::Floats(3),
            mirror: |a| out(&m::shading::specular_albedo(v3(a, 0), v2(a, 3)).to_array()),
            reference: Some(|a| {
                r::shading::specular_albedo(d3(a, 0), d2(a, 3))
                    .to_array()
                    .to_vec()
            }),
            ulps: 2,
            absolute: 1e-7,
        },
        Case {
            module: "shading",
            call: "shade_directional(a0, a1, a2, a3, a4, a5, a6, a7)",
            arguments: &[
                Direction,
                Direction,
                Direction,
                LIGHT_COLOUR,
                COLOUR,
                COLOUR,
                ROUGHNESS,
                ENV_BRDF,
            ],
            output: Output::Floats(3),
            mirror: |a| {
                out(&m::shading::shade_directional(
                    v3(a, 0),
                    v3(a, 3),
                    v3(a, 6),
                    v3(a, 9),
                    v3(a, 12),
                    v3(a, 15),
                    f(a, 18),
                    v2(a, 19),
                )
                .to_array())
            },
            reference: Some(|a| {
                r::shading::shade_directional(
                    d3(a, 0),
                    d3(a, 3),
                    d3(a, 6),
                    d3(a, 9),
                    d3(a, 12),
                    d3(a, 15),
                    a[18],
                    d2(a, 19),
                )
                .to_array()
                .to_vec()
            }),
            ulps: 256,
            absolute: 1e-5,
        },
        Case {
            module: "shading",
            call: "shade_directional_mobile(a0, a1, a2, a3, a4, a5, a6)",
            arguments: &[
                Direction,
                Direction,
                Direction,
                LIGHT_COLOUR,
                COLOUR,
                COLOUR,
                ROUGHNESS,
            ],
            output: Output::Floats(3),
            mirror: |a| {
                out(&m::shading::shade_directional_mobile(
                    v3(a, 0),
                    v3(a, 3),
                    v3(a, 6),
                    v3(a, 9),
                    v3(a, 12),
                    v3(a, 15),
                    f(a, 18),
                )
                .to_array())
            },
            reference: Some(|a| {
                r::shading::shade_directional_mobile(
                    d3(a, 0),
                    d3(a, 3),
                    d3(a, 6),
                    d3(a, 9),
                    d3(a, 12),
                    d3(a, 15),
                    a[18],
                )
                .to_array()
                .to_vec()
            }),
            ulps: 256,
            absolute: 1e-5,
        },
        Case {
            module: "shading",
            call: "shade_ibl(a0, a1, a2, a3, a4)",
            arguments: &[
                COLOUR,
                COLOUR,
                HDR_COLOUR,
                HDR_COLOUR,
                Pair {
                    low: 0.0,
                    high: 1.0,
                },
            ],
            output: Output::Floats(3),
            mirror: |a| {
                out(
                    &m::shading::shade_ibl(v3(a, 0), v3(a, 3), v3(a, 6), v3(a, 9), v2(a, 12))
                        .to_array(),
                )
            },
            reference: Some(|a| {
                r::shading::shade_ibl(d3(a, 0), d3(a, 3), d3(a, 6), d3(a, 9), d2(a, 12))
                    .to_array()
                    .to_vec()
            }),
            ulps: 8,
            absolute: 1e-6,
        },
        Case {
            module: "shading",
            call: "shade_ibl_mobile(a0, a1, a2, a3, a4, a5)",
            arguments: &[COLOUR, COLOUR, UNIT, UNIT, HDR_COLOUR, HDR_COLOUR],
            output: Output::Floats(3),
            mirror: |a| {
                out(&m::shading::shade_ibl_mobile(
                    v3(a, 0),
                    v3(a, 3),
                    f(a, 6),
                    f(a, 7),
                    v3(a, 8),
                    v3(a, 11),
                )
                .to_array())
            },
            reference: Some(|a| {
                r::shading::shade_ibl_mobile(d3(a, 0), d3(a, 3), a[6], a[7], d3(a, 8), d3(a, 11))
                    .to_array()
                    .to_vec()
            }),
            ulps: 32,
            absolute: 1e-5,
        },
        Case {
            module: "shading",
            call: "point_light_falloff(a0, a1)",
            arguments: &[
                Scalar {
                    low: 0.0,
                    high: 12.0,
                },
                Scalar {
                    low: 0.5,
                    high: 10.0,
                },
            ],
            output: Output::Floats(1),
            mirror: |a| out(&[m::shading::point_light_falloff(f(a, 0), f(a, 1))]),
            reference: Some(|a| vec![r::shading::point_light_falloff(a[0], a[1])]),
            ulps: 16,
            absolute: 1e-6,
        },
    ]
}

/// The case's input grid: the cartesian product of each argument's samples, with about
/// `target` points in all. Each point is the flattened arguments' bits.
pub fn grid(case: &Case, target: usize) -> Vec<Vec<u32>> {
    // Fixed sets (RGBM texels, constant integers) have their own sizes; the other arguments
    // share what is left of the target.
    let fixed_size = |argument: &Argument| match argument {
        Argument::Rgbm => Some(RGBM_TEXELS.len()),
        Argument::Unsigned { low, high } if low == high => Some(1),
        _ => None,
    };
    let fixed: usize = case.arguments.iter().filter_map(fixed_size).product();
    let free = case
        .arguments
        .iter()
        .filter(|argument| fixed_size(argument).is_none())
        .count();
    let per_argument = if free == 0 {
        1
    } else {
        ((target / fixed) as f64)
            .powf(1.0 / free as f64)
            .ceil()
            .max(2.0) as usize
    };
    let mut points: Vec<Vec<u32>> = vec![Vec::new()];
    for argument in case.arguments {
        let samples = argument.samples(fixed_size(argument).unwrap_or(per_argument));
        points = points
            .iter()
            .flat_map(|point| {
                samples.iter().map(move |sample| {
                    let mut extended = point.clone();
                    extended.extend_from_slice(sample);
                    extended
                })
            })
            .collect();
    }
    points
}

/// A compute shader that evaluates the case at every point of `inputs` (the flattened
/// arguments' bits) into `outputs`; bindings as [`gbuffer_gpu::Gpu::run_compute`] expects.
pub fn compute_harness(case: &Case) -> String {
    let mut wgsl = gbuffer::shading::compose(&[case.module]).expect("the case's module exists");
    let stride: usize = case
        .arguments
        .iter()
        .map(|argument| argument.components())
        .sum();
    wgsl.push_str("\n// ---- test harness ----\n");
    wgsl.push_str("@group(0) @binding(0) var<storage, read> inputs: array<u32>;\n");
    wgsl.push_str("@group(0) @binding(1) var<storage, read_write> outputs: array<u32>;\n");
    wgsl.push_str("@group(0) @binding(2) var<uniform> count: vec4<u32>;\n\n");
    wgsl.push_str("@compute @workgroup_size(64)\nfn harness_main(@builtin(global_invocation_id) id: vec3<u32>) {\n");
    wgsl.push_str("    let index = id.x;\n    if index >= count.x {\n        return;\n    }\n");
    wgsl.push_str(&format!("    let base = index * {stride}u;\n"));
    let mut offset = 0;
    for (position, argument) in case.arguments.iter().enumerate() {
        wgsl.push_str(&format!(
            "    let a{position} = {};\n",
            argument.wgsl(offset)
        ));
        offset += argument.components();
    }
    wgsl.push_str(&format!("    let result = {};\n", case.call));
    match case.output {
        Output::Unsigned => wgsl.push_str("    outputs[index] = result;\n"),
        Output::Floats(1) => wgsl.push_str("    outputs[index] = bitcast<u32>(result);\n"),
        Output::Floats(components) => {
            for component in 0..components {
                wgsl.push_str(&format!("    outputs[index * {components}u + {component}u] = bitcast<u32>(result[{component}]);\n"));
            }
        }
    }
    wgsl.push_str("}\n");
    wgsl
}

/// How far the f32 mirror strays from the f64 reference over the case's grid.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MirrorError {
    /// The largest |mirror - reference|.
    pub max_absolute: f64,
    /// The largest |mirror - reference| over the result's largest component (at least 1e-3:
    /// below that, a product of small inputs would turn f32 rounding into large ratios).
    pub max_relative: f64,
    /// Root mean square of |mirror - reference|.
    pub rms_absolute: f64,
}

/// The mirror's error against the reference over `points`, or None for a case without a
/// reference (integer-exact functions) or an integer result.
pub fn mirror_error(case: &Case, points: &[Vec<u32>]) -> Option<MirrorError> {
    let reference = case.reference?;
    if case.output == Output::Unsigned {
        return None;
    }
    let mut error = MirrorError::default();
    let mut squares = 0.0;
    let mut count = 0usize;
    for point in points {
        // Integer arguments stay integers; float arguments widen exactly.
        let widened: Vec<f64> = widen(case, point);
        let expected = reference(&widened);
        let got = (case.mirror)(point);
        // Relative to the result's largest component: a vector's small components are not
        // held to a tighter standard than its large ones.
        let magnitude = expected
            .iter()
            .fold(1e-3f64, |largest, value| largest.max(value.abs()));
        for (&want, &have) in expected.iter().zip(&got) {
            let have = f64::from(f32::from_bits(have));
            if !want.is_finite() || !have.is_finite() {
                continue;
            }
            let absolute = (have - want).abs();
            error.max_absolute = error.max_absolute.max(absolute);
            error.max_relative = error.max_relative.max(absolute / magnitude);
            squares += absolute * absolute;
            count += 1;
        }
    }
    error.rms_absolute = (squares / count.max(1) as f64).sqrt();
    Some(error)
}

/// A point's arguments as f64: floats widened, unsigned integers converted.
pub fn widen(case: &Case, point: &[u32]) -> Vec<f64> {
    let mut widened = Vec::with_capacity(point.len());
    let mut offset = 0;
    for argument in case.arguments {
        for component in 0..argument.components() {
            let bits = point[offset + component];
            widened.push(match argument {
                Argument::Unsigned { .. } => f64::from(bits),
                _ => f64::from(f32::from_bits(bits)),
            });
        }
        offset += argument.components();
    }
    widened
}

/// Components per result.
pub fn output_components(case: &Case) -> usize {
    match case.output {
        Output::Unsigned => 1,
        Output::Floats(components) => components,
    }
}

/// The distance in ulp between two f32s (0 for equal bits, NaN to NaN, or +0 to -0).
pub fn ulp_distance(a: f32, b: f32) -> u64 {
    if a.is_nan() && b.is_nan() || a == b {
        return 0;
    }
    let ordered = |value: f32| {
        let bits = value.to_bits() as i64;
        if bits < 0x8000_0000 {
            bits
        } else {
            0x8000_0000 - bits
        }
    };
    ordered(a).abs_diff(ordered(b))
}
