//! The codecs: how a value becomes the bits of a channel or a bit field, one file each.
//!
//! A codec's file holds all of it, as Bevy keeps one shader file per codec: the contract (its
//! doc), the Rust mirror (the encode and decode the derive and the CPU call), the WGSL text the
//! emitters write (exact, and fast where it has a fast form; GLSL is translated from it), and
//! the unit tests that hold the mirror against an independent reference.
//!
//! The whole-word formats are built from the same codecs: a format's channels are codecs at
//! fixed widths ([`crate::format`]), so `rgba8` is four 8-bit [`unorm`]s and
//! `r11f_g11f_b10f` three [`unsigned_float`]s.
//!
//! # Adding a codec
//!
//! Write one file here with a unit struct that implements [`Codec`], and add one line to the
//! list at the end of this file. The derive and layout files then accept its name, the WGSL
//! and GLSL emitters write it, the Rust mirror packs it, and the report and the solver's
//! catalogue list it. [`log_luminance`] was added this way.

pub mod boolean;
pub mod float32;
pub mod half;
pub mod integer;
pub mod log_luminance;
pub mod octahedral;
pub mod rgb9e5;
pub mod rgbm;
pub mod scaled_quotient;
pub mod small_float;
pub mod snorm;
pub mod unorm;
pub mod unsigned_float;
pub mod wgsl;

use crate::format::ScalarKind;
use crate::layout::FieldType;

/// The bits of +infinity as f32; a magnitude above it is a NaN (and so, as an unsigned
/// integer, is every negative float's bit pattern).
pub(crate) const F32_INFINITY_BITS: u32 = 0x7f80_0000;

/// The largest code of an unsigned integer of `bits` bits (`bits` from 1 to 32).
#[inline]
pub fn max_code(bits: u32) -> u32 {
    u32::MAX >> (32 - bits)
}

/// A float's significand (the implicit bit included) and its exponent field (denormals read
/// as exponent 1, as their value is), for a non-negative float given as bits.
#[inline(always)]
pub(crate) fn significand_and_exponent(bits: u32) -> (u32, u32) {
    let exponent = bits >> 23;
    (
        (bits & 0x7f_ffff) | (u32::from(exponent != 0) << 23),
        exponent.max(1),
    )
}

/// One codec: its name, what it holds, its mirror and its WGSL.
///
/// Values travel as *lanes*: each component's bits in a `u32` (an `f32`'s bits, a `u32`, an
/// `i32` as `u32`, a `bool` as 0 or 1), up to four. `each` is the width of one component's
/// code ([`Codec::component_bits`]); `range` is the parameter of codecs that take one
/// (RGBM's largest value).
pub trait Codec: Sync {
    /// Its name as layout files and the derive spell it: `unorm`, `octahedral`, ...
    fn name(&self) -> &'static str;

    /// The scalar kind of the fields it holds.
    fn scalar_kind(&self) -> ScalarKind {
        ScalarKind::Float
    }

    /// Whether fast conversions change its WGSL (float arithmetic and builtins in place of
    /// the exact integer algorithm).
    fn has_fast_form(&self) -> bool {
        false
    }

    /// Its [`Encoding`], given the range written after its name (which only RGBM takes).
    fn encoding(&self, range: Option<f32>) -> Result<Encoding, String>;

    /// Why a bit field of `bits` bits (1 to 32) cannot hold `ty` (whose scalar kind is
    /// already [`Codec::scalar_kind`]), if it cannot: one sentence naming `encoding`.
    fn mismatch(&self, encoding: Encoding, bits: u32, ty: FieldType) -> Option<String>;

    /// The bits of one component's code.
    fn component_bits(&self, bits: u32, components: usize) -> u32 {
        bits / components as u32
    }

    /// The code of a value's first `components` lanes, in the low bits: the Rust mirror.
    fn encode(&self, lanes: [u32; 4], components: usize, each: u32, range: Option<f32>) -> u32;

    /// The lanes of a code (lanes past the components are 0): the Rust mirror.
    fn decode(&self, code: u32, components: usize, each: u32, range: Option<f32>) -> [u32; 4];

    /// The WGSL of a bit field: its encode and decode functions' bodies and the helpers they
    /// call.
    fn wgsl(&self, field: &wgsl::BitField) -> wgsl::Functions;

    /// The bit fields it offers the solver for light (a `vec3` of linear HDR values, one width
    /// per component each), with their error bounds; empty where it stores no light this way.
    /// `floor` is the scene's smallest light value that matters (errors are relative to the
    /// brightest channel, or to `floor` where that is larger).
    fn light_storage(&self, floor: f64) -> Vec<LightStorage> {
        let _ = floor;
        Vec::new()
    }
}

/// A light bit field a codec offers the solver: its width and what it guarantees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightStorage {
    /// Bits per component (three components).
    pub each: u32,
    /// The bound on the error relative to the brightest channel (or to the floor).
    pub relative_error: f64,
    /// The largest value it holds without clipping.
    pub largest: f64,
}

/// `(name, bits)`: the shape of a codec refusing a vector or scalar type: "`unorm` takes 1 to
/// 23 bits per component, not 24 (`Vec2` in 48 bits)", for the per-component codecs.
pub(crate) fn per_component_mismatch(
    encoding: Encoding,
    bits: u32,
    ty: FieldType,
    (low, high): (u32, u32),
) -> Option<String> {
    let name = ty.rust_name();
    let components = ty.components as u32;
    if bits % components != 0 {
        return Some(format!(
            "`{name}` has {components} components, which cannot share {bits} bits evenly"
        ));
    }
    let each = bits / components;
    (!(low..=high).contains(&each)).then(|| {
        let range = if low == high {
            format!("exactly {low}")
        } else {
            format!("{low} to {high}")
        };
        format!(
            "`{encoding}` takes {range} bits per component, not {each} (`{name}` in {bits} bits)"
        )
    })
}

/// The refusal of a codec that stores one type in a fixed width: "`rgb9e5` stores a `Vec3` in
/// exactly 32 bits, not `Vec2` in 32".
pub(crate) fn exact_shape_mismatch(
    encoding: Encoding,
    bits: u32,
    ty: FieldType,
    (wanted_bits, components, what): (u32, usize, &str),
) -> Option<String> {
    (bits != wanted_bits || ty.components != components).then(|| {
        format!(
            "`{encoding}` stores {what} in exactly {wanted_bits} bit{}, not `{}` in {bits}",
            if wanted_bits == 1 { "" } else { "s" },
            ty.rust_name()
        )
    })
}

/// The encoding of a codec that takes no range, or why a range was given.
pub(crate) fn without_range(encoding: Encoding, range: Option<f32>) -> Result<Encoding, String> {
    match range {
        Some(_) => Err(format!("only `rgbm` takes a range, not `{encoding}`")),
        None => Ok(encoding),
    }
}

/// Each of the first `components` lanes' code at `each` bits, x in the low bits. Always
/// inlined with a known `code`: derived code's packing calls it per texel.
#[inline(always)]
pub(crate) fn join_codes(
    lanes: [u32; 4],
    components: usize,
    each: u32,
    code: impl Fn(u32, u32) -> u32,
) -> u32 {
    (0..components).fold(0, |word, index| {
        word | (code(lanes[index], each) << (each * index as u32))
    })
}

/// Each component's code at `each` bits taken out of `code` and decoded by `value`.
#[inline(always)]
pub(crate) fn split_codes(
    code: u32,
    components: usize,
    each: u32,
    value: impl Fn(u32, u32) -> u32,
) -> [u32; 4] {
    let mut lanes = [0; 4];
    for (index, lane) in lanes.iter_mut().enumerate().take(components) {
        *lane = value((code >> (each * index as u32)) & max_code(each), each);
    }
    lanes
}

/// The lanes of a `vec3` value.
#[inline(always)]
pub(crate) fn vector_lanes(value: [f32; 3]) -> [u32; 4] {
    let [x, y, z] = value.map(f32::to_bits);
    [x, y, z, 0]
}

/// A `vec3` value from its lanes.
#[inline(always)]
pub(crate) fn vector_of(lanes: [u32; 4]) -> [f32; 3] {
    [lanes[0], lanes[1], lanes[2]].map(f32::from_bits)
}

/// The list: every codec, as a variant of [`Encoding`] and the unit struct that implements
/// it. A variant with a parameter names its type (RGBM's range).
macro_rules! codecs {
    ($($(#[$doc:meta])* $variant:ident $(($parameter:ty))? => $codec:expr,)*) => {
        /// How bits encode a value: one variant per codec of [`crate::codecs`], the list in
        /// its module. A format's channels and a bit field both name one.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Encoding {
            $($(#[$doc])* $variant $(($parameter))?,)*
        }

        impl Encoding {
            /// Its codec.
            #[inline(always)]
            pub fn codec(self) -> &'static dyn Codec {
                match self {
                    $(Encoding::$variant $((first!(_, $parameter)))? => &$codec,)*
                }
            }

            /// Every codec, in the list's order.
            pub const CODECS: &'static [&'static dyn Codec] = &[$(&$codec,)*];
        }
    };
}

/// The first of two token trees (a pattern's `_` for a variant's parameter).
macro_rules! first {
    ($first:tt, $second:ty) => {
        $first
    };
}

codecs! {
    /// Unsigned normalized per component ([`unorm`]).
    Unorm => unorm::Unorm,
    /// Signed normalized per component ([`snorm`]).
    Snorm => snorm::Snorm,
    /// Unsigned integer per component ([`integer`]).
    Uint => integer::Uint,
    /// Signed integer per component, two's complement ([`integer`]).
    Sint => integer::Sint,
    /// A `bool` in one bit ([`boolean`]).
    Bool => boolean::Bool,
    /// IEEE binary16 per component ([`half`]).
    Half => half::Half,
    /// IEEE binary32, bit for bit ([`float32`]).
    Float32 => float32::Float32,
    /// An unsigned float with a 5-bit exponent, as in `r11f_g11f_b10f` ([`unsigned_float`]).
    UnsignedFloat => unsigned_float::UnsignedFloat,
    /// Shared-exponent `vec3` in 32 bits ([`rgb9e5`]).
    Rgb9e5 => rgb9e5::Rgb9e5,
    /// A unit `vec3` as an octahedral map ([`octahedral`]).
    Octahedral => octahedral::Octahedral,
    /// A `vec3` in `[0, range]` as RGBM in 32 bits ([`rgbm`]).
    Rgbm(rgbm::RgbmRange) => rgbm::Rgbm,
    /// A positive scalar per component as a piecewise-linear logarithm ([`log_luminance`]).
    LogLuminance => log_luminance::LogLuminance,
}

/// Runs `check` on every bit pattern in `patterns`, split over two threads; the first
/// failure, if any. The codecs' exhaustive tests take every f32 through it.
#[cfg(test)]
pub(crate) fn every_pattern(
    patterns: std::ops::RangeInclusive<u32>,
    check: impl Fn(u32) -> Option<String> + Sync,
) -> Option<String> {
    let (first, last) = (*patterns.start(), *patterns.end());
    let middle = first + (last - first) / 2;
    std::thread::scope(|scope| {
        let workers: Vec<_> = [first..=middle, middle + 1..=last]
            .into_iter()
            .map(|half| scope.spawn(|| half.into_iter().find_map(&check)))
            .collect();
        workers
            .into_iter()
            .find_map(|worker| worker.join().expect("a worker finishes"))
    })
}

impl Encoding {
    /// Every codec's name as layout files and the derive spell it (rgbm takes a range).
    pub fn names() -> Vec<&'static str> {
        Encoding::CODECS.iter().map(|codec| codec.name()).collect()
    }

    /// The codec's name: `unorm`, `octahedral`, `rgbm`, ...
    pub fn name(self) -> &'static str {
        self.codec().name()
    }

    /// Parses a name; `range` is rgbm's (and must be absent for the others).
    pub fn from_name(name: &str, range: Option<f32>) -> Result<Encoding, String> {
        let codec = Encoding::CODECS
            .iter()
            .find(|codec| codec.name() == name)
            .ok_or_else(|| {
                format!(
                    "unknown encoding `{name}`: expected one of {}",
                    Encoding::names().join(", ")
                )
            })?;
        codec.encoding(range)
    }

    /// The scalar kind of the fields it holds.
    pub fn scalar_kind(self) -> ScalarKind {
        self.codec().scalar_kind()
    }

    /// Whether fast conversions change its WGSL.
    pub fn has_fast_form(self) -> bool {
        self.codec().has_fast_form()
    }

    /// Its parameter: RGBM's range.
    #[inline(always)]
    pub fn range(self) -> Option<f32> {
        match self {
            Encoding::Rgbm(range) => Some(range.get()),
            _ => None,
        }
    }
}

impl std::fmt::Display for Encoding {
    fn fmt(&self, out: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.range() {
            Some(range) => write!(out, "{}({range:?})", self.name()),
            None => out.write_str(self.name()),
        }
    }
}
