//! The inputs harnesses are fed: edge sets with the hard cases of every conversion, a seeded
//! generator that mixes them with random bits and values in the formats' ranges, and
//! low-discrepancy spreads (Halton points, Fibonacci directions) over shading domains.

use gbuffer_core::ScalarKind;
use glam::{DVec3, Vec3};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// Floats every conversion must get right: zeros, one, values next to unorm rounding
/// midpoints, f32 and f16 denormals, each float format's largest finite value and what lies
/// above it, half-precision ties, negatives, NaN and both infinities.
pub fn float_edges() -> Vec<f32> {
    let mut edges = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        2.0,
        f32::MIN_POSITIVE,
        f32::from_bits(1),           // smallest f32 denormal
        f32::from_bits(0x007f_ffff), // largest f32 denormal
        -f32::from_bits(1),
        5.960_464_5e-8, // smallest f16 denormal
        2.980_232_2e-8, // half of it: a tie
        6.097_555e-5,   // largest f16 denormal
        6.103_515_6e-5, // smallest f16 normal
        9.536_743e-7,   // smallest r11f denormal, 2^-20
        1.907_348_6e-6, // smallest b10f denormal, 2^-19
        65504.0,        // f16 largest finite
        65519.0,
        65520.0, // rounds past the f16 maximum
        65024.0, // r11f and g11f largest finite
        64512.0, // b10f largest finite
        65536.0,
        1.0e6,
        f32::MAX,
        -65504.0,
        -1.0e6,
        f32::MIN,
        1.0 + 1.0 / 2048.0, // f16 tie between 1 and its successor: to even
        1.0 + 3.0 / 2048.0, // f16 tie: rounds up to even
        1.0 + 1.0 / 128.0,  // r11f tie
        1.0 + 1.0 / 64.0,   // b10f tie
        f32::NAN,
        -f32::NAN,
        f32::from_bits(0x7fc0_0001), // a NaN with a payload
        f32::INFINITY,
        f32::NEG_INFINITY,
    ];
    // Ties of the small floats' denormals, (k + 0.5) steps, even and odd k: the exact
    // conversions must round them to even on every translator and driver.
    for (step, last) in [(-24, 1023), (-20, 63), (-19, 31)] {
        for k in [0u32, 1, 2, 3, last / 2, last / 2 + 1, last - 1, last] {
            edges.push((k as f32 + 0.5) * 2f32.powi(step));
        }
    }
    // Unorm rounding midpoints (k + 0.5) / (2^n - 1) and their f32 neighbours.
    for bits in [2u32, 8, 10, 16] {
        let max = (1u32 << bits) - 1;
        for code in [0, 1, max / 3, max / 2, max - 2, max - 1] {
            let midpoint = ((f64::from(code) + 0.5) / f64::from(max)) as f32;
            edges.extend([
                midpoint,
                f32::from_bits(midpoint.to_bits() - 1),
                f32::from_bits(midpoint.to_bits() + 1),
            ]);
        }
    }
    edges
}

/// Unsigned integers at the limits of 2, 8, 10, 16 and 32 bits.
pub fn uint_edges() -> Vec<u32> {
    let mut edges = vec![0, 1, u32::MAX, u32::MAX - 1];
    for bits in [2, 8, 10, 16] {
        let max = (1u32 << bits) - 1;
        edges.extend([max - 1, max, max + 1]);
    }
    edges
}

/// Signed integers at the limits of 8, 16 and 32 bits.
pub fn sint_edges() -> Vec<i32> {
    let mut edges = vec![0, 1, -1, i32::MIN, i32::MAX];
    for bits in [8, 16] {
        let highest = (1i32 << (bits - 1)) - 1;
        edges.extend([
            highest - 1,
            highest,
            highest + 1,
            -highest,
            -highest - 1,
            -highest - 2,
        ]);
    }
    edges
}

/// A seeded source of test values: a quarter edge cases, the rest random bits, values in
/// 0..1 and values across the half-float range.
pub struct Values {
    rng: SmallRng,
    float_edges: Vec<f32>,
    uint_edges: Vec<u32>,
    sint_edges: Vec<i32>,
}

impl Values {
    /// A generator whose sequence `seed` fixes.
    pub fn new(seed: u64) -> Self {
        Values {
            rng: SmallRng::seed_from_u64(seed),
            float_edges: float_edges(),
            uint_edges: uint_edges(),
            sint_edges: sint_edges(),
        }
    }

    /// The next float: an edge case, random bits, or a value in [0, 1), [-1, 2), within
    /// ±70000 or among the subnormals, chosen at random.
    pub fn float(&mut self) -> f32 {
        match self.rng.random_range(0..8) {
            0 | 1 => self.float_edges[self.rng.random_range(0..self.float_edges.len())],
            2 => f32::from_bits(self.rng.random()),
            3 | 4 => self.rng.random::<f32>(),
            5 => self.rng.random_range(-1.0..2.0),
            6 => self.rng.random_range(-70000.0..70000.0),
            _ => {
                self.rng.random::<f32>()
                    * f32::from_bits(self.rng.random_range(0x3380_0000..0x3880_0000))
            } // tiny: denormal ranges
        }
    }

    /// The next unsigned integer: an edge case, a value below 70000 or random bits.
    pub fn uint(&mut self) -> u32 {
        match self.rng.random_range(0..4) {
            0 => self.uint_edges[self.rng.random_range(0..self.uint_edges.len())],
            1 => self.rng.random_range(0..70000),
            _ => self.rng.random(),
        }
    }

    /// The next signed integer: an edge case, a value within ±70000 or random bits.
    pub fn sint(&mut self) -> i32 {
        match self.rng.random_range(0..4) {
            0 => self.sint_edges[self.rng.random_range(0..self.sint_edges.len())],
            1 => self.rng.random_range(-70000..70000),
            _ => self.rng.random(),
        }
    }

    /// A value of the given kind, as the bits a shader would read with `bitcast`.
    pub fn bits(&mut self, kind: ScalarKind) -> u32 {
        match kind {
            ScalarKind::Float => self.float().to_bits(),
            ScalarKind::Uint => self.uint(),
            ScalarKind::Sint => self.sint() as u32,
            // A shader's `bool` from bits is `bits != 0`: mostly 0 and 1, sometimes others.
            ScalarKind::Bool => match self.rng.random_range(0..4) {
                0 => self.rng.random(),
                pick => pick & 1,
            },
        }
    }
}

/// Point `index` of the Halton sequence in `base`: a low-discrepancy spread over [0, 1).
pub fn halton(mut index: u32, base: u32) -> f64 {
    let (mut value, mut weight) = (0.0, 1.0);
    while index > 0 {
        weight /= f64::from(base);
        value += weight * f64::from(index % base);
        index /= base;
    }
    value
}

/// `count` unit vectors spread evenly over the sphere.
pub fn fibonacci_sphere(count: usize) -> Vec<Vec3> {
    let golden_angle = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|index| {
            let z = 1.0 - 2.0 * (index as f64 + 0.5) / count as f64;
            let radius = (1.0 - z * z).sqrt();
            let angle = golden_angle * index as f64;
            DVec3::new(radius * angle.cos(), radius * angle.sin(), z).as_vec3()
        })
        .collect()
}
