//! The smallest layout for a Bevy scene: which of `PbrInput`'s quantities the scene uses, at
//! what precision, solved into bit fields that fill Bevy's one `Rgba32Uint` texel, or the list
//! of what must give when 128 bits cannot hold them.
//!
//! Each quantity takes the narrowest encoding that meets its precision, by the codecs' own
//! error bounds, which the main solver (`gbuffer-solver`'s `representation`) reads too:
//! half a step for unorm (`unorm::max_error`), `sqrt(18)` half-steps of a coordinate for
//! octahedral directions (`octahedral::max_error_degrees`), half an ulp of the mantissa for
//! light (`small_float::max_relative_error`, `rgb9e5::MAX_RELATIVE_ERROR`).
//! The fields are packed first-fit, largest first, into 32-bit words (no field straddles two,
//! as gbuffer's layouts place them), and printed as the `#[derive(GBufferLayout)]` to paste.

use std::fmt;

use gbuffer::codecs::{octahedral, rgb9e5, small_float, unorm};

use crate::quantity::{Quantity, Values};

/// How precisely a scene needs a quantity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Precision {
    /// Distinct levels per channel over [0, 1]: 256 is what 8 bits give.
    Steps(u32),
    /// The largest angle, in degrees, between a direction and the direction read back.
    Degrees(f64),
    /// The largest error of a light channel relative to its own value.
    Relative(f64),
    /// Exactly (flags).
    Exact,
}

/// A scene in Bevy's terms: the quantities it uses and how precisely.
#[derive(Clone, Debug, PartialEq)]
pub struct BevyScene {
    /// The layout's name.
    pub name: String,
    /// Each quantity the scene uses, with its precision.
    pub needs: Vec<(Quantity, Precision)>,
}

impl BevyScene {
    /// A scene that uses nothing yet.
    pub fn new(name: &str) -> Self {
        BevyScene {
            name: name.to_string(),
            needs: Vec::new(),
        }
    }

    /// The scene uses `quantity` at `precision`.
    pub fn needs(mut self, quantity: Quantity, precision: Precision) -> Self {
        self.needs.push((quantity, precision));
        self
    }
}

/// One field of a solved layout.
#[derive(Clone, Debug, PartialEq)]
pub struct SolvedField {
    /// The quantity, whose first name the field takes.
    pub quantity: Quantity,
    /// Its width.
    pub bits: u32,
    /// Its encoding's name, as `#[bits(...)]` spells it.
    pub encoding: &'static str,
    /// The error its encoding makes, in the unit of its precision.
    pub error: f64,
}

impl SolvedField {
    /// Its largest error as reports write it: `0.48°`, `3.1% relative`, `±0.0323`, `exact`.
    pub fn error_text(&self) -> String {
        match self.quantity.values() {
            Values::Direction => format!("{:.2}°", self.error),
            Values::Unbounded => format!("{:.1}% relative", self.error * 100.0),
            Values::Unit => format!("±{:.4}", self.error),
            Values::Bits => "exact".to_string(),
        }
    }
}

/// A solved layout: its fields in the order that packs them into `words` words.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The layout's name.
    pub name: String,
    /// The fields, word by word.
    pub fields: Vec<SolvedField>,
    /// The words they fill.
    pub words: usize,
}

impl Solution {
    /// The bits the fields use.
    pub fn bits(&self) -> u32 {
        self.fields.iter().map(|field| field.bits).sum()
    }

    /// Its bit budget as a Markdown table: each quantity's bits, encoding and largest error.
    pub fn budget_table(&self) -> String {
        let mut table = String::from(
            "| quantity | bits | encoding | largest error |\n| --- | ---: | --- | ---: |\n",
        );
        for field in &self.fields {
            table.push_str(&format!(
                "| `{}` | {} | {} | {} |\n",
                field.quantity,
                field.bits,
                field.encoding,
                field.error_text()
            ));
        }
        table.push_str(&format!("| total | {} | | |\n", self.bits()));
        table
    }

    /// The layout as a Rust declaration to paste.
    pub fn derive_source(&self) -> String {
        let mut source = format!(
            "#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]\n\
             #[gbuffer(budget = {})]\n\
             struct {} {{\n",
            self.words * 32,
            self.name
        );
        for field in &self.fields {
            source.push_str(&format!(
                "    #[bits({}, {})] {}: {},\n",
                field.bits,
                field.encoding,
                field.quantity,
                field.quantity.field_type().rust_name()
            ));
        }
        source.push_str("}\n");
        source
    }
}

/// Why a scene's quantities do not fit Bevy's 128 bits: every field with its bits, widest
/// first, which is the list of what must give.
#[derive(Clone, Debug, PartialEq)]
pub enum SolveError {
    /// The quantities need more than 4 words.
    TooWide {
        /// The layout's name.
        name: String,
        /// The narrowest field for each quantity, widest first.
        fields: Vec<SolvedField>,
        /// The words they would fill.
        words: usize,
    },
    /// A precision no encoding meets, or one of the wrong kind for its quantity.
    Unmet {
        /// The quantity.
        quantity: Quantity,
        /// Its precision.
        precision: Precision,
    },
}

impl fmt::Display for SolveError {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveError::TooWide {
                name,
                fields,
                words,
            } => {
                let bits: u32 = fields.iter().map(|field| field.bits).sum();
                writeln!(
                    out,
                    "`{name}` needs {bits} bits in {words} words; Bevy's G-buffer holds 128 in 4. \
                     What must give, widest first:"
                )?;
                for field in fields {
                    writeln!(
                        out,
                        "  {}: {} bits ({})",
                        field.quantity, field.bits, field.encoding
                    )?;
                }
                Ok(())
            }
            SolveError::Unmet {
                quantity,
                precision,
            } => write!(
                out,
                "`{quantity}` at {precision:?}: no encoding meets it (directions take degrees, \
                 light relative error, flags Exact, the rest steps of 2 to 2^16)"
            ),
        }
    }
}

impl std::error::Error for SolveError {}

/// The narrowest field for `quantity` at `precision`.
fn narrowest(quantity: Quantity, precision: Precision) -> Result<SolvedField, SolveError> {
    let components = quantity.field_type().components as u32;
    let unmet = SolveError::Unmet {
        quantity,
        precision,
    };
    let field = |bits, encoding, error| SolvedField {
        quantity,
        bits,
        encoding,
        error,
    };
    match (quantity.values(), precision) {
        (Values::Bits, Precision::Exact) => Ok(field(
            if quantity == Quantity::Flags { 3 } else { 1 },
            "uint",
            0.0,
        )),
        (Values::Unit, Precision::Steps(steps)) if (2..=1 << 16).contains(&steps) => {
            let each = u32::BITS - (steps - 1).leading_zeros();
            Ok(field(each * components, "unorm", unorm::max_error(each)))
        }
        (Values::Direction, Precision::Degrees(degrees)) => (2..=16)
            .map(|each| (each, octahedral::max_error_degrees(each)))
            .find(|(_, error)| *error <= degrees)
            .map(|(each, error)| field(2 * each, "octahedral", error))
            .ok_or(unmet),
        (Values::Unbounded, Precision::Relative(relative)) => {
            // Unsigned floats: a 5-bit exponent over m mantissa bits; rgb9e5's 9-bit
            // mantissas share the brightest channel's exponent. The bounds are the codecs'.
            let unsigned = (1..=10)
                .map(|mantissa| (mantissa, small_float::max_relative_error(mantissa)))
                .find(|(_, error)| *error <= relative)
                .map(|(mantissa, error)| {
                    field((5 + mantissa) * components, "unsigned_float", error)
                });
            let shared = (components == 3 && rgb9e5::MAX_RELATIVE_ERROR <= relative)
                .then(|| field(32, "rgb9e5", rgb9e5::MAX_RELATIVE_ERROR));
            [unsigned, shared]
                .into_iter()
                .flatten()
                .filter(|field| field.bits <= 32)
                .min_by_key(|field| field.bits)
                .ok_or(unmet)
        }
        _ => Err(unmet),
    }
}

/// The smallest layout for `scene` that fits Bevy's 128 bits, or what must give.
pub fn solve(scene: &BevyScene) -> Result<Solution, SolveError> {
    let mut fields = scene
        .needs
        .iter()
        .map(|(quantity, precision)| narrowest(*quantity, *precision))
        .collect::<Result<Vec<_>, _>>()?;
    // Widest first (stable: the scene's order among equals), then first fit into words.
    fields.sort_by_key(|field| std::cmp::Reverse(field.bits));
    let mut words: Vec<(u32, Vec<SolvedField>)> = Vec::new();
    for field in &fields {
        match words.iter_mut().find(|(used, _)| used + field.bits <= 32) {
            Some((used, members)) => {
                *used += field.bits;
                members.push(field.clone());
            }
            None => words.push((field.bits, vec![field.clone()])),
        }
    }
    if words.len() > 4 {
        return Err(SolveError::TooWide {
            name: scene.name.clone(),
            fields,
            words: words.len(),
        });
    }
    Ok(Solution {
        name: scene.name.clone(),
        words: words.len(),
        fields: words.into_iter().flat_map(|(_, members)| members).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_quantity_takes_the_narrowest_encoding_that_meets_its_precision() {
        let field = |quantity, precision| narrowest(quantity, precision).unwrap();
        // 8 bits give 256 levels, and 257 need 9.
        assert_eq!(field(Quantity::Metallic, Precision::Steps(256)).bits, 8);
        assert_eq!(field(Quantity::Metallic, Precision::Steps(257)).bits, 9);
        assert_eq!(field(Quantity::BaseColor, Precision::Steps(64)).bits, 18);
        // Octahedral 2 x 12 bits: sqrt(18) / 4095 radians, 0.059 degrees.
        let normal = field(Quantity::Normal, Precision::Degrees(0.06));
        assert_eq!((normal.bits, normal.encoding), (24, "octahedral"));
        assert!((normal.error - 0.05936).abs() < 1e-4);
        // Light within 2%: 5 mantissa bits per channel (30) beat rgb9e5 (32); within 0.2%,
        // only rgb9e5's shared 9-bit mantissas (32) fit a word.
        let light = field(Quantity::Emissive, Precision::Relative(0.02));
        assert_eq!((light.bits, light.encoding), (30, "unsigned_float"));
        let light = field(Quantity::Emissive, Precision::Relative(0.002));
        assert_eq!((light.bits, light.encoding), (32, "rgb9e5"));
        assert_eq!(field(Quantity::Lightmapped, Precision::Exact).bits, 1);
        assert_eq!(field(Quantity::Flags, Precision::Exact).bits, 3);
    }

    #[test]
    fn a_precision_of_the_wrong_kind_or_too_fine_is_unmet() {
        for (quantity, precision) in [
            (Quantity::Normal, Precision::Steps(256)),
            (Quantity::Normal, Precision::Degrees(0.0001)),
            (Quantity::Emissive, Precision::Relative(0.0001)),
            (Quantity::Metallic, Precision::Steps(1)),
        ] {
            assert_eq!(
                narrowest(quantity, precision),
                Err(SolveError::Unmet {
                    quantity,
                    precision
                })
            );
        }
    }

    #[test]
    fn a_scene_over_128_bits_lists_what_must_give() {
        let scene = BevyScene::new("Everything")
            .needs(Quantity::BaseColor, Precision::Steps(256))
            .needs(Quantity::PerceptualRoughness, Precision::Steps(256))
            .needs(Quantity::Emissive, Precision::Relative(0.002))
            .needs(Quantity::Normal, Precision::Degrees(0.06))
            .needs(Quantity::ClearcoatNormal, Precision::Degrees(0.06))
            .needs(Quantity::ReflectanceColor, Precision::Steps(256));
        let error = solve(&scene).unwrap_err();
        assert_eq!(
            error.to_string(),
            "`Everything` needs 136 bits in 5 words; Bevy's G-buffer holds 128 in 4. What must \
             give, widest first:\n  emissive: 32 bits (rgb9e5)\n  base_color: 24 bits (unorm)\n  \
             normal: 24 bits (octahedral)\n  clearcoat_normal: 24 bits (octahedral)\n  \
             reflectance_color: 24 bits (unorm)\n  perceptual_roughness: 8 bits (unorm)\n"
        );
        // No field straddles two words: a 16-bit clearcoat normal brings the bits to 128, but
        // beside three 24-bit fields it takes a fifth word. Giving it up fits in four.
        let mut coarser = scene.clone();
        coarser.needs[4].1 = Precision::Degrees(1.0);
        assert!(matches!(
            solve(&coarser),
            Err(SolveError::TooWide { words: 5, .. })
        ));
        let mut fewer = scene.clone();
        fewer.needs.remove(4);
        let solution = solve(&fewer).unwrap();
        assert_eq!((solution.bits(), solution.words), (112, 4));
        assert!(solution.derive_source().starts_with(
            "#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]\n#[gbuffer(budget = 128)]\n\
             struct Everything {\n    #[bits(32, rgb9e5)] emissive: Vec3,\n"
        ));
    }
}
