//! Bit fields: a field of `N` bits in a shared `r32ui` word, and the encodings that turn its
//! value into those bits (`#[bits(N, ENCODING)]` in the derive, `bits` and `encoding` in a
//! layout file).
//!
//! Each encoding has one contract, kept by the Rust mirror here and [`crate::convert`], by the
//! WGSL of `gbuffer_codegen::emit::wgsl` and by the GLSL translated from it. A vector field of the
//! per-component encodings (unorm, snorm, uint, sint, half) splits its bits evenly, x in the
//! lowest.

use std::fmt;

use crate::convert;
use crate::format::ScalarKind;
use crate::layout::FieldType;

/// The largest value an RGBM field stores: a positive float with at most 16 significant bits
/// (6, 8, 16, 51.5, ...), so that the exact encoding holds it without rounding.
#[derive(Clone, Copy, Debug)]
pub struct RgbmRange(f32);

impl RgbmRange {
    /// The range, if it is one an RGBM field can hold; otherwise why not.
    pub fn new(range: f32) -> Result<RgbmRange, String> {
        if !(range.is_finite() && range >= f32::MIN_POSITIVE) {
            return Err(format!(
                "an RGBM range must be a positive finite number, not {range}"
            ));
        }
        if range.to_bits() & 0xff != 0 {
            return Err(format!(
                "RGBM range {range} has more than 16 significant bits; the exact encoding needs \
                 it within 16 (6, 8, 16 or 51.5 are fine)"
            ));
        }
        Ok(RgbmRange(range))
    }

    /// A range the derive has checked with [`RgbmRange::new`] (derived code builds its bit
    /// fields in constant expressions).
    #[doc(hidden)]
    pub const fn from_checked(range: f32) -> RgbmRange {
        RgbmRange(range)
    }

    /// The range as a float.
    pub fn get(self) -> f32 {
        self.0
    }
}

impl PartialEq for RgbmRange {
    fn eq(&self, other: &Self) -> bool {
        self.0.to_bits() == other.0.to_bits()
    }
}

impl Eq for RgbmRange {}

impl std::hash::Hash for RgbmRange {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.0.to_bits().hash(state);
    }
}

impl PartialOrd for RgbmRange {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for RgbmRange {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.to_bits().cmp(&other.0.to_bits())
    }
}

/// How a bit field's bits encode its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Encoding {
    /// Unsigned normalized, per component: `floor(0.5 + (2^n - 1) clamp(x, 0, 1))`, exact; NaN
    /// gives 0. 1 to 23 bits per component.
    Unorm,
    /// Signed normalized, GL's formula per component: `round(clamp(x, -1, 1) (2^(n-1) - 1))`,
    /// halves away from zero, exact, as an n-bit two's complement; decodes with `max(.., -1)`.
    /// 2 to 24 bits per component.
    Snorm,
    /// Unsigned integer per component, clamped to `2^n - 1`.
    Uint,
    /// Signed integer per component, clamped to `[-2^(n-1), 2^(n-1) - 1]`, two's complement.
    Sint,
    /// A `bool` in one bit.
    Bool,
    /// IEEE binary16 per component (16 bits each): round to nearest even, denormals kept,
    /// saturating at +-65504, NaN to 0.
    Half,
    /// Shared-exponent `vec3` in 32 bits (EXT_texture_shared_exponent's algorithm, exact).
    Rgb9e5,
    /// A unit `vec3` as an octahedral map (Cigolle et al. 2014), `n / 2` bits per coordinate,
    /// x in the low half. See [`convert::octahedral_from_f32`].
    Octahedral,
    /// A `vec3` in `[0, range]` as RGBM (Karis 2009) in 32 bits laid out as rgba8: the
    /// colour over a shared multiplier `m` (alpha), `colour = rgb * m * range`. See
    /// [`convert::rgbm_from_f32`].
    Rgbm(RgbmRange),
}

impl Encoding {
    /// Every encoding's name as layout files and the derive spell it (rgbm takes a range).
    pub const NAMES: [&'static str; 9] = [
        "unorm",
        "snorm",
        "uint",
        "sint",
        "bool",
        "half",
        "rgb9e5",
        "octahedral",
        "rgbm",
    ];

    /// The encoding's name: `unorm`, `octahedral`, `rgbm`, ...
    pub fn name(self) -> &'static str {
        match self {
            Encoding::Unorm => "unorm",
            Encoding::Snorm => "snorm",
            Encoding::Uint => "uint",
            Encoding::Sint => "sint",
            Encoding::Bool => "bool",
            Encoding::Half => "half",
            Encoding::Rgb9e5 => "rgb9e5",
            Encoding::Octahedral => "octahedral",
            Encoding::Rgbm(_) => "rgbm",
        }
    }

    /// Parses a name; `range` is rgbm's (and must be absent for the others).
    pub fn from_name(name: &str, range: Option<f32>) -> Result<Encoding, String> {
        let encoding = match name {
            "unorm" => Encoding::Unorm,
            "snorm" => Encoding::Snorm,
            "uint" => Encoding::Uint,
            "sint" => Encoding::Sint,
            "bool" => Encoding::Bool,
            "half" => Encoding::Half,
            "rgb9e5" => Encoding::Rgb9e5,
            "octahedral" => Encoding::Octahedral,
            "rgbm" => {
                let range = range.ok_or(
                    "`rgbm` needs the largest value it stores: `rgbm(8)` in the derive, \
                     `range = 8.0` in a layout file",
                )?;
                return RgbmRange::new(range).map(Encoding::Rgbm);
            }
            _ => {
                return Err(format!(
                    "unknown encoding `{name}`: expected one of {}",
                    Encoding::NAMES.join(", ")
                ))
            }
        };
        match range {
            Some(_) => Err(format!("only `rgbm` takes a range, not `{name}`")),
            None => Ok(encoding),
        }
    }

    /// The scalar kind of the fields it holds.
    pub fn scalar_kind(self) -> ScalarKind {
        match self {
            Encoding::Uint => ScalarKind::Uint,
            Encoding::Sint => ScalarKind::Sint,
            Encoding::Bool => ScalarKind::Bool,
            _ => ScalarKind::Float,
        }
    }

    /// Whether fast conversions change its WGSL (float arithmetic and builtins in place of
    /// the exact integer algorithm).
    pub fn has_fast_form(self) -> bool {
        matches!(
            self,
            Encoding::Unorm | Encoding::Half | Encoding::Octahedral | Encoding::Rgbm(_)
        )
    }
}

impl fmt::Display for Encoding {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Encoding::Rgbm(range) => write!(out, "rgbm({:?})", range.get()),
            other => out.write_str(other.name()),
        }
    }
}

/// A bit field: `bits` bits of a shared `r32ui` word and how they encode the field's value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BitField {
    /// Its width, 1 to 32.
    pub bits: u32,
    /// How the bits encode the value.
    pub encoding: Encoding,
}

impl BitField {
    /// Why a field of type `ty` cannot be this bit field, if it cannot: the width, the type
    /// and the encoding's own rules, in one sentence.
    pub fn mismatch(self, ty: FieldType) -> Option<String> {
        let BitField { bits, encoding } = self;
        let name = ty.rust_name();
        if !(1..=32).contains(&bits) {
            return Some(format!(
                "a bit field has 1 to 32 bits (it lives in one 32-bit word), not {bits}"
            ));
        }
        if ty.scalar != encoding.scalar_kind() {
            let wants = match encoding.scalar_kind() {
                ScalarKind::Float => "floats (`f32` or a `Vec`)",
                ScalarKind::Uint => "unsigned integers (`u32` or a `UVec`)",
                ScalarKind::Sint => "signed integers (`i32` or an `IVec`)",
                ScalarKind::Bool => "a `bool`",
            };
            return Some(format!("`{encoding}` holds {wants}, not `{name}`"));
        }
        let exactly = |wanted_bits: u32, components: usize, what: &str| {
            (bits != wanted_bits || ty.components != components).then(|| {
                format!(
                    "`{encoding}` stores {what} in exactly {wanted_bits} bit{}, not `{name}` in \
                     {bits}",
                    if wanted_bits == 1 { "" } else { "s" }
                )
            })
        };
        match encoding {
            Encoding::Bool => exactly(1, 1, "a `bool`"),
            Encoding::Rgb9e5 => exactly(32, 3, "a `Vec3`"),
            Encoding::Rgbm(_) => exactly(32, 3, "a `Vec3`"),
            Encoding::Octahedral if ty.components != 3 => {
                Some(format!("`octahedral` stores a unit `Vec3`, not `{name}`"))
            }
            Encoding::Octahedral if bits % 2 != 0 => Some(format!(
                "`octahedral` splits its bits between two coordinates: {bits} is odd"
            )),
            Encoding::Octahedral => None,
            _ => {
                let components = ty.components as u32;
                if bits % components != 0 {
                    return Some(format!(
                        "`{name}` has {components} components, which cannot share {bits} bits \
                         evenly"
                    ));
                }
                let each = bits / components;
                let (low, high) = match encoding {
                    Encoding::Unorm => (1, 23),
                    Encoding::Snorm => (2, 24),
                    Encoding::Half => (16, 16),
                    _ => (1, 32),
                };
                (!(low..=high).contains(&each)).then(|| {
                    let range = if low == high {
                        format!("exactly {low}")
                    } else {
                        format!("{low} to {high}")
                    };
                    format!(
                        "`{encoding}` takes {range} bits per component, not {each} (`{name}` in \
                         {bits} bits)"
                    )
                })
            }
        }
    }

    /// The bits of each component (per-component encodings) or of each octahedral coordinate.
    pub fn component_bits(self, components: usize) -> u32 {
        match self.encoding {
            Encoding::Octahedral => self.bits / 2,
            _ => self.bits / components as u32,
        }
    }

    /// The field's code: its value's lanes as bits (f32 bits, u32, i32 as u32, bool as 0 or 1;
    /// `components` of them) encoded into the low `bits` bits. The Rust mirror of the WGSL.
    #[inline(always)]
    pub fn encode(self, lanes: [u32; 4], components: usize) -> u32 {
        let each = self.component_bits(components);
        let floats = lanes.map(f32::from_bits);
        match self.encoding {
            Encoding::Unorm => join_codes(lanes, components, each, |lane, each| {
                convert::unorm_from_f32(f32::from_bits(lane), each)
            }),
            Encoding::Snorm => join_codes(lanes, components, each, |lane, each| {
                convert::snorm_from_f32(f32::from_bits(lane), each)
            }),
            Encoding::Uint => join_codes(lanes, components, each, convert::uint_saturate),
            Encoding::Sint => join_codes(lanes, components, each, |lane, each| {
                convert::sint_saturate(lane as i32, each)
            }),
            Encoding::Bool => u32::from(lanes[0] != 0),
            Encoding::Half => join_codes(lanes, components, each, |lane, _| {
                convert::half_from_f32(f32::from_bits(lane))
            }),
            Encoding::Rgb9e5 => convert::rgb9e5_from_f32([floats[0], floats[1], floats[2]]),
            Encoding::Octahedral => {
                convert::octahedral_from_f32([floats[0], floats[1], floats[2]], each)
            }
            Encoding::Rgbm(range) => {
                convert::rgbm_from_f32([floats[0], floats[1], floats[2]], range.get())
            }
        }
    }

    /// The value of a field's code (in its low bits) as lanes, as [`BitField::encode`] takes
    /// them; lanes past the field's components are 0.
    #[inline(always)]
    pub fn decode(self, code: u32, components: usize) -> [u32; 4] {
        let each = self.component_bits(components);
        let mut lanes = [0; 4];
        let vector = |value: [f32; 3]| {
            let [x, y, z] = value.map(f32::to_bits);
            [x, y, z, 0]
        };
        match self.encoding {
            Encoding::Rgb9e5 => return vector(convert::f32_from_rgb9e5(code)),
            Encoding::Octahedral => return vector(convert::f32_from_octahedral(code, each)),
            Encoding::Rgbm(range) => return vector(convert::f32_from_rgbm(code, range.get())),
            Encoding::Bool => return [u32::from(code & 1 != 0), 0, 0, 0],
            _ => {}
        }
        for (index, lane) in lanes.iter_mut().enumerate().take(components) {
            let component = (code >> (each * index as u32)) & convert::max_code(each);
            *lane = match self.encoding {
                Encoding::Unorm => convert::f32_from_unorm(component, each).to_bits(),
                Encoding::Snorm => convert::f32_from_snorm(component, each).to_bits(),
                Encoding::Half => convert::f32_from_half(component).to_bits(),
                Encoding::Sint => convert::i32_from_sint(component, each) as u32,
                _ => component,
            };
        }
        lanes
    }
}

/// Each of the first `components` lanes' code at `each` bits, x in the low bits. Always
/// inlined with a known `code`: derived code's packing calls it per texel.
#[inline(always)]
fn join_codes(
    lanes: [u32; 4],
    components: usize,
    each: u32,
    code: impl Fn(u32, u32) -> u32,
) -> u32 {
    (0..components).fold(0, |word, index| {
        word | (code(lanes[index], each) << (each * index as u32))
    })
}

impl fmt::Display for BitField {
    /// `4-bit unorm`, `32-bit rgbm(8.0)`.
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(out, "{}-bit {}", self.bits, self.encoding)
    }
}
