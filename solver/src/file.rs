//! Scene descriptions in TOML.
//!
//! ```toml
//! name = "MobileScene"      # the solved layout's name, UpperCamelCase
//! model = "metallic"        # or "specular"; optional, "metallic" by default
//! budget = 128              # bits; optional, 128 by default
//!
//! [features]                # a feature not named here is off
//! metals = true
//! normal_maps = true
//! image_based_lighting = true
//! light_maps = true
//! sun = true
//!
//! [precision]               # optional; each key defaults as `Precision::default()`
//! normal_degrees = 0.5
//! colour_steps = 256
//! material_steps = 256
//! hdr_max = 8.0
//! hdr_min = 0.015625
//! hdr_relative = 0.02
//! ```
//!
//! Every problem, from TOML syntax to a requirement the solver cannot meet, is a
//! [`FileDiagnostic`] at the file, line and column of the key or value it is about.

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::Path;

use gbuffer_core::Named;
use gbuffer_files::toml_table::{self, Entry, ShapeError, Table};
use gbuffer_layout_file::{FileDiagnostic, FileError};
use toml::de::{DeTable, DeValue};
use toml::Spanned;

use crate::description::{
    Feature, Features, MaterialModel, Precision, SceneDescription, Setting, DEFAULT_BUDGET,
};
use crate::solver::{solve, Solution, SolveError};

/// A scene file's keys, as written.
struct SceneEntry {
    name: Spanned<String>,
    model: Option<Spanned<String>>,
    budget: Option<Spanned<u32>>,
    /// `[features]`: each key and whether it is on, in file order.
    features: Option<Spanned<Vec<Entry<bool>>>>,
    precision: Option<Spanned<PrecisionEntry>>,
}

/// The `[precision]` table's keys, as written.
struct PrecisionEntry {
    normal_degrees: Option<Spanned<f64>>,
    colour_steps: Option<Spanned<u32>>,
    material_steps: Option<Spanned<u32>>,
    hdr_max: Option<Spanned<f64>>,
    hdr_min: Option<Spanned<f64>>,
    hdr_relative: Option<Spanned<f64>>,
}

impl SceneEntry {
    /// The file's keys, checked for their names and types.
    fn read(document: &Spanned<DeTable<'_>>) -> Result<SceneEntry, ShapeError> {
        let keys = ["name", "model", "budget", "features", "precision"];
        let table = Table::root(document, &keys)?;
        let features = match table.value("features") {
            Some(value) => Some(Spanned::new(
                value.span(),
                Table::with_any_keys(value)?.entries()?,
            )),
            None => None,
        };
        let precision = match table.value("precision") {
            Some(value) => Some(Spanned::new(value.span(), PrecisionEntry::read(value)?)),
            None => None,
        };
        Ok(SceneEntry {
            name: table.required("name")?,
            model: table.optional("model")?,
            budget: table.optional("budget")?,
            features,
            precision,
        })
    }
}

impl PrecisionEntry {
    /// The `[precision]` table's keys, checked for their names and types.
    fn read(value: &Spanned<DeValue<'_>>) -> Result<PrecisionEntry, ShapeError> {
        let keys = [
            "normal_degrees",
            "colour_steps",
            "material_steps",
            "hdr_max",
            "hdr_min",
            "hdr_relative",
        ];
        let table = Table::new(value, &keys)?;
        Ok(PrecisionEntry {
            normal_degrees: table.optional("normal_degrees")?,
            colour_steps: table.optional("colour_steps")?,
            material_steps: table.optional("material_steps")?,
            hdr_max: table.optional("hdr_max")?,
            hdr_min: table.optional("hdr_min")?,
            hdr_relative: table.optional("hdr_relative")?,
        })
    }
}

/// A parsed scene file: the description and where each setting was written.
struct Parsed {
    scene: SceneDescription,
    spans: BTreeMap<&'static str, Range<usize>>,
}

impl Parsed {
    /// Where a diagnostic about `setting` points: its value, else the name.
    fn span_of(&self, setting: Setting) -> Range<usize> {
        self.spans
            .get(setting.key())
            .or_else(|| self.spans.get("name"))
            .cloned()
            .unwrap_or(0..0)
    }
}

/// Reads a scene file and solves it.
pub fn read_and_solve(path: &Path) -> Result<Solution, FileError> {
    FileError::read(path, "scene file", parse_and_solve)
}

/// Parses and checks scene-file text; `path` names it in diagnostics.
pub fn parse_scene(source: &str, path: &Path) -> Result<SceneDescription, Vec<FileDiagnostic>> {
    parse(source, path).map(|parsed| parsed.scene)
}

/// Parses and solves scene-file text: a requirement the solver cannot meet points at its key.
pub fn parse_and_solve(source: &str, path: &Path) -> Result<Solution, Vec<FileDiagnostic>> {
    let parsed = parse(source, path)?;
    solve(&parsed.scene).map_err(|error| {
        let span = match &error {
            SolveError::Unmet { setting, .. } => parsed.span_of(*setting),
            SolveError::NothingStored => parsed
                .spans
                .get("features")
                .or_else(|| parsed.spans.get("name"))
                .cloned()
                .unwrap_or(0..0),
            SolveError::Description(_) => parsed.span_of(Setting::Name),
        };
        vec![FileDiagnostic::at(path, source, span, error.to_string())]
    })
}

fn parse(source: &str, path: &Path) -> Result<Parsed, Vec<FileDiagnostic>> {
    let entry = toml_table::parse(source)
        .and_then(|document| SceneEntry::read(&document))
        .map_err(|error| vec![FileDiagnostic::from_shape(path, source, &error)])?;
    let mut diagnostics = Vec::new();
    let mut spans = BTreeMap::new();
    spans.insert("name", entry.name.span());

    let model = match &entry.model {
        None => MaterialModel::Metallic,
        Some(model) => MaterialModel::from_name(model.get_ref()).unwrap_or_else(|| {
            diagnostics.push(FileDiagnostic::at(
                path,
                source,
                model.span(),
                format!(
                    "unknown material model `{}`: expected \"metallic\" or \"specular\"",
                    model.get_ref()
                ),
            ));
            MaterialModel::Metallic
        }),
    };

    let mut features = Features::NONE;
    if let Some(table) = &entry.features {
        spans.insert("features", table.span());
        for (key, enabled) in table.get_ref() {
            match Feature::from_name(key.get_ref()) {
                Some(feature) if *enabled.get_ref() => features = features.with(feature),
                Some(_) => {}
                None => {
                    let names = Feature::names();
                    diagnostics.push(FileDiagnostic::at(
                        path,
                        source,
                        key.span(),
                        format!(
                            "unknown feature `{}`; the features are: {}",
                            key.get_ref(),
                            names.join(", ")
                        ),
                    ));
                }
            }
        }
    }

    let mut precision = Precision::default();
    if let Some(entry) = &entry.precision {
        let entry = entry.get_ref();
        let mut float = |setting: Setting, value: &Option<Spanned<f64>>, target: &mut f64| {
            if let Some(value) = value {
                spans.insert(setting.key(), value.span());
                *target = *value.get_ref();
            }
        };
        float(
            Setting::NormalDegrees,
            &entry.normal_degrees,
            &mut precision.normal_degrees,
        );
        float(Setting::HdrMax, &entry.hdr_max, &mut precision.hdr_max);
        float(Setting::HdrMin, &entry.hdr_min, &mut precision.hdr_min);
        float(
            Setting::HdrRelative,
            &entry.hdr_relative,
            &mut precision.hdr_relative,
        );
        for (setting, value, target) in [
            (
                Setting::ColourSteps,
                &entry.colour_steps,
                &mut precision.colour_steps,
            ),
            (
                Setting::MaterialSteps,
                &entry.material_steps,
                &mut precision.material_steps,
            ),
        ] {
            if let Some(value) = value {
                spans.insert(setting.key(), value.span());
                *target = *value.get_ref();
            }
        }
    }
    let budget = entry.budget.as_ref().map_or(DEFAULT_BUDGET, |budget| {
        spans.insert("budget", budget.span());
        *budget.get_ref()
    });

    let parsed = Parsed {
        scene: SceneDescription {
            name: entry.name.get_ref().clone(),
            model,
            features,
            precision,
            budget,
        },
        spans,
    };
    for error in parsed.scene.check() {
        diagnostics.push(FileDiagnostic::at(
            path,
            source,
            parsed.span_of(error.setting),
            error.message,
        ));
    }
    diagnostics.sort_by_key(|diagnostic| (diagnostic.line, diagnostic.column));
    if diagnostics.is_empty() {
        Ok(parsed)
    } else {
        Err(diagnostics)
    }
}
