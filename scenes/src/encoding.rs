//! How a quantity becomes bits: the encodings the solver chooses from, what storage each takes,
//! the error each is predicted to make, and its round trip on the CPU (to measure that error).
//!
//! Errors are measured per kind of quantity (see [`Kind`]): degrees for normals; the largest
//! error in the stored [0, 1] space for colours (pseudo-gamma) and scalars; for light, the
//! largest channel error relative to the pixel's brightest channel, or to `hdr_min` when that
//! is larger. The predictions are bounds for exact arithmetic; f32 rounding adds about 1e-7.

use std::fmt;

use gbuffer::glam::{Vec2, Vec3};
use gbuffer::shading::mirror as m;
use gbuffer::shading::mirror::rgb9e5;
use gbuffer_codegen::convert;
use gbuffer_codegen::Format;

use crate::description::Precision;
use crate::quantity::{Kind, Quantity};

/// One way to store a quantity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Encoding {
    /// A 32-bit float (`r32f`): depth.
    Float32,
    /// Light in `r11f_g11f_b10f`: per-channel unsigned floats, 6, 6 and 5-bit mantissas.
    PackedFloat,
    /// Light as shared-exponent rgb9e5 in an `r32ui` word: 9-bit mantissas, one exponent.
    SharedExponent,
    /// Light as RGBM (Karis 2009) in 4 x 8 bits: rgb times a multiplier of `range`.
    Rgbm {
        /// The largest value stored: the multiplier's range.
        range: f64,
    },
    /// Light scaled by 1 / range into `bits`-bit unorm channels (the seeds' rgb10_a2).
    ScaledUnorm {
        /// Bits per channel.
        bits: u32,
        /// The value stored as 1.
        range: f64,
    },
    /// IEEE binary16 per channel, in `rg16f` channels (GPU Pro 7 Listings 2.7 and 2.8).
    Half,
    /// A normal's components mapped to [0, 1], `bits` each (the seeds' rgba8 normals).
    NormalUnorm {
        /// Bits per component.
        bits: u32,
    },
    /// Octahedral normal (Cigolle et al. 2014), 2 x `bits`.
    Octahedral {
        /// Bits per coordinate.
        bits: u32,
    },
    /// A colour's square root (pseudo-gamma, GPU Pro 7 Listing 2.4), `bits` per channel.
    PseudoGamma {
        /// Bits per channel.
        bits: u32,
    },
    /// A scalar in [0, 1], `bits` bits.
    Unorm {
        /// Bits of the code.
        bits: u32,
    },
}

/// Storage an encoding needs: the pieces the solver places in words.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Part {
    /// A whole word of a format.
    Word(Format),
    /// Unsigned normalized components of these widths, in one word.
    Unorm(Vec<u32>),
    /// One binary16 channel of an `rg16f` word.
    Half,
}

/// The largest value of a binary16 and of the two formats with a 5-bit exponent.
const HALF_MAX: f64 = 65504.0;
const PACKED_FLOAT_MAX: f64 = 64512.0; // b10f: (2 - 2^-5) 2^15
const SHARED_EXPONENT_MAX: f64 = 65408.0; // (511 / 512) 2^16

impl Encoding {
    /// The pieces of storage it takes.
    pub fn parts(self, quantity: Quantity) -> Vec<Part> {
        match self {
            Encoding::Float32 => vec![Part::Word(Format::R32f)],
            Encoding::PackedFloat => vec![Part::Word(Format::R11fG11fB10f)],
            Encoding::SharedExponent => vec![Part::Word(Format::R32ui)],
            Encoding::Rgbm { .. } => vec![Part::Unorm(vec![8; 4])],
            Encoding::Half => vec![Part::Half; quantity.components()],
            Encoding::ScaledUnorm { bits, .. }
            | Encoding::NormalUnorm { bits }
            | Encoding::PseudoGamma { bits } => vec![Part::Unorm(vec![bits; 3])],
            Encoding::Octahedral { bits } => vec![Part::Unorm(vec![bits; 2])],
            Encoding::Unorm { bits } => vec![Part::Unorm(vec![bits])],
        }
    }

    /// Bits of storage.
    pub fn bits(self, quantity: Quantity) -> u32 {
        self.parts(quantity)
            .iter()
            .map(|part| match part {
                Part::Word(_) => 32,
                Part::Unorm(widths) => widths.iter().sum(),
                Part::Half => 16,
            })
            .sum()
    }

    /// The largest light value it stores without clipping (light encodings only).
    pub fn hdr_max(self) -> f64 {
        match self {
            Encoding::PackedFloat => PACKED_FLOAT_MAX,
            Encoding::SharedExponent => SHARED_EXPONENT_MAX,
            Encoding::Half => HALF_MAX,
            Encoding::Rgbm { range } | Encoding::ScaledUnorm { range, .. } => range,
            _ => f64::INFINITY,
        }
    }

    /// The bound on its error for light, normals, colours and unorm scalars.
    fn bound(self, precision: &Precision) -> f64 {
        let step = |bits: u32| 1.0 / f64::from(convert::max_code(bits));
        let floor = precision.hdr_min;
        match self {
            // A 24-bit significand rounded to nearest.
            Encoding::Float32 => 0.5f64.powi(24),
            // Half an ulp of the 5-bit mantissa, or half the b10f denormal step 2^-19.
            Encoding::PackedFloat => 0.5f64.powi(6).max(0.5f64.powi(20) / floor),
            // Half a step of the brightest channel's mantissa (>= 256 of 512), or half the
            // smallest step 2^-24.
            Encoding::SharedExponent => 0.5f64.powi(9).max(0.5f64.powi(25) / floor),
            // Channel error <= half a code times m range, with m range < brightest + range / 255.
            Encoding::Rgbm { range } => 0.5 / 255.0 * (1.0 + range / (255.0 * floor)),
            // An absolute half step of range / (2^bits - 1), against the floor.
            Encoding::ScaledUnorm { bits, range } => 0.5 * range * step(bits) / floor,
            // Light: half an ulp of a 10-bit mantissa, or half the denormal step 2^-24; a
            // scalar in [0, 1]: half the ulp of [0.5, 1).
            Encoding::Half => 0.5f64.powi(11).max(0.5f64.powi(25) / floor),
            // Each component off by at most one step e (half a code of [0, 1], times 2):
            // the vector moves by at most sqrt(3) e.
            Encoding::NormalUnorm { bits } => {
                (3f64.sqrt() * step(bits)).min(1.0).asin().to_degrees()
            }
            // Proven in tests/tests/shading_physics.rs: sqrt(18) e.
            Encoding::Octahedral { bits } => (18f64.sqrt() * step(bits)).to_degrees(),
            Encoding::PseudoGamma { bits } | Encoding::Unorm { bits } => 0.5 * step(bits),
        }
    }

    /// The error a quantity of `kind` may make under `precision`, in the same unit.
    pub fn allowed_error(kind: Kind, precision: &Precision) -> f64 {
        let half_step = |steps: u32| 0.5 / f64::from(steps.max(2) - 1);
        match kind {
            Kind::Hdr => precision.hdr_relative,
            Kind::Distance => f64::INFINITY,
            Kind::Direction => precision.normal_degrees,
            Kind::Colour => half_step(precision.colour_steps),
            Kind::Scalar => half_step(precision.material_steps),
        }
    }

    /// Whether it meets the scene's precision for `quantity`.
    pub fn meets(self, quantity: Quantity, precision: &Precision) -> bool {
        let error = self.predicted_error(quantity, precision);
        error <= Encoding::allowed_error(quantity.kind(), precision)
            && (quantity.kind() != Kind::Hdr || self.hdr_max() >= precision.hdr_max)
    }

    /// The bound on its error storing `quantity`, in the unit of the quantity's kind (see the
    /// module's doc).
    pub fn predicted_error(self, quantity: Quantity, precision: &Precision) -> f64 {
        match (self, quantity.kind()) {
            (Encoding::Half, Kind::Scalar) => 0.5f64.powi(12),
            _ => self.bound(precision),
        }
    }

    /// Every encoding of a quantity the solver considers, before precision: for each family
    /// the widths from 1 bit up to what one word holds. The light encodings clip at the
    /// scene's `hdr_max`.
    pub fn catalogue(quantity: Quantity, precision: &Precision) -> Vec<Encoding> {
        let range = precision.hdr_max;
        match quantity.kind() {
            Kind::Hdr => {
                let mut all = vec![
                    Encoding::PackedFloat,
                    Encoding::SharedExponent,
                    Encoding::Rgbm { range },
                    Encoding::Half,
                ];
                all.extend((1..=10).map(|bits| Encoding::ScaledUnorm { bits, range }));
                all
            }
            Kind::Distance => vec![Encoding::Float32],
            Kind::Direction => (1..=10)
                .map(|bits| Encoding::NormalUnorm { bits })
                .chain((2..=16).map(|bits| Encoding::Octahedral { bits }))
                .collect(),
            Kind::Colour => (1..=10)
                .map(|bits| Encoding::PseudoGamma { bits })
                .collect(),
            Kind::Scalar => (1..=16)
                .map(|bits| Encoding::Unorm { bits })
                .chain([Encoding::Half])
                .collect(),
        }
    }

    /// The shading library modules its WGSL calls.
    pub fn modules(self) -> &'static [&'static str] {
        match self {
            Encoding::SharedExponent | Encoding::Rgbm { .. } | Encoding::ScaledUnorm { .. } => {
                &["hdr"]
            }
            Encoding::NormalUnorm { .. } | Encoding::Octahedral { .. } => &["normals"],
            Encoding::PseudoGamma { .. } => &["colour"],
            _ => &[],
        }
    }

    /// WGSL that turns `value` (of the quantity's type) into what is stored: a `vecN<f32>`
    /// of unorm components, the value itself, or a whole word.
    pub fn encode_wgsl(self, value: &str) -> String {
        match self {
            Encoding::Float32 | Encoding::PackedFloat | Encoding::Half | Encoding::Unorm { .. } => {
                value.to_string()
            }
            Encoding::SharedExponent => format!("rgb9e5_encode({value})"),
            Encoding::Rgbm { range } => format!("rgbm_encode({value}, {})", wgsl_float(range)),
            Encoding::ScaledUnorm { range, .. } => {
                format!("scale_hdr_to_unit({value}, {})", wgsl_float(range))
            }
            Encoding::NormalUnorm { .. } => format!("normal_to_unorm({value})"),
            Encoding::Octahedral { .. } => {
                format!("octahedral_encode({value}) * 0.5 + vec2<f32>(0.5)")
            }
            Encoding::PseudoGamma { .. } => format!("linear_to_pseudo_gamma({value})"),
        }
    }

    /// Scalar components of what `encode_wgsl` makes of `quantity`, for the pieces that sit in
    /// channels or bit fields.
    pub fn stored_components(self, quantity: Quantity) -> usize {
        match self {
            Encoding::Rgbm { .. } => 4,
            Encoding::Octahedral { .. } => 2,
            Encoding::Unorm { .. } | Encoding::Float32 => 1,
            _ => quantity.components(),
        }
    }

    /// WGSL that turns what was stored (`stored`, as `encode_wgsl` made it) back into the
    /// quantity.
    pub fn decode_wgsl(self, stored: &str) -> String {
        match self {
            Encoding::Float32 | Encoding::PackedFloat | Encoding::Half | Encoding::Unorm { .. } => {
                stored.to_string()
            }
            Encoding::SharedExponent => format!("rgb9e5_decode({stored})"),
            Encoding::Rgbm { range } => format!("rgbm_decode({stored}, {})", wgsl_float(range)),
            Encoding::ScaledUnorm { range, .. } => {
                format!("scale_unit_to_hdr({stored}, {})", wgsl_float(range))
            }
            Encoding::NormalUnorm { .. } => format!("unorm_to_normal({stored})"),
            Encoding::Octahedral { .. } => {
                format!("octahedral_decode({stored} * 2.0 - vec2<f32>(1.0))")
            }
            Encoding::PseudoGamma { .. } => format!("pseudo_gamma_to_linear({stored})"),
        }
    }

    /// The CPU round trip of a value (a scalar in `value.x`), as the generated WGSL does it
    /// with the layout's exact conversions: for measuring the error.
    pub fn round_trip(self, value: Vec3) -> Vec3 {
        let unorm = |value: f32, bits: u32| {
            convert::f32_from_unorm(convert::unorm_from_f32(value, bits), bits)
        };
        let unorm3 = |value: Vec3, bits: u32| {
            Vec3::new(
                unorm(value.x, bits),
                unorm(value.y, bits),
                unorm(value.z, bits),
            )
        };
        let half = |value: f32| convert::f32_from_half(convert::half_from_f32(value));
        match self {
            Encoding::Float32 => value,
            Encoding::PackedFloat => {
                let format = Format::R11fG11fB10f;
                let decoded: [f32; 4] =
                    format.decode(format.encode([value.x, value.y, value.z, 0.0]));
                Vec3::new(decoded[0], decoded[1], decoded[2])
            }
            Encoding::SharedExponent => rgb9e5::rgb9e5_decode(rgb9e5::rgb9e5_encode(value)),
            Encoding::Rgbm { range } => {
                let encoded = m::hdr::rgbm_encode(value, range as f32);
                let stored = unorm3(encoded.truncate(), 8).extend(unorm(encoded.w, 8));
                m::hdr::rgbm_decode(stored, range as f32)
            }
            Encoding::ScaledUnorm { bits, range } => m::hdr::scale_unit_to_hdr(
                unorm3(m::hdr::scale_hdr_to_unit(value, range as f32), bits),
                range as f32,
            ),
            Encoding::Half => Vec3::new(half(value.x), half(value.y), half(value.z)),
            Encoding::NormalUnorm { bits } => {
                m::normals::unorm_to_normal(unorm3(m::normals::normal_to_unorm(value), bits))
            }
            Encoding::Octahedral { bits } => {
                let encoded = m::normals::octahedral_encode(value) * 0.5 + Vec2::splat(0.5);
                let stored = Vec2::new(unorm(encoded.x, bits), unorm(encoded.y, bits));
                m::normals::octahedral_decode(stored * 2.0 - Vec2::ONE)
            }
            Encoding::PseudoGamma { bits } => m::colour::pseudo_gamma_to_linear(unorm3(
                m::colour::linear_to_pseudo_gamma(value),
                bits,
            )),
            Encoding::Unorm { bits } => Vec3::new(unorm(value.x, bits), 0.0, 0.0),
        }
    }
}

impl fmt::Display for Encoding {
    /// A short description for reports: "octahedral, 2 x 12 bits".
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Encoding::Float32 => write!(out, "32-bit float"),
            Encoding::PackedFloat => write!(out, "r11f_g11f_b10f floats"),
            Encoding::SharedExponent => write!(out, "rgb9e5 shared exponent"),
            Encoding::Rgbm { range } => write!(out, "RGBM, 4 x 8 bits, range {range}"),
            Encoding::ScaledUnorm { bits, range } => {
                write!(out, "scaled by 1/{range}, 3 x {bits}-bit unorm")
            }
            Encoding::Half => write!(out, "binary16"),
            Encoding::NormalUnorm { bits } => write!(out, "xyz to unorm, 3 x {bits} bits"),
            Encoding::Octahedral { bits } => write!(out, "octahedral, 2 x {bits} bits"),
            Encoding::PseudoGamma { bits } => write!(out, "pseudo-gamma, 3 x {bits} bits"),
            Encoding::Unorm { bits } => write!(out, "unorm, {bits} bits"),
        }
    }
}

/// A WGSL float literal that round-trips.
fn wgsl_float(value: f64) -> String {
    format!("{:?}", value as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storage_sizes() {
        assert_eq!(Encoding::Half.bits(Quantity::Light), 48);
        assert_eq!(Encoding::Half.bits(Quantity::Roughness), 16);
        assert_eq!(Encoding::Octahedral { bits: 12 }.bits(Quantity::Normal), 24);
        assert_eq!(
            Encoding::Rgbm { range: 8.0 }.parts(Quantity::Light),
            [Part::Unorm(vec![8; 4])]
        );
    }

    #[test]
    fn predictions_match_the_textbook_figures() {
        let precision = Precision::default();
        let degrees = |encoding: Encoding| encoding.predicted_error(Quantity::Normal, &precision);
        // 8-bit xyz: asin(sqrt(3) / 255) = 0.389 degrees.
        assert!((degrees(Encoding::NormalUnorm { bits: 8 }) - 0.3892).abs() < 1e-3);
        assert!((degrees(Encoding::Octahedral { bits: 16 }) - 0.00371).abs() < 1e-4);
        assert_eq!(
            Encoding::PseudoGamma { bits: 8 }.predicted_error(Quantity::BaseColour, &precision),
            0.5 / 255.0
        );
        assert!(Encoding::PseudoGamma { bits: 8 }.meets(Quantity::BaseColour, &precision));
        assert!(!Encoding::PseudoGamma { bits: 7 }.meets(Quantity::BaseColour, &precision));
        // r11f_g11f_b10f: 1/64 relative meets 2%; a 10-bit scale of 8 does not at 1/64.
        assert!(Encoding::PackedFloat.meets(Quantity::Light, &precision));
        let scaled = Encoding::ScaledUnorm {
            bits: 10,
            range: 8.0,
        };
        assert!(!scaled.meets(Quantity::Light, &precision));
    }
}
