//! How a quantity becomes bits: the representations the solver chooses from, each a storage of the
//! layout vocabulary (a whole word of a format, or a bit field), the error each is predicted to
//! make, and its round trip through the layout's own mirror (to measure that error).
//!
//! Errors are measured per kind of quantity (see [`Kind`]): degrees for normals; the largest
//! error in the stored [0, 1] space for colours and scalars; for light, the largest channel
//! error relative to the pixel's brightest channel, or to `hdr_min` when that is larger. The
//! predictions are bounds for exact arithmetic; f32 rounding adds about 1e-7.

use std::fmt;

use gbuffer_core::codecs::{octahedral, rgb9e5, small_float, unorm};
use gbuffer_core::{
    BitField, Encoding, FieldType, Format, LightStorage, RgbmRange, ScalarKind, Storage,
};
use glam::Vec3;

use crate::description::Precision;
use crate::quantity::{Kind, Quantity};

/// One way to store a quantity: one field of the layout, or for light in halves two (a
/// quantity's components may span fields; each field's conversions are the layout's own).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Representation {
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
    /// Light as a bit field of any codec that offers light storage
    /// ([`Codec::light_storage`](gbuffer_core::Codec#structfield.light_storage)), `each` bits per
    /// component: a codec added to the list is in the catalogue by itself.
    Light {
        /// The codec.
        encoding: Encoding,
        /// Bits per component.
        each: u32,
    },
}

/// What `encoding` guarantees for light at `each` bits per component.
fn light_storage(encoding: Encoding, each: u32, floor: f64) -> LightStorage {
    (encoding.codec().light_storage)(floor)
        .into_iter()
        .find(|storage| storage.each == each)
        .expect("the catalogue offers the widths the codec offers")
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

impl Representation {
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
            Representation::Float32 => whole(Storage::Word(Format::R32f)),
            Representation::PackedFloat => whole(Storage::Word(Format::R11fG11fB10f)),
            Representation::SharedExponent => whole(bits(32, Encoding::Rgb9e5)),
            Representation::Rgbm { range } => whole(bits(
                32,
                Encoding::Rgbm(
                    RgbmRange::new(range as f32).expect("the catalogue offers valid ranges only"),
                ),
            )),
            Representation::Half if components == 3 => vec![
                Piece {
                    suffix: "rg",
                    storage: bits(32, Encoding::Half),
                    ty: FieldType::new(ScalarKind::Float, 2),
                    first_component: 0,
                },
                Piece {
                    suffix: "b",
                    storage: bits(16, Encoding::Half),
                    ty: FieldType::new(ScalarKind::Float, 1),
                    first_component: 2,
                },
            ],
            Representation::Half => whole(bits(16, Encoding::Half)),
            Representation::Octahedral { bits: each } => {
                whole(bits(2 * each, Encoding::Octahedral))
            }
            Representation::Unorm { bits: each } => {
                whole(bits(each * components as u32, Encoding::Unorm))
            }
            Representation::UnormWord { format } => whole(Storage::Word(format)),
            Representation::Light { encoding, each } => whole(bits(3 * each, encoding)),
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

    /// The largest light value it stores without clipping (light representations only).
    pub fn hdr_max(self) -> f64 {
        match self {
            Representation::PackedFloat => PACKED_FLOAT_MAX,
            Representation::SharedExponent => SHARED_EXPONENT_MAX,
            Representation::Half => HALF_MAX,
            Representation::Rgbm { range } => range,
            Representation::Light { encoding, each } => light_storage(encoding, each, 1.0).largest,
            _ => f64::INFINITY,
        }
    }

    /// The bound on its error for light, normals, colours and unorm scalars.
    fn bound(self, precision: &Precision) -> f64 {
        let floor = precision.hdr_min;
        match self {
            // A 24-bit significand rounded to nearest.
            Representation::Float32 => 0.5f64.powi(24),
            // Half an ulp of the 5-bit mantissa, or half the b10f denormal step 2^-19.
            Representation::PackedFloat => {
                small_float::max_relative_error(5).max(0.5f64.powi(20) / floor)
            }
            // Half a step of the brightest channel's mantissa (>= 256 of 512), or half the
            // smallest step 2^-24.
            Representation::SharedExponent => {
                rgb9e5::MAX_RELATIVE_ERROR.max(0.5f64.powi(25) / floor)
            }
            // Channel error <= half a code times m range, with m range < brightest + range /
            // 255; and the fixed point's 2^-22 range.
            Representation::Rgbm { range } => {
                0.5 / 255.0 * (1.0 + range / (255.0 * floor)) + range * 0.5f64.powi(21) / floor
            }
            // Light: half an ulp of a 10-bit mantissa, or half the denormal step 2^-24.
            Representation::Half => {
                small_float::max_relative_error(10).max(0.5f64.powi(25) / floor)
            }
            Representation::Octahedral { bits } => octahedral::max_error_degrees(bits),
            Representation::Unorm { bits } => unorm::max_error(bits),
            Representation::UnormWord { format } => unorm::max_error(format.channels()[0].bits),
            Representation::Light { encoding, each } => {
                light_storage(encoding, each, floor).relative_error
            }
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
        error <= Representation::allowed_error(quantity.kind(), precision)
            && (quantity.kind() != Kind::Hdr || self.hdr_max() >= precision.hdr_max)
    }

    /// The bound on its error storing `quantity`, in the unit of the quantity's kind (see the
    /// module's doc).
    pub fn predicted_error(self, quantity: Quantity, precision: &Precision) -> f64 {
        match (self, quantity.kind()) {
            // A scalar in [0, 1]: half the ulp of [0.5, 1).
            (Representation::Half, Kind::Scalar) => 0.5f64.powi(12),
            _ => self.bound(precision),
        }
    }

    /// Every representation of a quantity the solver considers, before precision: for each family
    /// the widths from 1 bit up to what one word holds. The light representations clip at the
    /// scene's `hdr_max` (RGBM takes it as its range where the exact encoding can hold it).
    pub fn catalogue(quantity: Quantity, precision: &Precision) -> Vec<Representation> {
        match quantity.kind() {
            Kind::Hdr => {
                let mut all = vec![
                    Representation::PackedFloat,
                    Representation::SharedExponent,
                    Representation::Half,
                ];
                if RgbmRange::new(precision.hdr_max as f32).is_ok() {
                    all.push(Representation::Rgbm {
                        range: precision.hdr_max,
                    });
                }
                for codec in Encoding::CODECS {
                    let Ok(encoding) = Encoding::from_name(codec.name, None) else {
                        continue; // a codec that needs a parameter offers none here
                    };
                    all.extend((codec.light_storage)(precision.hdr_min).into_iter().map(
                        |storage| Representation::Light {
                            encoding,
                            each: storage.each,
                        },
                    ));
                }
                all
            }
            Kind::Distance => vec![Representation::Float32],
            Kind::Direction => (1..=16)
                .map(|bits| Representation::Octahedral { bits })
                .collect(),
            Kind::Colour => (1..=10)
                .map(|bits| Representation::Unorm { bits })
                .chain(
                    [Format::Rgba8, Format::Rgb10A2]
                        .map(|format| Representation::UnormWord { format }),
                )
                .collect(),
            Kind::Scalar => (1..=16)
                .map(|bits| Representation::Unorm { bits })
                .chain([Representation::Half])
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

impl fmt::Display for Representation {
    /// A short description for reports: "octahedral, 2 x 12 bits".
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Representation::Float32 => write!(out, "32-bit float"),
            Representation::PackedFloat => write!(out, "r11f_g11f_b10f floats"),
            Representation::SharedExponent => write!(out, "rgb9e5 shared exponent"),
            Representation::Rgbm { range } => write!(out, "RGBM, 4 x 8 bits, range {range}"),
            Representation::Half => write!(out, "binary16"),
            Representation::Octahedral { bits } => write!(out, "octahedral, 2 x {bits} bits"),
            Representation::Unorm { bits } => write!(out, "unorm, {bits} bits"),
            Representation::UnormWord { format } => write!(out, "unorm in a {format} word"),
            Representation::Light { encoding, each } => write!(out, "{encoding}, 3 x {each} bits"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storage_sizes() {
        assert_eq!(Representation::Half.bits(Quantity::Roughness), 16);
        assert_eq!(
            Representation::Octahedral { bits: 12 }.bits(Quantity::Normal),
            24
        );
        assert_eq!(
            Representation::Unorm { bits: 8 }.bits(Quantity::BaseColour),
            24
        );
        assert_eq!(
            Representation::Rgbm { range: 8.0 }.bits(Quantity::Light),
            32
        );
        assert_eq!(Representation::Half.bits(Quantity::Light), 48);
        assert_eq!(Representation::Half.pieces(Quantity::Light).len(), 2);
        assert_eq!(
            Representation::UnormWord {
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
        let degrees = |representation: Representation| {
            representation.predicted_error(Quantity::Normal, &precision)
        };
        assert!((degrees(Representation::Octahedral { bits: 16 }) - 0.00371).abs() < 1e-4);
        assert_eq!(
            Representation::Unorm { bits: 8 }.predicted_error(Quantity::BaseColour, &precision),
            0.5 / 255.0
        );
        assert!(Representation::Unorm { bits: 8 }.meets(Quantity::BaseColour, &precision));
        assert!(!Representation::Unorm { bits: 7 }.meets(Quantity::BaseColour, &precision));
        // r11f_g11f_b10f: 1/64 relative meets 2%.
        assert!(Representation::PackedFloat.meets(Quantity::Light, &precision));
    }

    /// A codec that offers light storage is in the catalogue without the solver naming it:
    /// log luminance at 10 bits a channel (1/64 relative) meets the default 2%.
    #[test]
    fn the_codecs_light_storage_is_in_the_catalogue() {
        let precision = Precision::default();
        let log_luminance = Representation::Light {
            encoding: Encoding::LogLuminance,
            each: 10,
        };
        assert!(Representation::catalogue(Quantity::Light, &precision).contains(&log_luminance));
        assert_eq!(log_luminance.bits(Quantity::Light), 30);
        assert!(log_luminance.meets(Quantity::Light, &precision));
        assert_eq!(log_luminance.to_string(), "log_luminance, 3 x 10 bits");
        // The bound holds through the layout's own mirror.
        for index in 0..10_000 {
            let value = 2f32.powf(-6.0 + 9.0 * index as f32 / 10_000.0);
            let light = Vec3::new(value, value * 0.7, value * 0.2);
            let back = log_luminance.round_trip(Quantity::Light, light);
            let error = ((back - light).abs() / light.max_element()).max_element();
            assert!(f64::from(error) <= 1.0 / 64.0, "{light} -> {back}");
        }
    }
}
