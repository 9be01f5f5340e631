//! The layout solver: the smallest layout that stores what a scene needs at the precision it
//! asks for, within its budget, in the layout vocabulary the derive and layout files speak.
//!
//! Each stored quantity becomes one field: a whole word of a format (depth in `r32f`, light in
//! `r11f_g11f_b10f`, a colour alone in `rgba8`) or a bit field (octahedral normals, rgb9e5 and
//! RGBM light, unorm colours and scalars, half scalars). For each quantity the candidates are
//! the representations that meet its precision (of each family the narrowest, and the wider ones a
//! format stores natively); the solver tries every combination, packs the bit fields into
//! `r32ui` words by an exhaustive bin packing, and keeps the combination with, in this order:
//! the fewest words, the fewest `r32ui` words (bit fields cost shader instructions where
//! native formats convert in hardware), the most precision (the least sum of predicted over
//! allowed error). Ties go to the first found: the search order is fixed, so the result is
//! deterministic. The solution is an ordinary [`Layout`]: [`Solution::layout_file`] and
//! [`Solution::derive_source`] write it out, and its mirror is the solver's.

use std::collections::HashMap;
use std::fmt;

use gbuffer_core::Named;
use gbuffer_core::{Conversions, Field, Layout, Storage};

use crate::description::{DescriptionError, Feature, SceneDescription, Setting};
use crate::quantity::{stored_quantities, Kind, Quantity, Stored};
use crate::representation::Representation;

/// How the solution stores one quantity.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The quantity stored.
    pub quantity: Quantity,
    /// How it is encoded.
    pub representation: Representation,
    /// The features that read it.
    pub needed_by: Vec<Feature>,
    /// The error bound of the representation, in the unit of the quantity's kind.
    pub predicted_error: f64,
    /// What the scene allows, in the same unit.
    pub allowed_error: f64,
    /// The layout fields that store it, one per [`Representation::pieces`].
    pub fields: Vec<usize>,
}

/// A solved scene: an ordinary layout and where each quantity lives in it.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The scene solved for.
    pub scene: SceneDescription,
    /// The layout that stores it.
    pub layout: Layout,
    /// Where each stored quantity lives, in the order they are stored.
    pub placements: Vec<Placement>,
}

impl Solution {
    /// Where `quantity` is stored, if the scene stores it.
    pub fn placement(&self, quantity: Quantity) -> Option<&Placement> {
        self.placements
            .iter()
            .find(|placement| placement.quantity == quantity)
    }

    /// `r32ui` words of bit fields, converted by shader code rather than by a format.
    pub fn custom_words(&self) -> usize {
        self.layout
            .word_contents()
            .iter()
            .filter(|word| word.is_bit_fields)
            .count()
    }

    /// The solved layout as a layout file (`gbuffer codegen` reads it back as this layout).
    pub fn layout_file(&self) -> String {
        format!(
            "# Solved by gbuffer for scene `{}`.\n{}",
            self.scene.name,
            gbuffer_layout_file::to_toml(&self.layout, Conversions::Exact)
        )
    }

    /// The solved layout as Rust source that derives it (`#[derive(GBufferLayout)]`).
    pub fn derive_source(&self) -> String {
        format!(
            "// Solved by gbuffer for scene `{}`.\n{}",
            self.scene.name,
            gbuffer_codegen::emit::rust::derive_source(&self.layout, Conversions::Exact)
        )
    }
}

/// Why a scene has no layout.
#[derive(Clone, Debug, PartialEq)]
pub enum SolveError {
    /// The description itself is invalid.
    Description(Vec<DescriptionError>),
    /// No feature needs the G-buffer to store anything.
    NothingStored,
    /// A requirement no representation meets, or that cannot be met within the budget.
    Unmet {
        /// The setting that cannot be met.
        setting: Setting,
        /// Why, with the figures.
        message: String,
    },
}

impl fmt::Display for SolveError {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveError::Description(errors) => {
                let messages: Vec<&str> = errors.iter().map(|e| e.message.as_str()).collect();
                write!(out, "{}", messages.join("; "))
            }
            SolveError::NothingStored => write!(
                out,
                "the scene stores nothing: no feature reads the G-buffer (enable the sun, point \
                 lights, image-based lighting, light maps or emissive surfaces)"
            ),
            SolveError::Unmet { setting, message } => {
                write!(out, "`{}` cannot be met: {message}", setting.key())
            }
        }
    }
}

impl std::error::Error for SolveError {}

/// Solves a scene.
pub fn solve(scene: &SceneDescription) -> Result<Solution, SolveError> {
    let errors = scene.check();
    if !errors.is_empty() {
        return Err(SolveError::Description(errors));
    }
    let stored = stored_quantities(scene);
    if stored.is_empty() {
        return Err(SolveError::NothingStored);
    }
    let mut candidates = Vec::new();
    for entry in &stored {
        let meeting = candidates_meeting(entry.quantity, scene);
        if meeting.is_empty() {
            return Err(unreachable_requirement(entry.quantity, scene));
        }
        candidates.push(meeting);
    }
    let mut packer = Packer::default();
    match search(&stored, &candidates, scene, &mut packer, Some(scene.budget)) {
        Some(best) => Ok(build(scene, &stored, best)),
        None => Err(over_budget(scene, &stored, &candidates, &mut packer)),
    }
}

/// The representations of a quantity that meet the scene's precision: of each family, the narrowest
/// and the wider native widths.
fn candidates_meeting(quantity: Quantity, scene: &SceneDescription) -> Vec<Representation> {
    let meeting: Vec<Representation> = Representation::catalogue(quantity, &scene.precision)
        .into_iter()
        .filter(|representation| representation.meets(quantity, &scene.precision))
        .collect();
    prune(meeting)
}

/// Keeps, of each family of widths, the narrowest: a wider bit field takes more of its word
/// and is no cheaper to convert. Whole-word representations all stay.
fn prune(representations: Vec<Representation>) -> Vec<Representation> {
    let mut kept: Vec<Representation> = Vec::new();
    for representation in representations {
        let family = |representation: &Representation| match representation {
            Representation::Octahedral { .. } => Some((0, None)),
            Representation::Unorm { .. } => Some((1, None)),
            Representation::Light { encoding, .. } => Some((2, Some(*encoding))),
            _ => None,
        };
        let widened = family(&representation)
            .is_some_and(|mine| kept.iter().any(|other| family(other) == Some(mine)));
        if !widened {
            kept.push(representation);
        }
    }
    kept
}

/// One combination's layout: the pieces in each word, and its score.
#[derive(Clone, Debug)]
struct Candidate {
    representations: Vec<Representation>,
    /// Per word, the pieces it holds as (quantity index, piece index): one for a whole word.
    words: Vec<Vec<(usize, usize)>>,
    custom_words: usize,
    /// Sum of predicted over allowed error.
    slack: f64,
}

/// Tries every combination of candidates; the best whose words fit `budget` (any, without one).
fn search(
    stored: &[Stored],
    candidates: &[Vec<Representation>],
    scene: &SceneDescription,
    packer: &mut Packer,
    budget: Option<u32>,
) -> Option<Candidate> {
    let mut choice = vec![0usize; candidates.len()];
    let mut best: Option<Candidate> = None;
    loop {
        let representations: Vec<Representation> = choice
            .iter()
            .zip(candidates)
            .map(|(&index, list)| list[index])
            .collect();
        let candidate = arrange(stored, representations, scene, packer);
        let fits = budget.is_none_or(|bits| 32 * candidate.words.len() as u32 <= bits);
        if fits && best.as_ref().is_none_or(|best| better(&candidate, best)) {
            best = Some(candidate);
        }
        // The next combination, odometer style; done when every digit wrapped.
        let mut digit = 0;
        loop {
            if digit == choice.len() {
                return best;
            }
            choice[digit] += 1;
            if choice[digit] < candidates[digit].len() {
                break;
            }
            choice[digit] = 0;
            digit += 1;
        }
    }
}

fn better(candidate: &Candidate, best: &Candidate) -> bool {
    (candidate.words.len(), candidate.custom_words) < (best.words.len(), best.custom_words)
        || ((candidate.words.len(), candidate.custom_words)
            == (best.words.len(), best.custom_words)
            && candidate.slack < best.slack)
}

/// Places one combination's fields in words: a whole word each, and the bit fields packed
/// into as few `r32ui` words as hold them.
fn arrange(
    stored: &[Stored],
    representations: Vec<Representation>,
    scene: &SceneDescription,
    packer: &mut Packer,
) -> Candidate {
    let mut words = Vec::new();
    let mut bit_fields = Vec::new();
    for (index, (entry, representation)) in stored.iter().zip(&representations).enumerate() {
        for (part, piece) in representation
            .pieces(entry.quantity)
            .into_iter()
            .enumerate()
        {
            match piece.storage {
                Storage::Word(_) => words.push(vec![(index, part)]),
                Storage::Bits(field) => bit_fields.push(((index, part), field.bits)),
            }
        }
    }
    let widths: Vec<u32> = bit_fields.iter().map(|&(_, bits)| bits).collect();
    let bins = packer.pack(&widths);
    let custom_words = bins.len();
    for bin in bins {
        words.push(bin.iter().map(|&item| bit_fields[item].0).collect());
    }
    // Words in the order of the quantities they hold, light first, as the seeds order them.
    words.sort_by_key(|word| word.iter().min().copied());
    let slack = stored
        .iter()
        .zip(&representations)
        .map(|(entry, representation)| {
            let allowed = Representation::allowed_error(entry.quantity.kind(), &scene.precision);
            if allowed.is_finite() {
                representation.predicted_error(entry.quantity, &scene.precision) / allowed
            } else {
                0.0
            }
        })
        .sum();
    Candidate {
        representations,
        words,
        custom_words,
        slack,
    }
}

/// Exhaustive bin packing of bit fields into 32-bit words: the fewest words. Fields are few
/// (one per stored quantity at most), so every assignment is tried; results are remembered per
/// list of widths.
#[derive(Default)]
struct Packer {
    known: HashMap<Vec<u32>, Vec<Vec<usize>>>,
}

impl Packer {
    /// Bins of item indices, each item's index in ascending order within its bin.
    fn pack(&mut self, items: &[u32]) -> Vec<Vec<usize>> {
        if let Some(bins) = self.known.get(items) {
            return bins.clone();
        }
        let mut best: Option<Vec<Vec<usize>>> = None;
        let mut bins: Vec<Vec<usize>> = Vec::new();
        assign(items, 0, &mut bins, &mut best);
        let bins = best.unwrap_or_default();
        self.known.insert(items.to_vec(), bins.clone());
        bins
    }
}

fn assign(
    items: &[u32],
    next: usize,
    bins: &mut Vec<Vec<usize>>,
    best: &mut Option<Vec<Vec<usize>>>,
) {
    if best.as_ref().is_some_and(|best| bins.len() >= best.len()) {
        return;
    }
    if next == items.len() {
        *best = Some(bins.clone());
        return;
    }
    for bin in 0..bins.len() {
        let used: u32 = bins[bin].iter().map(|&item| items[item]).sum();
        if used + items[next] <= 32 {
            bins[bin].push(next);
            assign(items, next + 1, bins, best);
            bins[bin].pop();
        }
    }
    bins.push(vec![next]);
    assign(items, next + 1, bins, best);
    bins.pop();
}

/// The solution's layout and placements: a field per piece, named for its quantity, in word
/// order. The bit fields of one bin are consecutive, so they fill one `r32ui` word (a bin's
/// first field may join the word before, which only saves a word: the solver's count is a
/// bound).
fn build(scene: &SceneDescription, stored: &[Stored], best: Candidate) -> Solution {
    let mut fields = Vec::new();
    let mut fields_of: Vec<Vec<(usize, usize)>> = vec![Vec::new(); stored.len()];
    for &(quantity, part) in best.words.iter().flatten() {
        let entry = &stored[quantity];
        let piece = best.representations[quantity].pieces(entry.quantity)[part];
        fields_of[quantity].push((part, fields.len()));
        let name = entry.quantity.name();
        fields.push(Field {
            name: if piece.suffix.is_empty() {
                name.to_string()
            } else {
                format!("{name}_{}", piece.suffix)
            },
            storage: piece.storage,
            ty: piece.ty,
            conversions: None,
        });
    }
    let placements = stored
        .iter()
        .zip(&best.representations)
        .zip(fields_of)
        .map(|((entry, &representation), mut pieces)| {
            pieces.sort_unstable();
            Placement {
                quantity: entry.quantity,
                representation,
                needed_by: entry.needed_by.clone(),
                predicted_error: representation.predicted_error(entry.quantity, &scene.precision),
                allowed_error: Representation::allowed_error(
                    entry.quantity.kind(),
                    &scene.precision,
                ),
                fields: pieces.into_iter().map(|(_, field)| field).collect(),
            }
        })
        .collect();
    let layout = Layout {
        name: scene.name.clone(),
        budget: scene.budget,
        fields,
    };
    debug_assert!(layout.words() <= best.words.len());
    Solution {
        scene: scene.clone(),
        layout,
        placements,
    }
}

/// The setting that governs a quantity's precision.
fn setting_of(quantity: Quantity) -> Setting {
    match quantity.kind() {
        Kind::Hdr => Setting::HdrRelative,
        Kind::Direction => Setting::NormalDegrees,
        Kind::Colour => Setting::ColourSteps,
        Kind::Scalar | Kind::Distance => Setting::MaterialSteps,
    }
}

/// The error for a quantity no representation can store precisely enough.
fn unreachable_requirement(quantity: Quantity, scene: &SceneDescription) -> SolveError {
    let precision = &scene.precision;
    let catalogue = Representation::catalogue(quantity, precision);
    let best = catalogue
        .into_iter()
        .filter(|representation| {
            quantity.kind() != Kind::Hdr || representation.hdr_max() >= precision.hdr_max
        })
        .min_by(|a, b| {
            a.predicted_error(quantity, precision)
                .total_cmp(&b.predicted_error(quantity, precision))
        });
    let setting = setting_of(quantity);
    let best = best.map_or(String::new(), |representation| {
        format!(
            "; the most precise representation, {representation}, is within {}",
            describe_error(
                quantity,
                representation.predicted_error(quantity, precision)
            )
        )
    });
    SolveError::Unmet {
        setting,
        message: format!(
            "{} needs {} but no representation of {} is that precise{best}",
            setting.key(),
            describe_error(
                quantity,
                Representation::allowed_error(quantity.kind(), precision)
            ),
            quantity.name(),
        ),
    }
}

/// The error when the precise enough representations do not fit the budget: names the precision
/// setting that, relaxed alone, would fit, else the budget.
fn over_budget(
    scene: &SceneDescription,
    stored: &[Stored],
    candidates: &[Vec<Representation>],
    packer: &mut Packer,
) -> SolveError {
    let smallest = search(stored, candidates, scene, packer, None)
        .map_or(0, |candidate| 32 * candidate.words.len() as u32);
    let breakdown: Vec<String> = stored
        .iter()
        .zip(candidates)
        .map(|(entry, list)| {
            let bits = list
                .iter()
                .map(|representation| representation.bits(entry.quantity))
                .min()
                .unwrap_or(0);
            format!("{} {bits}", entry.quantity.name())
        })
        .collect();
    for (index, entry) in stored.iter().enumerate() {
        if entry.quantity.kind() == Kind::Distance {
            continue;
        }
        let mut relaxed = candidates.to_vec();
        relaxed[index] = prune(Representation::catalogue(entry.quantity, &scene.precision));
        if let Some(fitting) = search(stored, &relaxed, scene, packer, Some(scene.budget)) {
            let setting = setting_of(entry.quantity);
            let loosest = fitting.representations[index];
            return SolveError::Unmet {
                setting,
                message: format!(
                    "{} = {} makes the layout {smallest} bits (pieces of at least: {}) but the \
                     budget is {}; {} within {} would fit ({loosest})",
                    setting.key(),
                    setting_value(scene, setting),
                    breakdown.join(" + "),
                    scene.budget,
                    entry.quantity.name(),
                    describe_error(
                        entry.quantity,
                        loosest.predicted_error(entry.quantity, &scene.precision)
                    ),
                ),
            };
        }
    }
    let needed_by: Vec<String> = stored
        .iter()
        .map(|entry| {
            let features: Vec<&str> = entry.needed_by.iter().map(|f| f.name()).collect();
            format!("{} (for {})", entry.quantity.name(), features.join(", "))
        })
        .collect();
    SolveError::Unmet {
        setting: Setting::Budget,
        message: format!(
            "the scene needs {smallest} bits at the least but the budget is {}: it stores {}; \
             no single precision setting relaxed would fit, so drop features or raise the budget",
            scene.budget,
            needed_by.join(", ")
        ),
    }
}

fn setting_value(scene: &SceneDescription, setting: Setting) -> String {
    let precision = &scene.precision;
    match setting {
        Setting::NormalDegrees => precision.normal_degrees.to_string(),
        Setting::ColourSteps => precision.colour_steps.to_string(),
        Setting::MaterialSteps => precision.material_steps.to_string(),
        Setting::HdrRelative => precision.hdr_relative.to_string(),
        Setting::HdrMax => precision.hdr_max.to_string(),
        Setting::HdrMin => precision.hdr_min.to_string(),
        Setting::Budget => scene.budget.to_string(),
        Setting::Name => scene.name.clone(),
    }
}

/// An error in words: "0.389 degrees", "1.96e-3 (256 steps)", "2.000% of the brightest channel".
pub fn describe_error(quantity: Quantity, error: f64) -> String {
    match quantity.kind() {
        Kind::Direction => format!("{error:.3} degrees"),
        Kind::Colour | Kind::Scalar => {
            format!("{error:.2e} ({} steps)", (0.5 / error + 1.0).round())
        }
        Kind::Hdr => format!("{:.3}% of the brightest channel", error * 100.0),
        Kind::Distance => format!("{error:.1e} relative"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pruning_keeps_the_narrowest_bit_field_and_every_word() {
        let kept = prune(
            (5..=16)
                .map(|bits| Representation::Unorm { bits })
                .chain([Representation::UnormWord {
                    format: gbuffer_core::Format::Rgba8,
                }])
                .collect(),
        );
        assert_eq!(
            kept,
            [
                Representation::Unorm { bits: 5 },
                Representation::UnormWord {
                    format: gbuffer_core::Format::Rgba8
                }
            ]
        );
    }

    #[test]
    fn bin_packing_finds_the_fewest_words() {
        let mut packer = Packer::default();
        // 20 + 12 and 24 + 8 fill two words exactly; first fit in this order would take three.
        let bins = packer.pack(&[20, 24, 12, 8]);
        assert_eq!(bins.len(), 2);
        for bin in &bins {
            assert_eq!(
                bin.iter().map(|&item| [20, 24, 12, 8][item]).sum::<u32>(),
                32
            );
        }
    }
}
