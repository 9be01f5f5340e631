//! The codecs' WGSL: one file per codec, as Bevy keeps one shader file per codec, each holding
//! its helper templates and what a bit field of it calls. The contract each one keeps and its
//! Rust mirror are the codec's file of the same name in `gbuffer_core::codecs`, which states
//! the formula; the WGSL here keeps it bit for bit (exact conversions) or within the codec's
//! stated bound (fast ones), and the GPU tests hold every one against the mirror on a driver.
//!
//! A helper template is WGSL with placeholders: `PREFIX` (the layout's snake_case name, so
//! that several layouts' code can share one module), `LANES` (`f32`, `f32x2`, ... in helper
//! names, [`Symbols::lanes`]), and `UINTS`, `SINTS`, `FLOATS` (the scalar or vector types of
//! those lanes). One instruction converts every lane. What calls a helper from outside its
//! template names it through the layout's [`Symbols`] ([`Symbols::codec_helper`],
//! [`Symbols::codec_function`]), with the helper's name beside its template
//! (`unorm::ENCODE_HELPER`).
//!
//! # Adding a codec
//!
//! Beside its file in `gbuffer_core::codecs` (the contract and the mirror), write one file here
//! with its WGSL and add its arm to [`functions`].

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

use gbuffer_core::codecs::{max_code, Encoding};
use gbuffer_core::Symbols;

/// The lanes a helper works on: a scalar for one, a vector for several.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Lanes(pub usize);

impl Lanes {
    /// The WGSL type with `scalar` in every lane.
    pub fn of(self, scalar: &str) -> String {
        match self.0 {
            1 => scalar.to_string(),
            n => format!("vec{n}<{scalar}>"),
        }
    }

    /// A literal with one value per lane, e.g. `vec4<u32>(0u, 8u, 16u, 24u)`; a splat when the
    /// values agree.
    pub fn literal(self, scalar: &str, values: &[String]) -> String {
        if self.0 == 1 {
            values[0].clone()
        } else if values.iter().all(|value| *value == values[0]) {
            format!("{}({})", self.of(scalar), values[0])
        } else {
            format!("{}({})", self.of(scalar), values.join(", "))
        }
    }

    /// A splat of a `u32`: `4u` or `vec3<u32>(4u)`.
    pub fn splat(self, value: u32) -> String {
        self.literal("u32", &[format!("{value}u")])
    }

    /// A splat of an `f32`.
    pub fn splat_f32(self, value: f32) -> String {
        self.literal("f32", &[format!("{value:?}")])
    }

    /// `template` with its placeholders filled for these lanes and the names of `symbols`'
    /// layout: `PREFIX_LANES_to_unorm` becomes [`Symbols::codec_helper`]'s name.
    pub fn fill(self, template: &str, symbols: &Symbols) -> String {
        template
            .replace("PREFIX", symbols.snake())
            .replace("LANES", &Symbols::lanes(self.0))
            .replace("SINTS", &self.of("i32"))
            .replace("FLOATS", &self.of("f32"))
            .replace("UINTS", &self.of("u32"))
    }
}

/// A bit field as its codec's WGSL sees it.
#[derive(Clone, Copy, Debug)]
pub struct BitField<'a> {
    /// The layout's names: its helpers' prefix.
    pub symbols: &'a Symbols,
    /// One lane per component of the field's type.
    pub lanes: Lanes,
    /// The bits of one component's code (of one coordinate, for octahedral).
    pub each: u32,
    /// Whether the field's conversions are fast (only codecs with a fast form look).
    pub fast: bool,
    /// The codec's parameter (RGBM's range).
    pub range: Option<f32>,
}

/// A bit field's WGSL: the bodies of `fn encode(value: T) -> u32` (the code in the low bits)
/// and `fn decode(code: u32) -> T`, and the complete helper functions they call.
#[derive(Clone, Debug)]
pub struct Functions {
    /// The encode function's body.
    pub encode: String,
    /// The decode function's body.
    pub decode: String,
    /// Helper functions, each a complete text (the emitter writes each distinct text once).
    pub helpers: Vec<String>,
}

impl Functions {
    /// Functions whose bodies need no helper.
    pub fn inline(encode: &str, decode: &str) -> Functions {
        Functions {
            encode: encode.to_string(),
            decode: decode.to_string(),
            helpers: Vec::new(),
        }
    }
}

/// The WGSL of a bit field of `encoding`: each codec's file writes its own.
pub fn functions(encoding: Encoding, field: &BitField) -> Functions {
    match encoding {
        Encoding::Unorm => unorm::functions(field),
        Encoding::Snorm => snorm::functions(field),
        Encoding::Uint => integer::uint_functions(field),
        Encoding::Sint => integer::sint_functions(field),
        Encoding::Bool => boolean::functions(field),
        Encoding::Half => half::functions(field),
        Encoding::Float32 => float32::functions(field),
        Encoding::UnsignedFloat => unsigned_float::functions(field),
        Encoding::Rgb9e5 => rgb9e5::functions(field),
        Encoding::Octahedral => octahedral::functions(field),
        Encoding::Rgbm(_) => rgbm::functions(field),
        Encoding::LogLuminance => log_luminance::functions(field),
    }
}

/// Whether the WGSL of `encoding` calls `unpack2x16float` or `pack2x16float` (a decode that
/// widens its codes into binary16, a fast encode that rounds through it), which naga validates
/// only with `Capabilities::SHADER_FLOAT16_IN_FLOAT32`: the generated WGSL's header says so.
pub fn uses_binary16_builtins(encoding: Encoding) -> bool {
    matches!(encoding, Encoding::Half | Encoding::UnsignedFloat)
}

impl BitField<'_> {
    /// `codes.x | (codes.y << 8u) | ...`: per-component codes (`codes`, a vector of the
    /// field's lanes) joined into one code, x in the low bits.
    pub fn joined(&self, codes: &str) -> String {
        if self.lanes.0 == 1 {
            return codes.to_string();
        }
        let parts: Vec<String> = "xyzw"[..self.lanes.0]
            .chars()
            .enumerate()
            .map(|(index, lane)| match index {
                0 => format!("{codes}.{lane}"),
                _ => format!("({codes}.{lane} << {}u)", self.each * index as u32),
            })
            .collect();
        parts.join(" | ")
    }

    /// `let codes = ...;`: the components' codes of the field's code, one per lane.
    pub fn split_codes(&self) -> String {
        let lanes = self.lanes;
        if lanes.0 == 1 {
            return "    let codes = code;\n".to_string();
        }
        let offsets: Vec<String> = (0..lanes.0)
            .map(|index| format!("{}u", self.each * index as u32))
            .collect();
        format!(
            "    let codes = ({}(code) >> {}) & {};\n",
            lanes.of("u32"),
            lanes.literal("u32", &offsets),
            lanes.splat(max_code(self.each))
        )
    }

    /// The splat of the correctly rounded reciprocal of a `bits`-bit code's largest value.
    pub fn reciprocal(&self, bits: u32) -> String {
        self.lanes.splat_f32(1.0 / max_code(bits) as f32)
    }

    /// The name of codec helper `name` on this field's lanes ([`Symbols::codec_helper`]).
    pub fn helper(&self, name: &str) -> String {
        self.symbols.codec_helper(self.lanes.0, name)
    }

    /// `template` filled for this field's lanes and layout.
    pub fn fill(&self, template: &str) -> String {
        self.lanes.fill(template, self.symbols)
    }
}

#[cfg(test)]
mod tests {
    use super::{half, small_float, unorm, unsigned_float, Lanes};
    use gbuffer_core::Symbols;

    /// The helpers' names that callers outside the templates spell through [`Symbols`] are
    /// the ones the templates define, once filled.
    #[test]
    fn the_named_helpers_are_the_ones_the_templates_define() {
        let symbols = Symbols::new("P");
        for lanes in (1..=4).map(Lanes) {
            let defines = |text: &str, name: &str| {
                let definition = format!("fn {}(", symbols.codec_helper(lanes.0, name));
                assert!(text.contains(&definition), "{definition} in:\n{text}");
            };
            defines(
                &lanes.fill(unorm::WGSL_ENCODE, &symbols),
                unorm::ENCODE_HELPER,
            );
            let mantissas = vec![10; lanes.0];
            let helpers = |name, wrapper| small_float::helpers(&symbols, name, wrapper, &mantissas);
            defines(
                &helpers("unsigned_half", half::WGSL_ENCODE).concat(),
                half::ENCODE_HELPER,
            );
            defines(
                &helpers("unsigned_float", unsigned_float::WGSL_ENCODE).concat(),
                unsigned_float::ENCODE_HELPER,
            );
        }
    }
}
