//! The Rust mirror of `mobile_half.wgsl`: the mobile forms in half precision. Every operation
//! rounds to IEEE binary16, as an f16 ALU does (an f32 operation on two f16 values, then
//! rounded to f16, is the correctly rounded f16 result: f32 carries more than twice f16's
//! precision). Names and clamps are the WGSL's.

use std::ops::{Add, Div, Mul, Neg, Sub};

use half::f16;

/// A binary16 value; arithmetic rounds each result to binary16.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Half(f16);

impl Half {
    /// +0.
    pub const ZERO: Half = Half(f16::ZERO);
    /// 1.
    pub const ONE: Half = Half(f16::ONE);

    /// Rounds an f32 to the nearest binary16 (past 65504: infinity, as a conversion does).
    pub fn new(value: f32) -> Self {
        Half(f16::from_f32(value))
    }

    /// The value as an f32 (exact).
    pub fn to_f32(self) -> f32 {
        self.0.to_f32()
    }

    /// Whether the value is neither infinite nor NaN.
    pub fn is_finite(self) -> bool {
        self.0.is_finite()
    }

    /// The smaller of two values, as WGSL's `min`.
    pub fn min(self, other: Half) -> Half {
        if other.0 < self.0 {
            other
        } else {
            self
        }
    }

    /// The larger of two values, as WGSL's `max`.
    pub fn max(self, other: Half) -> Half {
        if other.0 > self.0 {
            other
        } else {
            self
        }
    }

    /// `min(max(self, low), high)`, as WGSL's `clamp`.
    pub fn clamp(self, low: Half, high: Half) -> Half {
        self.max(low).min(high)
    }

    /// 2 to the power of the value, rounded to binary16.
    pub fn exp2(self) -> Half {
        Half::new(self.to_f32().exp2())
    }
}

macro_rules! rounded_operator {
    ($trait:ident, $method:ident, $op:tt) => {
        impl $trait for Half {
            type Output = Half;
            fn $method(self, other: Half) -> Half {
                Half::new(self.to_f32() $op other.to_f32())
            }
        }
    };
}
rounded_operator!(Add, add, +);
rounded_operator!(Sub, sub, -);
rounded_operator!(Mul, mul, *);
rounded_operator!(Div, div, /);

impl Neg for Half {
    type Output = Half;
    fn neg(self) -> Half {
        Half(-self.0)
    }
}

/// A `vec3<f16>`.
pub type Half3 = [Half; 3];

fn h(value: f32) -> Half {
    Half::new(value)
}

fn dot(a: Half3, b: Half3) -> Half {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn map(a: Half3, f: impl Fn(Half) -> Half) -> Half3 {
    a.map(f)
}

fn zip(a: Half3, b: Half3, f: impl Fn(Half, Half) -> Half) -> Half3 {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2])]
}

/// The smallest roughness the half-precision forms are fed (see mobile_half.wgsl).
pub fn min_roughness_half() -> Half {
    h(0.065)
}

/// The smallest n.v the half-precision forms are fed.
pub fn min_n_dot_v_half() -> Half {
    h(0.0001)
}

/// The largest radiance the half-precision composites return: f16's largest finite value.
pub fn max_radiance_half() -> Half {
    h(65504.0)
}

/// env_brdf_approx in f16.
pub fn env_brdf_approx_half(specular_colour: Half3, roughness: Half, n_dot_v: Half) -> Half3 {
    let c0 = [h(-1.0), h(-0.0275), h(-0.572), h(0.022)];
    let c1 = [h(1.0), h(0.0425), h(1.04), h(-0.04)];
    let r: Vec<Half> = (0..4)
        .map(|index| roughness * c0[index] + c1[index])
        .collect();
    let a004 = (r[0] * r[0]).min((h(-9.28) * n_dot_v).exp2()) * r[0] + r[1];
    let scale = h(-1.04) * a004 + r[2];
    let bias = h(1.04) * a004 + r[3];
    map(specular_colour, |channel| channel * scale + bias)
}

/// env_brdf_approx_nonmetal in f16.
pub fn env_brdf_approx_nonmetal_half(roughness: Half, n_dot_v: Half) -> Half {
    let r = [
        roughness * h(-1.0) + h(1.0),
        roughness * h(-0.0275) + h(0.0425),
    ];
    (r[0] * r[0]).min((h(-9.28) * n_dot_v).exp2()) * r[0] + r[1]
}

/// d_approx in f16, roughness clamped to `min_roughness_half`.
pub fn d_approx_half(roughness: Half, r_dot_l: Half) -> Half {
    let clamped_roughness = roughness.max(min_roughness_half());
    let alpha = clamped_roughness * clamped_roughness;
    let inverse_alpha_squared = Half::ONE / (alpha * alpha);
    let c = h(0.721_347_5) * inverse_alpha_squared + h(0.396_741_13);
    inverse_alpha_squared * (c * r_dot_l - c).exp2()
}

/// shade_directional_mobile in f16, saturating at `max_radiance_half`.
#[allow(clippy::too_many_arguments)]
pub fn shade_directional_mobile_half(
    normal: Half3,
    view: Half3,
    light_direction: Half3,
    light_colour: Half3,
    diffuse_colour: Half3,
    f0: Half3,
    roughness: Half,
) -> Half3 {
    let n_dot_v = dot(normal, view).max(min_n_dot_v_half());
    let n_dot_l = dot(normal, light_direction).clamp(Half::ZERO, Half::ONE);
    let twice_n_dot_v = h(2.0) * dot(normal, view);
    let reflected = zip(
        map(normal, |channel| twice_n_dot_v * channel),
        view,
        |a, b| a - b,
    );
    let r_dot_l = dot(reflected, light_direction).clamp(Half::ZERO, Half::ONE);
    let clamped_roughness = roughness.max(min_roughness_half());
    let specular_colour =
        env_brdf_approx_half(f0, clamped_roughness, n_dot_v).map(|channel| channel.max(Half::ZERO));
    let lobe = d_approx_half(clamped_roughness, r_dot_l);
    let diffuse = zip(diffuse_colour, specular_colour, |diffuse, specular| {
        diffuse * (Half::ONE - specular).clamp(Half::ZERO, Half::ONE)
    });
    let inverse_pi_n_dot_l = h(std::f32::consts::FRAC_1_PI) * n_dot_l;
    let scale = map(light_colour, |channel| inverse_pi_n_dot_l * channel);
    let maximum = max_radiance_half();
    let specular = zip(
        specular_colour,
        map(scale, |channel| (lobe * channel).min(maximum)),
        |a, b| a * b,
    );
    zip(zip(diffuse, scale, |a, b| a * b), specular, |a, b| {
        (a + b).min(maximum)
    })
}

/// Converts a vector to half precision.
pub fn half3(value: glam::Vec3) -> Half3 {
    value.to_array().map(Half::new)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_rounds_to_half() {
        assert_eq!((h(1.0) + h(0.0001)).to_f32(), 1.0); // below half an f16 ulp of 1
        assert_eq!((h(60000.0) * h(2.0)).to_f32(), f32::INFINITY);
        // Roughness 0 is clamped to 0.065: 1 / 0.065^4 is about 56020, finite in f16.
        let peak = d_approx_half(Half::ZERO, Half::ONE).to_f32();
        assert!((55_000.0..=65_504.0).contains(&peak), "{peak}");
        // Without the clamp the lobe overflows f16 at the f32 form's minimum roughness.
        let alpha = h(0.045) * h(0.045);
        assert!(!(Half::ONE / (alpha * alpha)).is_finite());
    }
}
