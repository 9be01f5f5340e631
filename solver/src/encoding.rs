//! How a quantity becomes bits: the encodings the solver chooses from, each a storage of the
//! layout vocabulary (a whole word of a format, or a bit field), the error each is predicted to
//! make, and its round trip through the layout's own mirror (to measure that error).
//!
//! Errors are measured per kind of quantity (see [`Kind`]): degrees for normals; the largest
//! error in the stored [0, 1] space for colours and scalars; for light, the largest channel
//! error relative to the pixel's brightest channel, or to `hdr_min` when that is larger. The
//! predictions are bounds for exact arithmetic; f32 rounding adds about 1e-7.

use std::fmt;

use gbuffer::glam::Vec3;
use gbuffer_codegen::{
    convert, BitField, Encoding as BitEncoding, FieldType, Format, RgbmRange, ScalarKind, Storage,
};

use crate::description::Precision;
use crate::quantity::{Kind, Quantity};

/// One way to store a quantity: one field of the layout, or for light in halves two (a
/// quantity's components may span fields; each field's conversions are the layout's own).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Encoding {
    /// A 32-bit float (`r32f`): depth.
    Float32,
    /// Light in `r11f_g11f_b10f`: per-channel unsigned floats, 6, 6 and 5-bit mantissas.
    PackedFloat,
    /// Light as a 32-bit rgb9e5 bit field: 9-bit mantissas, one exponent.
    SharedExponent,
    /// Light as a 32-bit RGBM bit field (Karis 2009): rgb times a multiplier of `range`.
    Rgbm {
        /// The largest value stored: the multiplier's range.
        range: f64,
    },
    /// IEEE binary16 per component: a 16-bit bit field for a scalar; for light, a 32-bit
    /// field of red and green beside a 16-bit one of blue.
    Half,
    /// Octahedral normal (Cigolle et al. 2014), a bit field of 2 x `bits`.
    Octahedral {
        /// Bits per coordinate.
        bits: u32,
    },
    /// A colour or scalar in [0, 1], a unorm bit field of `bits` per component.
    Unorm {
        /// Bits per component.
        bits: u32,
    },
    /// A colour in [0, 1] alone in a word of a unorm format (`rgba8`, `rgb10_a2`): the format
    /// converts, no shader code does.
    UnormWord {
        /// The format.
        format: Format,
    },
}

/// The largest value of a binary16 and of the two formats with a 5-bit exponent.
const HALF_MAX: f64 = 65504.0;
const PACKED_FLOAT_MAX: f64 = 64512.0; // b10f: (2 - 2^-5) 2^15
const SHARED_EXPONENT_MAX: f64 = 65408.0; // (511 / 512) 2^16

/// One field of a quantity's storage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Piece {
    /// What the field's name adds to the quantity's: empty for a whole quantity, `rg` or `b`
    /// for light in halves.
    pub suffix: &'static str,
    /// Its storage.
    pub storage: Storage,
    /// Its type.
    pub ty: FieldType,
    /// The quantity's first component it holds.
    pub first_component: usize,
}

impl Encoding {
    /// The fields that store `quantity` this way.
    pub fn pieces(self, quantity: Quantity) -> Vec<Piece> {
        let components = quantity.components();
        let bits = |bits, encoding| Storage::Bits(BitField { bits, encoding });
        let whole = |storage| {
            vec![Piece {
                suffix: "",
                storage,
                ty: FieldType::new(ScalarKind::Float, components),
                first_component: 0,
            }]
        };
        match self {
            Encoding::Float32 => whole(Storage::Word(Format::R32f)),
            Encoding::PackedFloat => whole(Storage::Word(Format::R11fG11fB10f)),
            Encoding::SharedExponent => whole(bits(32, BitEncoding::Rgb9e5)),
            Encoding::Rgbm { range } => whole(bits(
                32,
                BitEncoding::Rgbm(
                    RgbmRange::new(range as f32).expect("the catalogue offers valid ranges only"),
                ),
            )),
            Encoding::Half if components == 3 => vec![
                Piece {
                    suffix: "rg",
                    storage: bits(32, BitEncoding::Half),
                    ty: FieldType::new(ScalarKind::Float, 2),
                    first_component: 0,
                },
                Piece {
                    suffix: "b",
                    storage: bits(16, BitEncoding::Half),
                    ty: FieldType::new(ScalarKind::Float, 1),
                    first_component: 2,
                },
            ],
            Encoding::Half => whole(bits(16, BitEncoding::Half)),
            Encoding::Octahedral { bits: each } => whole(bits(2 * each, BitEncoding::Octahedral)),
            Encoding::Unorm { bits: each } => {
                whole(bits(each * components as u32, BitEncoding::Unorm))
            }
            Encoding::UnormWord { format } => whole(Storage::Word(format)),
        }
    }

    /// Bits of storage: 32 for a whole word, a bit field's width otherwise.
    pub fn bits(self, quantity: Quantity) -> u32 {
        self.pieces(quantity)
            .iter()
            .map(|piece| match piece.storage {
                Storage::Word(_) => 32,
                Storage::Bits(field) => field.bits,
            })
            .sum()
    }

    /// The largest light value it stores without clipping (light encodings only).
    pub fn hdr_max(self) -> f64 {
        match self {
            Encoding::PackedFloat => PACKED_FLOAT_MAX,
            Encoding::SharedExponent => SHARED_EXPONENT_MAX,
            Encoding::Half => HALF_MAX,
            Encoding::Rgbm { range } => range,
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
            // Channel error <= half a code times m range, with m range < brightest + range /
            // 255; and the fixed point's 2^-22 range.
            Encoding::Rgbm { range } => {
                0.5 / 255.0 * (1.0 + range / (255.0 * floor)) + range * 0.5f64.powi(21) / floor
            }
            // Light: half an ulp of a 10-bit mantissa, or half the denormal step 2^-24.
            Encoding::Half => 0.5f64.powi(11).max(0.5f64.powi(25) / floor),
            // Proven in integration-tests/tests/shading_physics.rs and `convert`'s tests: sqrt(18)
            // half-steps of a coordinate.
            Encoding::Octahedral { bits } => (18f64.sqrt() * step(bits)).to_degrees(),
            Encoding::Unorm { bits } => 0.5 * step(bits),
            Encoding::UnormWord { format } => 0.5 * step(format.channels()[0].bits),
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
            // A scalar in [0, 1]: half the ulp of [0.5, 1).
            (Encoding::Half, Kind::Scalar) => 0.5f64.powi(12),
            _ => self.bound(precision),
        }
    }

    /// Every encoding of a quantity the solver considers, before precision: for each family
    /// the widths from 1 bit up to what one word holds. The light encodings clip at the
    /// scene's `hdr_max` (RGBM takes it as its range where the exact encoding can hold it).
    pub fn catalogue(quantity: Quantity, precision: &Precision) -> Vec<Encoding> {
        match quantity.kind() {
            Kind::Hdr => {
                let mut all = vec![
                    Encoding::PackedFloat,
                    Encoding::SharedExponent,
                    Encoding::Half,
                ];
                if RgbmRange::new(precision.hdr_max as f32).is_ok() {
                    all.push(Encoding::Rgbm {
                        range: precision.hdr_max,
                    });
                }
                all
            }
            Kind::Distance => vec![Encoding::Float32],
            Kind::Direction => (1..=16).map(|bits| Encoding::Octahedral { bits }).collect(),
            Kind::Colour => (1..=10)
                .map(|bits| Encoding::Unorm { bits })
                .chain(
                    [Format::Rgba8, Format::Rgb10A2].map(|format| Encoding::UnormWord { format }),
                )
                .collect(),
            Kind::Scalar => (1..=16)
                .map(|bits| Encoding::Unorm { bits })
                .chain([Encoding::Half])
                .collect(),
        }
    }

    /// The CPU round trip of a value (a scalar in `value.x`) through the layout's own mirror:
    /// the same bits the generated WGSL and GLSL store, for measuring the error.
    pub fn round_trip(self, quantity: Quantity, value: Vec3) -> Vec3 {
        let mut back = Vec3::ZERO;
        for piece in self.pieces(quantity) {
            let count = piece.ty.components;
            let mut lanes = [0u32; 4];
            for (index, lane) in lanes.iter_mut().enumerate().take(count) {
                *lane = value[piece.first_component + index].to_bits();
            }
            let decoded = match piece.storage {
                Storage::Word(format) => {
                    format.decode::<f32>(format.encode(lanes.map(f32::from_bits)))
                }
                Storage::Bits(field) => field
                    .decode(field.encode(lanes, count), count)
                    .map(f32::from_bits),
            };
            for (index, component) in decoded.iter().enumerate().take(count) {
                back[piece.first_component + index] = *component;
            }
        }
        back
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
            Encoding::Half => write!(out, "binary16"),
            Encoding::Octahedral { bits } => write!(out, "octahedral, 2 x {bits} bits"),
            Encoding::Unorm { bits } => write!(out, "unorm, {bits} bits"),
            Encoding::UnormWord { format } => write!(out, "unorm in a {format} word"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storage_sizes() {
        assert_eq!(Encoding::Half.bits(Quantity::Roughness), 16);
        assert_eq!(Encoding::Octahedral { bits: 12 }.bits(Quantity::Normal), 24);
        assert_eq!(Encoding::Unorm { bits: 8 }.bits(Quantity::BaseColour), 24);
        assert_eq!(Encoding::Rgbm { range: 8.0 }.bits(Quantity::Light), 32);
        assert_eq!(Encoding::Half.bits(Quantity::Light), 48);
        assert_eq!(Encoding::Half.pieces(Quantity::Light).len(), 2);
        assert_eq!(
            Encoding::UnormWord {
                format: Format::Rgba8
            }
            .pieces(Quantity::BaseColour)[0]
                .storage,
            Storage::Word(Format::Rgba8)
        );
    }

    #[test]
    fn predictions_match_the_textbook_figures() {
        let precision = Precision::default();
        let degrees = |encoding: Encoding| encoding.predicted_error(Quantity::Normal, &precision);
        assert!((degrees(Encoding::Octahedral { bits: 16 }) - 0.00371).abs() < 1e-4);
        assert_eq!(
            Encoding::Unorm { bits: 8 }.predicted_error(Quantity::BaseColour, &precision),
            0.5 / 255.0
        );
        assert!(Encoding::Unorm { bits: 8 }.meets(Quantity::BaseColour, &precision));
        assert!(!Encoding::Unorm { bits: 7 }.meets(Quantity::BaseColour, &precision));
        // r11f_g11f_b10f: 1/64 relative meets 2%.
        assert!(Encoding::PackedFloat.meets(Quantity::Light, &precision));
    }
}
