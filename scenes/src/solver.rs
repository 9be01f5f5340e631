//! The layout solver: the smallest layout that stores what a scene needs at the precision it
//! asks for, within its budget.
//!
//! For each stored quantity the candidates are the encodings that meet its precision (for each
//! family, the narrowest that does and the wider ones a native format stores); the solver tries
//! every combination, places the pieces in 32-bit words (unorm pieces by an exhaustive bin
//! packing, in a native format where their widths match one, else in an `r32ui` word split
//! into bit fields), and keeps the combination with, in this order: the fewest words, the
//! fewest `r32ui` words (bit fields and rgb9e5 cost shader instructions where native formats
//! convert in hardware), the most precision
//! (the least sum of predicted over allowed error). Ties go to the first found: the search
//! order is fixed, so the result is deterministic.

use std::collections::HashMap;
use std::fmt;

use gbuffer_codegen::{Field, FieldType, Format, Layout};

use crate::description::{DescriptionError, Feature, SceneDescription, Setting};
use crate::encoding::{Encoding, Part};
use crate::quantity::{stored_quantities, Kind, Quantity, Stored};

/// Where one piece of a quantity lives in its word.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Slot {
    /// The whole word.
    Word,
    /// These channels of a native format (0 = r), one per component.
    Channels(Vec<usize>),
    /// Bit fields of an `r32ui` word: (offset, width) per component.
    Bits(Vec<(u32, u32)>),
}

/// A piece of a quantity: its field (word) and slot.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The layout field (word) it is in.
    pub field: usize,
    /// Where in the word.
    pub slot: Slot,
}

/// How the solution stores one quantity.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The quantity stored.
    pub quantity: Quantity,
    /// How it is encoded.
    pub encoding: Encoding,
    /// The features that read it.
    pub needed_by: Vec<Feature>,
    /// The error bound of the encoding, in the unit of the quantity's kind.
    pub predicted_error: f64,
    /// What the scene allows, in the same unit.
    pub allowed_error: f64,
    /// One per piece of [`Encoding::parts`], in order.
    pub locations: Vec<Location>,
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

    /// `r32ui` words: bit fields or rgb9e5, converted by shader code rather than by the
    /// format.
    pub fn custom_words(&self) -> usize {
        self.layout
            .fields
            .iter()
            .filter(|field| field.format() == Some(Format::R32ui))
            .count()
    }
}

/// Why a scene has no layout.
#[derive(Clone, Debug, PartialEq)]
pub enum SolveError {
    /// The description itself is invalid.
    Description(Vec<DescriptionError>),
    /// No feature needs the G-buffer to store anything.
    NothingStored,
    /// A requirement no encoding meets, or that cannot be met within the budget.
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

/// The encodings of a quantity that meet the scene's precision: of each family, the narrowest
/// and the wider native widths.
fn candidates_meeting(quantity: Quantity, scene: &SceneDescription) -> Vec<Encoding> {
    let meeting: Vec<Encoding> = Encoding::catalogue(quantity, &scene.precision)
        .into_iter()
        .filter(|encoding| encoding.meets(quantity, &scene.precision))
        .collect();
    prune(meeting)
}

/// Keeps, of each family of widths, the narrowest and the native widths (2, 8, 10, 16): a wider
/// non-native piece can only sit in an `r32ui` word, where the narrowest fits too.
fn prune(encodings: Vec<Encoding>) -> Vec<Encoding> {
    let width = |encoding: &Encoding| match *encoding {
        Encoding::ScaledUnorm { bits, .. }
        | Encoding::NormalUnorm { bits }
        | Encoding::Octahedral { bits }
        | Encoding::PseudoGamma { bits }
        | Encoding::Unorm { bits } => Some(bits),
        _ => None,
    };
    let mut kept: Vec<Encoding> = Vec::new();
    for encoding in encodings {
        let narrowest_of_family = !kept
            .iter()
            .any(|other| std::mem::discriminant(other) == std::mem::discriminant(&encoding));
        match width(&encoding) {
            Some(bits) if !narrowest_of_family && ![2, 8, 10, 16].contains(&bits) => {}
            _ => kept.push(encoding),
        }
    }
    kept
}

/// One combination's layout: its words and its score.
#[derive(Clone, Debug)]
struct Candidate {
    encodings: Vec<Encoding>,
    words: Vec<Word>,
    custom_words: usize,
    /// Sum of predicted over allowed error.
    slack: f64,
}

/// A word of a candidate: its format and the pieces in it, as (quantity index, part index).
#[derive(Clone, Debug)]
struct Word {
    format: Format,
    pieces: Vec<(usize, usize)>,
    slots: Vec<Slot>,
}

/// Tries every combination of candidates; the best whose words fit `budget` (any, without one).
fn search(
    stored: &[Stored],
    candidates: &[Vec<Encoding>],
    scene: &SceneDescription,
    packer: &mut Packer,
    budget: Option<u32>,
) -> Option<Candidate> {
    let mut choice = vec![0usize; candidates.len()];
    let mut best: Option<Candidate> = None;
    loop {
        let encodings: Vec<Encoding> = choice
            .iter()
            .zip(candidates)
            .map(|(&index, list)| list[index])
            .collect();
        let candidate = arrange(stored, encodings, scene, packer);
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

/// Places one combination's pieces in words.
fn arrange(
    stored: &[Stored],
    encodings: Vec<Encoding>,
    scene: &SceneDescription,
    packer: &mut Packer,
) -> Candidate {
    let mut words = Vec::new();
    let mut halves = Vec::new();
    let mut unorm_pieces = Vec::new();
    for (quantity_index, (entry, encoding)) in stored.iter().zip(&encodings).enumerate() {
        for (part_index, part) in encoding.parts(entry.quantity).into_iter().enumerate() {
            let piece = (quantity_index, part_index);
            match part {
                Part::Word(format) => words.push(Word {
                    format,
                    pieces: vec![piece],
                    slots: vec![Slot::Word],
                }),
                Part::Half => halves.push(piece),
                Part::Unorm(widths) => unorm_pieces.push((piece, widths)),
            }
        }
    }
    for pair in halves.chunks(2) {
        words.push(Word {
            format: Format::Rg16f,
            pieces: pair.to_vec(),
            slots: (0..pair.len())
                .map(|channel| Slot::Channels(vec![channel]))
                .collect(),
        });
    }
    let widths: Vec<Vec<u32>> = unorm_pieces
        .iter()
        .map(|(_, widths)| widths.clone())
        .collect();
    for bin in packer.pack(&widths) {
        let bin_widths: Vec<&Vec<u32>> = bin.iter().map(|&item| &widths[item]).collect();
        let (format, slots) = place_in_word(&bin_widths);
        words.push(Word {
            format,
            pieces: bin.iter().map(|&item| unorm_pieces[item].0).collect(),
            slots,
        });
    }
    // Words in the order of the quantities they hold, light first, as the seeds order them.
    words.sort_by_key(|word| word.pieces.iter().min().copied());
    let custom_words = words
        .iter()
        .filter(|word| word.format == Format::R32ui)
        .count();
    let slack = stored
        .iter()
        .zip(&encodings)
        .map(|(entry, encoding)| {
            let allowed = Encoding::allowed_error(entry.quantity.kind(), &scene.precision);
            if allowed.is_finite() {
                encoding.predicted_error(entry.quantity, &scene.precision) / allowed
            } else {
                0.0
            }
        })
        .sum();
    Candidate {
        encodings,
        words,
        custom_words,
        slack,
    }
}

/// The native format whose channels take these unorm pieces, with each piece's channels; else
/// an `r32ui` word with each piece's bit fields, packed from bit 0 up.
fn place_in_word(pieces: &[&Vec<u32>]) -> (Format, Vec<Slot>) {
    let all_widths: Vec<u32> = pieces
        .iter()
        .flat_map(|widths| widths.iter().copied())
        .collect();
    let count = |width: u32| all_widths.iter().filter(|&&w| w == width).count();
    let sequential = |format: Format| {
        let mut next = 0;
        let slots = pieces
            .iter()
            .map(|widths| {
                let channels = (next..next + widths.len()).collect();
                next += widths.len();
                Slot::Channels(channels)
            })
            .collect();
        (format, slots)
    };
    if count(8) == all_widths.len() && all_widths.len() <= 4 {
        return sequential(Format::Rgba8);
    }
    if count(16) == all_widths.len() && all_widths.len() <= 2 {
        return sequential(Format::Rg16);
    }
    if count(10) + count(2) == all_widths.len() && count(10) <= 3 && count(2) <= 1 {
        // 10-bit components in r, g, b; a 2-bit one in a.
        let mut next_rgb = 0;
        let slots = pieces
            .iter()
            .map(|widths| {
                Slot::Channels(
                    widths
                        .iter()
                        .map(|&width| {
                            if width == 2 {
                                3
                            } else {
                                next_rgb += 1;
                                next_rgb - 1
                            }
                        })
                        .collect(),
                )
            })
            .collect();
        return (Format::Rgb10A2, slots);
    }
    let mut offset = 0;
    let slots = pieces
        .iter()
        .map(|widths| {
            Slot::Bits(
                widths
                    .iter()
                    .map(|&width| {
                        offset += width;
                        (offset - width, width)
                    })
                    .collect(),
            )
        })
        .collect();
    (Format::R32ui, slots)
}

/// Exhaustive bin packing of unorm pieces into 32-bit words: the fewest words, then the fewest
/// that no native format takes. Pieces are few (one per stored quantity at most), so every
/// assignment is tried; results are remembered per list of widths.
#[derive(Default)]
struct Packer {
    known: HashMap<Vec<Vec<u32>>, Vec<Vec<usize>>>,
}

impl Packer {
    /// Bins of item indices.
    fn pack(&mut self, items: &[Vec<u32>]) -> Vec<Vec<usize>> {
        if let Some(bins) = self.known.get(items) {
            return bins.clone();
        }
        let mut best: Option<(usize, usize, Vec<Vec<usize>>)> = None;
        let mut bins: Vec<Vec<usize>> = Vec::new();
        assign(items, 0, &mut bins, &mut best);
        let bins = best.map(|(_, _, bins)| bins).unwrap_or_default();
        self.known.insert(items.to_vec(), bins.clone());
        bins
    }
}

fn assign(
    items: &[Vec<u32>],
    next: usize,
    bins: &mut Vec<Vec<usize>>,
    best: &mut Option<(usize, usize, Vec<Vec<usize>>)>,
) {
    if best
        .as_ref()
        .is_some_and(|(count, _, _)| bins.len() > *count)
    {
        return;
    }
    let bits = |item: usize| items[item].iter().sum::<u32>();
    if next == items.len() {
        let custom = bins
            .iter()
            .filter(|bin| {
                let widths: Vec<&Vec<u32>> = bin.iter().map(|&item| &items[item]).collect();
                place_in_word(&widths).0 == Format::R32ui
            })
            .count();
        let score = (bins.len(), custom);
        if best
            .as_ref()
            .is_none_or(|(count, custom, _)| score < (*count, *custom))
        {
            *best = Some((score.0, score.1, bins.clone()));
        }
        return;
    }
    for bin in 0..bins.len() {
        let used: u32 = bins[bin].iter().map(|&item| bits(item)).sum();
        if used + bits(next) <= 32 {
            bins[bin].push(next);
            assign(items, next + 1, bins, best);
            bins[bin].pop();
        }
    }
    bins.push(vec![next]);
    assign(items, next + 1, bins, best);
    bins.pop();
}

/// The solution's layout and placements.
fn build(scene: &SceneDescription, stored: &[Stored], best: Candidate) -> Solution {
    let mut locations: Vec<Vec<(usize, Location)>> = vec![Vec::new(); stored.len()];
    let mut fields = Vec::new();
    for (field_index, word) in best.words.iter().enumerate() {
        for (&(quantity, part), slot) in word.pieces.iter().zip(&word.slots) {
            locations[quantity].push((
                part,
                Location {
                    field: field_index,
                    slot: slot.clone(),
                },
            ));
        }
        fields.push(Field {
            name: field_name(stored, &best.encodings, word),
            storage: gbuffer_codegen::Storage::Word(word.format),
            ty: field_type(word),
            conversions: None,
        });
    }
    let placements = stored
        .iter()
        .zip(&best.encodings)
        .zip(locations)
        .map(|((entry, &encoding), mut pieces)| {
            pieces.sort_by_key(|(part, _)| *part);
            Placement {
                quantity: entry.quantity,
                encoding,
                needed_by: entry.needed_by.clone(),
                predicted_error: encoding.predicted_error(entry.quantity, &scene.precision),
                allowed_error: Encoding::allowed_error(entry.quantity.kind(), &scene.precision),
                locations: pieces.into_iter().map(|(_, location)| location).collect(),
            }
        })
        .collect();
    Solution {
        scene: scene.clone(),
        layout: Layout {
            name: scene.name.clone(),
            budget: scene.budget,
            fields,
        },
        placements,
    }
}

/// A field's name from what it holds: `normal_roughness`, `light_rg`, `light_b_roughness`.
fn field_name(stored: &[Stored], encodings: &[Encoding], word: &Word) -> String {
    let mut groups: Vec<(usize, String)> = Vec::new();
    for &(quantity, part) in &word.pieces {
        let split = encodings[quantity].parts(stored[quantity].quantity).len() > 1;
        let suffix = if split {
            ["r", "g", "b"][part].to_string()
        } else {
            String::new()
        };
        match groups.last_mut() {
            Some((last, suffixes)) if *last == quantity => suffixes.push_str(&suffix),
            _ => groups.push((quantity, suffix)),
        }
    }
    groups
        .into_iter()
        .map(|(quantity, suffix)| {
            let name = stored[quantity].quantity.name();
            if suffix.is_empty() {
                name.to_string()
            } else {
                format!("{name}_{suffix}")
            }
        })
        .collect::<Vec<_>>()
        .join("_")
}

/// A field's type: as many components as its highest channel in use.
fn field_type(word: &Word) -> FieldType {
    let components = word
        .slots
        .iter()
        .map(|slot| match slot {
            Slot::Channels(channels) => channels.iter().max().map_or(1, |last| last + 1),
            Slot::Word => word.format.channels().len().min(3),
            Slot::Bits(_) => 1,
        })
        .max()
        .unwrap_or(1);
    FieldType::new(word.format.scalar_kind(), components)
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

/// The error for a quantity no encoding can store precisely enough.
fn unreachable_requirement(quantity: Quantity, scene: &SceneDescription) -> SolveError {
    let precision = &scene.precision;
    let catalogue = Encoding::catalogue(quantity, precision);
    let best = catalogue
        .into_iter()
        .filter(|encoding| quantity.kind() != Kind::Hdr || encoding.hdr_max() >= precision.hdr_max)
        .min_by(|a, b| {
            a.predicted_error(quantity, precision)
                .total_cmp(&b.predicted_error(quantity, precision))
        });
    let setting = setting_of(quantity);
    let best = best.map_or(String::new(), |encoding| {
        format!(
            "; the most precise encoding, {encoding}, is within {}",
            describe_error(quantity, encoding.predicted_error(quantity, precision))
        )
    });
    SolveError::Unmet {
        setting,
        message: format!(
            "{} needs {} but no encoding of {} is that precise{best}",
            setting.key(),
            describe_error(
                quantity,
                Encoding::allowed_error(quantity.kind(), precision)
            ),
            quantity.name(),
        ),
    }
}

/// The error when the precise enough encodings do not fit the budget: names the precision
/// setting that, relaxed alone, would fit, else the budget.
fn over_budget(
    scene: &SceneDescription,
    stored: &[Stored],
    candidates: &[Vec<Encoding>],
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
                .map(|encoding| encoding.bits(entry.quantity))
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
        relaxed[index] = prune(Encoding::catalogue(entry.quantity, &scene.precision));
        if let Some(fitting) = search(stored, &relaxed, scene, packer, Some(scene.budget)) {
            let setting = setting_of(entry.quantity);
            let loosest = fitting.encodings[index];
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
    fn native_widths_find_their_format() {
        let eights = vec![8, 8, 8];
        let one = vec![8];
        assert_eq!(place_in_word(&[&eights, &one]).0, Format::Rgba8);
        let tens = vec![10, 10, 10];
        let two = vec![2];
        let (format, slots) = place_in_word(&[&two, &tens]);
        assert_eq!(format, Format::Rgb10A2);
        assert_eq!(slots[0], Slot::Channels(vec![3]));
        let twelves = vec![12, 12];
        let (format, slots) = place_in_word(&[&twelves, &one]);
        assert_eq!(format, Format::R32ui);
        assert_eq!(slots[1], Slot::Bits(vec![(24, 8)]));
    }

    #[test]
    fn pruning_keeps_the_narrowest_and_native_widths() {
        let kept = prune((5..=16).map(|bits| Encoding::Unorm { bits }).collect());
        assert_eq!(kept, [5, 8, 10, 16].map(|bits| Encoding::Unorm { bits }));
    }

    #[test]
    fn bin_packing_prefers_native_words() {
        let mut packer = Packer::default();
        // 24 + 24 + 8 + 8: two rgba8 words, not a 24 + 8 custom split of the wrong kind.
        let items = vec![vec![8; 3], vec![8; 3], vec![8], vec![8]];
        let bins = packer.pack(&items);
        assert_eq!(bins.len(), 2);
        for bin in &bins {
            let widths: Vec<&Vec<u32>> = bin.iter().map(|&item| &items[item]).collect();
            assert_eq!(place_in_word(&widths).0, Format::Rgba8);
        }
    }
}
