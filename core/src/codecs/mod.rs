//! The codecs: how a value becomes the bits of a channel or a bit field, one file each.
//!
//! A codec's file holds the model's part of it: the contract (its doc, the formula and its
//! precision), the Rust mirror (the encode and decode the derive and the CPU call), and the unit
//! tests that hold the mirror against an independent reference. Its WGSL (exact, and fast where
//! it has a fast form; GLSL is translated from it) is the WGSL back end's, in a file of the same
//! name under gbuffer-codegen's `wgsl/codecs/`, which keeps this contract.
//!
//! The whole-word formats are built from the same codecs: a format's channels are codecs at
//! fixed widths ([`crate::format`]), so `rgba8` is four 8-bit [`unorm`]s and
//! `r11f_g11f_b10f` three [`unsigned_float`]s.
//!
//! # Adding a codec
//!
//! Write one file here that builds its [`Codec`] as a constant (`pub const CODEC: Codec =
//! Codec::floats(...)`, with its mirror's functions), add one line to the list at the end of
//! this file, and write its WGSL in one file of gbuffer-codegen's `wgsl/codecs/` (the back
//! end's match over [`Encoding`] names what is missing). The derive and layout files then
//! accept its name, the WGSL and GLSL emitters write it, the Rust mirror packs it, and where it
//! offers light storage the solver's catalogue lists it. [`log_luminance`] was added this way.

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

use crate::field_type::{FieldType, ScalarKind};

/// The bits of +infinity as f32; a magnitude above it is a NaN (and so, as an unsigned
/// integer, is every negative float's bit pattern).
pub(crate) const F32_INFINITY_BITS: u32 = 0x7f80_0000;

/// An integer-valued float in `[0, 2^23)` as that integer: adding 2^23 puts it in the low bits of
/// the sum's significand, exactly. The same as `value as u32` there, and unlike it a conversion
/// CPUs have in their vector units (AVX2 converts floats only to signed integers, and
/// `as`'s saturation keeps LLVM from vectorising even that): the slices' lanes stay vectors.
#[inline(always)]
pub(crate) fn small_integer_from_f32(value: f32) -> u32 {
    (value + 8_388_608.0).to_bits() - 0x4B00_0000
}

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

/// One codec: its name, what it holds and its Rust mirror. Each codec's file builds its own as a
/// constant (`CODEC`) with the constructors below.
///
/// Values travel as *lanes*: each component's bits in a `u32` (an `f32`'s bits, a `u32`, an
/// `i32` as `u32`, a `bool` as 0 or 1), up to four. `each` is the width of one component's
/// code ([`Codec::component_bits`]); `range` is the parameter of the codecs that take one
/// (RGBM's largest value).
#[derive(Clone, Copy, Debug)]
pub struct Codec {
    /// Its name as layout files and the derive spell it: `unorm`, `octahedral`, ...
    pub name: &'static str,
    /// The scalar kind of the fields it holds.
    pub scalar_kind: ScalarKind,
    /// The types and widths it takes.
    pub shape: Shape,
    /// Whether it has a fast form: conversions a layout or field may ask for that trade the
    /// exact algorithm for the adapter's float arithmetic and builtins, within a stated bound.
    pub has_fast_form: bool,
    /// The Rust mirror.
    pub conversion: Conversion,
    /// The bit fields it offers the solver for light (a `vec3` of linear HDR values, one width
    /// per component each) with their error bounds, given the scene's smallest light value
    /// that matters; empty where it stores no light this way.
    pub light_storage: fn(f64) -> Vec<LightStorage>,
}

/// The types and widths a codec takes.
#[derive(Clone, Copy, Debug)]
pub enum Shape {
    /// A scalar or vector, each component in `low` to `high` bits (a vector splits its bits
    /// evenly).
    PerComponent(u32, u32),
    /// Exactly `components` components in exactly `bits` bits; `what` names them for errors
    /// (``a `Vec3` ``).
    Fixed(u32, usize, &'static str),
    /// A unit `Vec3` as two coordinates sharing an even number of bits.
    Coordinates,
}

/// A codec's Rust mirror.
#[derive(Clone, Copy, Debug)]
pub enum Conversion {
    /// Floats, each component on its own: a value to its code of `each` bits, and back.
    Floats(fn(f32, u32) -> u32, fn(u32, u32) -> f32),
    /// Integers and bools, each component on its own: a lane to its code, and back.
    Integers(fn(u32, u32) -> u32, fn(u32, u32) -> u32),
    /// A `vec3` at once, given `each` and the range: its code, and back.
    Vector(
        fn([f32; 3], u32, Option<f32>) -> u32,
        fn(u32, u32, Option<f32>) -> [f32; 3],
    ),
}

/// A float codec's conversions of one component: a value to its code of `each` bits, and back.
pub type FloatConversions = (fn(f32, u32) -> u32, fn(u32, u32) -> f32);

/// A vector codec's conversions: a `vec3` to its code given `each` and the range, and back.
pub type VectorConversions = (
    fn([f32; 3], u32, Option<f32>) -> u32,
    fn(u32, u32, Option<f32>) -> [f32; 3],
);

/// No light storage.
fn no_light_storage(_: f64) -> Vec<LightStorage> {
    Vec::new()
}

impl Codec {
    /// A codec of these parts, without a fast form or light storage (the `with_` methods add
    /// them). `conversion` goes with `scalar_kind`: `Floats` and `Vector` with floats,
    /// `Integers` with the integers and bools. Float codecs of one component at a time have the
    /// shorter [`Codec::floats`].
    pub const fn new(
        name: &'static str,
        scalar_kind: ScalarKind,
        shape: Shape,
        conversion: Conversion,
    ) -> Codec {
        Codec {
            name,
            scalar_kind,
            shape,
            has_fast_form: false,
            conversion,
            light_storage: no_light_storage,
        }
    }

    /// A per-component codec of floats, `low` to `high` bits a component.
    pub const fn floats(
        name: &'static str,
        (low, high): (u32, u32),
        (encode, decode): FloatConversions,
    ) -> Codec {
        let shape = Shape::PerComponent(low, high);
        let conversion = Conversion::Floats(encode, decode);
        Codec::new(name, ScalarKind::Float, shape, conversion)
    }

    /// A codec of a whole `Vec3`, of `shape`.
    pub const fn vector(
        name: &'static str,
        shape: Shape,
        (encode, decode): VectorConversions,
    ) -> Codec {
        let conversion = Conversion::Vector(encode, decode);
        Codec::new(name, ScalarKind::Float, shape, conversion)
    }

    /// The codec with a fast form.
    pub const fn with_fast_form(self) -> Codec {
        Codec {
            has_fast_form: true,
            ..self
        }
    }

    /// The codec offering light storage.
    pub const fn with_light_storage(self, light_storage: fn(f64) -> Vec<LightStorage>) -> Codec {
        Codec {
            light_storage,
            ..self
        }
    }

    /// The bits of one component's code (of one coordinate, for two coordinates).
    pub fn component_bits(&self, bits: u32, components: usize) -> u32 {
        match self.shape {
            Shape::Coordinates => bits / 2,
            _ => bits / components as u32,
        }
    }

    /// Why a bit field of `bits` bits (1 to 32) cannot hold `ty` (whose scalar kind is
    /// already [`Codec::scalar_kind`]), if it cannot: one sentence naming `encoding`.
    pub fn mismatch(&self, encoding: Encoding, bits: u32, ty: FieldType) -> Option<String> {
        let name = ty.rust_name();
        match self.shape {
            Shape::PerComponent(low, high) => {
                let components = ty.components as u32;
                if !bits.is_multiple_of(components) {
                    return Some(format!(
                        "`{name}` has {components} components, which cannot share {bits} bits \
                         evenly"
                    ));
                }
                let each = bits / components;
                let range = match low == high {
                    true => format!("exactly {low}"),
                    false => format!("{low} to {high}"),
                };
                (!(low..=high).contains(&each)).then(|| {
                    format!(
                        "`{encoding}` takes {range} bits per component, not {each} (`{name}` in \
                         {bits} bits)"
                    )
                })
            }
            Shape::Fixed(wanted_bits, components, what) => {
                (bits != wanted_bits || ty.components != components).then(|| {
                    let plural = if wanted_bits == 1 { "" } else { "s" };
                    format!(
                        "`{encoding}` stores {what} in exactly {wanted_bits} bit{plural}, not \
                         `{name}` in {bits}"
                    )
                })
            }
            Shape::Coordinates if ty.components != 3 => {
                Some(format!("`{encoding}` stores a unit `Vec3`, not `{name}`"))
            }
            Shape::Coordinates => (!bits.is_multiple_of(2)).then(|| {
                format!("`{encoding}` splits its bits between two coordinates: {bits} is odd")
            }),
        }
    }

    /// The code of a value's first `components` lanes, in the low bits: the Rust mirror.
    // Always inlined: derived code calls it with a constant codec, and its dispatch folds
    // away.
    #[inline(always)]
    pub fn encode(&self, lanes: [u32; 4], components: usize, each: u32, range: Option<f32>) -> u32 {
        match self.conversion {
            Conversion::Floats(encode, _) => join_codes(lanes, components, each, |lane, each| {
                encode(f32::from_bits(lane), each)
            }),
            Conversion::Integers(encode, _) => join_codes(lanes, components, each, encode),
            Conversion::Vector(encode, _) => encode(
                [lanes[0], lanes[1], lanes[2]].map(f32::from_bits),
                each,
                range,
            ),
        }
    }

    /// The lanes of a code (lanes past the components are 0): the Rust mirror.
    #[inline(always)]
    pub fn decode(&self, code: u32, components: usize, each: u32, range: Option<f32>) -> [u32; 4] {
        match self.conversion {
            Conversion::Floats(_, decode) => split_codes(code, components, each, |code, each| {
                decode(code, each).to_bits()
            }),
            Conversion::Integers(_, decode) => split_codes(code, components, each, decode),
            Conversion::Vector(_, decode) => {
                let [x, y, z] = decode(code, each, range).map(f32::to_bits);
                [x, y, z, 0]
            }
        }
    }
}

/// Each of the first `components` lanes' code at `each` bits, x in the low bits.
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

/// Each component's code at `each` bits taken out of `code` and decoded by `value`.
#[inline(always)]
fn split_codes(
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

/// The list: every codec, as a variant of [`Encoding`] and the constant its file builds. A
/// variant with a parameter names its type (RGBM's range), which parses the range written
/// after the codec's name.
macro_rules! codecs {
    ($($(#[$doc:meta])* $variant:ident $(($parameter:ty))? => $codec:path,)*) => {
        /// How bits encode a value: one variant per codec of [`crate::codecs`], the list in
        /// its module. A format's channels and a bit field both name one.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Encoding {
            $($(#[$doc])* $variant $(($parameter))?,)*
        }

        impl Encoding {
            /// Its codec.
            #[inline(always)]
            pub fn codec(self) -> &'static Codec {
                match self {
                    $(Encoding::$variant $((first!(_, $parameter)))? => &$codec,)*
                }
            }

            /// Every codec, in the list's order.
            pub const CODECS: &'static [&'static Codec] = &[$(&$codec,)*];

            /// Parses a codec's name; `range` is what layout files and the derive write after
            /// it (only a codec with a parameter takes one).
            pub fn from_name(name: &str, range: Option<f32>) -> Result<Encoding, String> {
                $(if name == $codec.name {
                    return construct!($variant, range $(, $parameter)?);
                })*
                Err(format!(
                    "unknown encoding `{name}`: expected one of {}",
                    Encoding::names().join(", ")
                ))
            }
        }
    };
}

/// The first of two token trees (a pattern's `_` for a variant's parameter).
macro_rules! first {
    ($first:tt, $second:ty) => {
        $first
    };
}

/// An encoding from its variant and the range after its name: none for a codec without a
/// parameter, the parameter's own parse otherwise.
macro_rules! construct {
    ($variant:ident, $range:ident) => {
        match $range {
            Some(_) => Err(format!(
                "only `rgbm` takes a range, not `{}`",
                Encoding::$variant
            )),
            None => Ok(Encoding::$variant),
        }
    };
    ($variant:ident, $range:ident, $parameter:ty) => {
        <$parameter>::from_range($range).map(Encoding::$variant)
    };
}

codecs! {
    /// Unsigned normalized per component ([`unorm`]).
    Unorm => unorm::CODEC,
    /// Signed normalized per component ([`snorm`]).
    Snorm => snorm::CODEC,
    /// Unsigned integer per component ([`integer`]).
    Uint => integer::UINT,
    /// Signed integer per component, two's complement ([`integer`]).
    Sint => integer::SINT,
    /// A `bool` in one bit ([`boolean`]).
    Bool => boolean::CODEC,
    /// IEEE binary16 per component ([`half`]).
    Half => half::CODEC,
    /// IEEE binary32, bit for bit ([`float32`]).
    Float32 => float32::CODEC,
    /// An unsigned float with a 5-bit exponent, as in `r11f_g11f_b10f` ([`unsigned_float`]).
    UnsignedFloat => unsigned_float::CODEC,
    /// Shared-exponent `vec3` in 32 bits ([`rgb9e5`]).
    Rgb9e5 => rgb9e5::CODEC,
    /// A unit `vec3` as an octahedral map ([`octahedral`]).
    Octahedral => octahedral::CODEC,
    /// A `vec3` in `[0, range]` as RGBM in 32 bits ([`rgbm`]).
    Rgbm(rgbm::RgbmRange) => rgbm::CODEC,
    /// A positive scalar per component as a piecewise-linear logarithm ([`log_luminance`]).
    LogLuminance => log_luminance::CODEC,
}

/// Encodes every f32 at each of `widths` with `encode`, and asserts that the code is
/// `reference`'s, on two threads. The codecs' exhaustive tests,
/// which a debug build skips (each says how to run it): optimised, `cargo test --release -p
/// gbuffer-core --lib every_f32` runs them all (CI's `exhaustive` step).
///
/// The f32s go in blocks of 2^16, and a block's codes are compared as one reduction (the XOR of
/// each pair, ORed together) with no branch per value, which the compiler can turn into vector
/// code. Only a block that differs somewhere is searched value by value, for the first f32 that
/// fails, which the assertion names.
#[cfg(test)]
pub(crate) fn assert_every_f32(
    name: &str,
    widths: &[u32],
    encode: impl Fn(f32, u32) -> u32 + Sync,
    reference: impl Fn(f32, u32) -> u32 + Sync,
) {
    const BLOCK: u32 = 1 << 16;
    let first_failure = |value_bits: u32| {
        let value = f32::from_bits(value_bits);
        widths.iter().find_map(|&bits| {
            let (got, want) = (encode(value, bits), reference(value, bits));
            (got != want).then(|| {
                format!("{value:e} ({value_bits:#010x}) as {name} of {bits} bits: {got:#x}, reference {want:#x}")
            })
        })
    };
    let block_differs = |first: u32| {
        widths.iter().any(|&bits| {
            let differences = (0..BLOCK).fold(0, |differences, offset| {
                let value = f32::from_bits(first + offset);
                differences | (encode(value, bits) ^ reference(value, bits))
            });
            differences != 0
        })
    };
    // Worker 0 takes the even blocks and worker 1 the odd: the f32s' two halves (the negative
    // ones, which many codecs clamp) may cost a codec very different times.
    let search = |worker: u32| {
        (worker..=u32::MAX / BLOCK)
            .step_by(2)
            .map(|block| block * BLOCK)
            .find(|&first| block_differs(first))
            .and_then(|first| (first..=first + (BLOCK - 1)).find_map(first_failure))
    };
    let failure = std::thread::scope(|scope| {
        let workers: Vec<_> = [0, 1]
            .into_iter()
            .map(|worker| scope.spawn(move || search(worker)))
            .collect();
        workers
            .into_iter()
            .find_map(|worker| worker.join().expect("a worker finishes"))
    });
    assert_eq!(failure, None);
}

/// The exhaustive check itself: one wrong code among the 2^32 f32s fails it, and the failure
/// names that f32 (not the block it lies in).
#[cfg(test)]
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "exhaustive: run optimised, `cargo test --release -p gbuffer-core --lib every_f32`"
)]
#[should_panic(expected = "1.0000001e0 (0x3f800001) as wrong of 8 bits: 0x1, reference 0x0")]
fn every_f32_names_the_one_value_that_differs() {
    assert_every_f32(
        "wrong",
        &[4, 8],
        |value, bits| u32::from(bits == 8 && value.to_bits() == 0x3f80_0001),
        |_, _| 0,
    );
}

impl Encoding {
    /// Every codec's name as layout files and the derive spell it (rgbm takes a range).
    pub fn names() -> Vec<&'static str> {
        Encoding::CODECS.iter().map(|codec| codec.name).collect()
    }

    /// The codec's name: `unorm`, `octahedral`, `rgbm`, ...
    pub fn name(self) -> &'static str {
        self.codec().name
    }

    /// The scalar kind of the fields it holds.
    pub fn scalar_kind(self) -> ScalarKind {
        self.codec().scalar_kind
    }

    /// Whether it has a fast form ([`Codec::has_fast_form`]).
    pub fn has_fast_form(self) -> bool {
        self.codec().has_fast_form
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
