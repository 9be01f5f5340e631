//! What the codecs' WGSL is written with: the placeholders of their helper templates, the
//! lanes a helper works on, and the pieces a bit field's functions are made of.
//!
//! A helper template is WGSL with placeholders: `PREFIX` (the layout's snake_case name, so
//! that several layouts' code can share one module), `LANES` (`f32`, `f32x2`, ... in helper
//! names; no name may end in a digit, which naga_oil refuses), and `UINTS`, `SINTS`, `FLOATS`
//! (the scalar or vector types of those lanes). One instruction converts every lane.

use super::max_code;

/// The lanes a helper works on: a scalar for one, a vector for several.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Lanes(pub usize);

impl Lanes {
    /// The lane count's name in helper names: `f32`, `f32x2`, `f32x3`, `f32x4`.
    pub fn name(self) -> String {
        match self.0 {
            1 => "f32".to_string(),
            n => format!("f32x{n}"),
        }
    }

    /// The name of helper `name` (`to_unorm`) for these lanes, as a template spells it
    /// `PREFIX_LANES_<name>` and [`Lanes::fill`] fills it: `<prefix>_<lanes>_<name>`
    /// (`mobile_metallic_f32x4_to_unorm`). What calls a template's helper from outside it names
    /// it here, with the helper's constant beside its template (`unorm::ENCODE_HELPER`).
    pub fn helper(self, prefix: &str, name: &str) -> String {
        format!("{prefix}_{}_{name}", self.name())
    }

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

    /// `template` with its placeholders filled for these lanes.
    pub fn fill(self, template: &str, prefix: &str) -> String {
        template
            .replace("PREFIX", prefix)
            .replace("LANES", &self.name())
            .replace("SINTS", &self.of("i32"))
            .replace("FLOATS", &self.of("f32"))
            .replace("UINTS", &self.of("u32"))
    }
}

/// A bit field as its codec's WGSL sees it.
#[derive(Clone, Copy, Debug)]
pub struct BitField<'a> {
    /// The layout's prefix for helper names.
    pub prefix: &'a str,
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
}

#[cfg(test)]
mod tests {
    use super::super::{half, small_float, unorm, unsigned_float};
    use super::Lanes;

    /// The helpers' names that callers outside the templates use are the ones the templates
    /// define, once filled.
    #[test]
    fn the_named_helpers_are_the_ones_the_templates_define() {
        for lanes in (1..=4).map(Lanes) {
            let defines = |text: &str, name: &str| {
                let definition = format!("fn {}(", lanes.helper("p", name));
                assert!(text.contains(&definition), "{definition} in:\n{text}");
            };
            defines(&lanes.fill(unorm::WGSL_ENCODE, "p"), unorm::ENCODE_HELPER);
            let mantissas = vec![10; lanes.0];
            let helpers = |name, wrapper| small_float::wgsl_helpers("p", name, wrapper, &mantissas);
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
