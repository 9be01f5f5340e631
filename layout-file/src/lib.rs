//! Layout files: the layout model in TOML, for engines and asset pipelines that do not declare
//! their G-buffer in Rust. A front end, as the derive's attribute parser is the other: both
//! make one [`Layout`] of `gbuffer-core`, which the emitters (`gbuffer-codegen`) take from
//! there.
//!
//! ```toml
//! name = "MobileMetallic"   # the struct's name, UpperCamelCase
//! budget = 128              # bits; optional, 128 by default
//! conversions = "exact"     # optional; "fast" uses WGSL's pack builtins where it can
//!
//! [[fields]]
//! name = "light_accumulation"
//! format = "rgb10_a2"
//! components = 3            # or: type = "Vec3"
//!
//! [[fields]]
//! name = "depth"
//! format = "r32f"
//! type = "f32"
//!
//! [[fields]]
//! name = "albedo"
//! format = "rgba8"
//! type = "Vec4"
//! conversions = "fast"      # optional: this field's own, over the layout's
//!
//! [[fields]]                # a bit field: bits of a shared r32ui word
//! name = "normal"
//! bits = 24
//! encoding = "octahedral"   # unorm, snorm, uint, sint, bool, half, rgb9e5, octahedral, rgbm
//! type = "Vec3"             # or: components = 3
//!
//! [[fields]]
//! name = "emissive"
//! bits = 32
//! encoding = "rgbm"
//! range = 8.0               # rgbm's largest value
//! type = "Vec3"
//! ```
//!
//! A field has either `format` (a whole word) or `bits` and `encoding` (a bit field), as
//! `#[pls(...)]` and `#[bits(...)]` in the derive.
//!
//! Every problem, from TOML syntax to the budget, is a [`FileDiagnostic`] naming the file,
//! line and column; the model's checks are [`Layout::check`], the same as the derive's.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use gbuffer_core::Named;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

use gbuffer_core::format::Format;
use gbuffer_core::layout::{Conversions, Field, Layout, Storage, Subject, DEFAULT_BUDGET};
use gbuffer_core::{BitField, Encoding, FieldType, ScalarKind};
use gbuffer_files::toml_table::{self, ShapeError, Table};

/// A layout file's keys, as written.
struct LayoutEntry {
    name: Spanned<String>,
    budget: Option<Spanned<u32>>,
    conversions: Option<Spanned<String>>,
    fields: Spanned<Vec<Spanned<FieldEntry>>>,
}

/// A `[[fields]]` entry's keys, as written.
struct FieldEntry {
    name: Spanned<String>,
    format: Option<Spanned<String>>,
    bits: Option<Spanned<i64>>,
    encoding: Option<Spanned<String>>,
    range: Option<Spanned<f64>>,
    /// `type`.
    ty: Option<Spanned<String>>,
    components: Option<Spanned<i64>>,
    conversions: Option<Spanned<String>>,
}

impl LayoutEntry {
    /// The file's keys, checked for their names and types.
    fn read(document: &Spanned<DeTable<'_>>) -> Result<LayoutEntry, ShapeError> {
        let table = Table::root(document, &["name", "budget", "conversions", "fields"])?;
        let name = table.required("name")?;
        let budget = table.optional("budget")?;
        let conversions = table.optional("conversions")?;
        let fields = table.required_value("fields")?;
        let entries = toml_table::array(fields)?
            .iter()
            .map(|field| Ok(Spanned::new(field.span(), FieldEntry::read(field)?)))
            .collect::<Result<_, ShapeError>>()?;
        Ok(LayoutEntry {
            name,
            budget,
            conversions,
            fields: Spanned::new(fields.span(), entries),
        })
    }
}

impl FieldEntry {
    /// A `[[fields]]` table's keys, checked for their names and types.
    fn read(value: &Spanned<DeValue<'_>>) -> Result<FieldEntry, ShapeError> {
        let keys = [
            "name",
            "format",
            "bits",
            "encoding",
            "range",
            "type",
            "components",
            "conversions",
        ];
        let table = Table::new(value, &keys)?;
        Ok(FieldEntry {
            name: table.required("name")?,
            format: table.optional("format")?,
            bits: table.optional("bits")?,
            encoding: table.optional("encoding")?,
            range: table.optional("range")?,
            ty: table.optional("type")?,
            components: table.optional("components")?,
            conversions: table.optional("conversions")?,
        })
    }
}

/// A layout file's contents: the layout, and how its WGSL converts values.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LayoutFile {
    /// The layout the file declares.
    pub layout: Layout,
    /// `conversions = "exact"` (the default) or `"fast"`, as in `#[gbuffer(...)]`.
    pub conversions: Conversions,
}

/// A problem in a layout file, at a position in it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileDiagnostic {
    /// The layout file.
    pub path: PathBuf,
    /// 1-based.
    pub line: usize,
    /// 1-based, in characters.
    pub column: usize,
    /// What is wrong.
    pub message: String,
    /// The text of the line, for display.
    pub source_line: String,
    /// How many characters the caret underlines (at least 1).
    pub width: usize,
}

impl FileDiagnostic {
    /// A diagnostic at a byte span of `source`, the text of the file at `path`.
    pub fn at(path: &Path, source: &str, span: Range<usize>, message: impl Into<String>) -> Self {
        let start = span.start.min(source.len());
        let line_start = source[..start].rfind('\n').map_or(0, |index| index + 1);
        let line_end = source[start..]
            .find('\n')
            .map_or(source.len(), |index| start + index);
        let source_line = source[line_start..line_end]
            .trim_end_matches('\r')
            .to_string();
        let end = span.end.clamp(start, line_end);
        FileDiagnostic {
            path: path.to_path_buf(),
            line: source[..start].matches('\n').count() + 1,
            column: source[line_start..start].chars().count() + 1,
            message: message.into(),
            source_line,
            width: source[start..end].chars().count().max(1),
        }
    }
}

impl FileDiagnostic {
    /// A TOML syntax or shape error, at its span.
    pub fn from_shape(path: &Path, source: &str, error: &ShapeError) -> Self {
        FileDiagnostic::at(path, source, error.span.clone(), error.message.clone())
    }
}

impl fmt::Display for FileDiagnostic {
    /// `file:line:col: error: message`, then the line and a caret under the span.
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            out,
            "{}:{}:{}: error: {}",
            self.path.display(),
            self.line,
            self.column,
            self.message
        )?;
        let gutter = self.line.to_string().len();
        writeln!(out, "{:gutter$} |", "")?;
        writeln!(out, "{} | {}", self.line, self.source_line)?;
        write!(
            out,
            "{:gutter$} | {}{}",
            "",
            " ".repeat(self.column - 1),
            "^".repeat(self.width)
        )
    }
}

/// Why a TOML file of this project (a layout file, a scene file) could not be used.
#[derive(Debug)]
pub enum FileError {
    /// The file could not be read at all.
    Io {
        /// What the file is, e.g. `layout file`.
        kind: &'static str,
        /// The file that could not be read.
        path: PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// The file was read; these are its problems, in file order.
    Invalid(Vec<FileDiagnostic>),
}

impl FileError {
    /// Reads `path`, a file of `kind` (`layout file`, `scene file`), and hands its text and path
    /// to `parse`, whose diagnostics make the error.
    pub fn read<T>(
        path: &Path,
        kind: &'static str,
        parse: impl FnOnce(&str, &Path) -> Result<T, Vec<FileDiagnostic>>,
    ) -> Result<T, FileError> {
        let source = gbuffer_files::input::read_input(path).map_err(|error| FileError::Io {
            kind,
            path: path.to_path_buf(),
            error,
        })?;
        parse(&source, path).map_err(FileError::Invalid)
    }
}

impl fmt::Display for FileError {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FileError::Io { kind, path, error } => {
                write!(out, "{}: cannot read the {kind}: {error}", path.display())
            }
            FileError::Invalid(diagnostics) => {
                let texts: Vec<String> = diagnostics.iter().map(ToString::to_string).collect();
                write!(out, "{}", texts.join("\n\n"))
            }
        }
    }
}

impl std::error::Error for FileError {}

/// Reads and checks a layout file.
pub fn read_layout_file(path: &Path) -> Result<LayoutFile, FileError> {
    FileError::read(path, "layout file", parse_layout)
}

/// Parses and checks layout-file text; `path` names it in diagnostics.
pub fn parse_layout(source: &str, path: &Path) -> Result<LayoutFile, Vec<FileDiagnostic>> {
    let entry = toml_table::parse(source)
        .and_then(|document| LayoutEntry::read(&document))
        .map_err(|error| vec![FileDiagnostic::from_shape(path, source, &error)])?;

    let mut diagnostics = Vec::new();
    let mut conversions_of = |value: &Option<Spanned<String>>| {
        let value = value.as_ref()?;
        let conversions = Conversions::from_name(value.get_ref());
        if conversions.is_none() {
            let message = format!("unknown conversions `{}`: expected \"exact\" (the default: bit-identical everywhere) or \"fast\" (WGSL's pack builtins where they exist)", value.get_ref());
            diagnostics.push(FileDiagnostic::at(path, source, value.span(), message));
        }
        conversions
    };
    let conversions = conversions_of(&entry.conversions).unwrap_or_default();
    let field_conversions: Vec<Option<Conversions>> = entry
        .fields
        .get_ref()
        .iter()
        .map(|field| conversions_of(&field.get_ref().conversions))
        .collect();
    let mut layout = Layout {
        name: entry.name.get_ref().clone(),
        budget: entry
            .budget
            .as_ref()
            .map_or(DEFAULT_BUDGET, |budget| *budget.get_ref()),
        fields: Vec::new(),
    };
    // Per field of the layout: the spans of its name, format and type.
    let mut field_spans: Vec<[Range<usize>; 3]> = Vec::new();
    for field in entry.fields.get_ref() {
        let field_span = field.span();
        let field = field.get_ref();
        let mut report = |span: Range<usize>, message: String| {
            diagnostics.push(FileDiagnostic::at(path, source, span, message));
        };
        let (storage, storage_span) = storage_of(field, &mut report);
        let storage_span = storage_span.unwrap_or_else(|| field.name.span());
        let (ty, ty_span) = match (storage, &field.ty, &field.components) {
            (_, Some(_), Some(components)) => {
                report(
                    components.span(),
                    "give the field either `type` or `components`, not both".to_string(),
                );
                (None, field_span.clone())
            }
            (_, None, None) => {
                let message = format!(
                    "field `{}` needs `type` (e.g. \"Vec3\") or `components` (1 to 4)",
                    field.name.get_ref()
                );
                report(field.name.span(), message);
                (None, field_span.clone())
            }
            (_, Some(ty), None) => match FieldType::from_rust_name(ty.get_ref()) {
                Some(parsed) => (Some(parsed), ty.span()),
                None => {
                    let message = format!(
                        "unknown field type `{}`: use f32, Vec2, Vec3, Vec4, u32, UVec2, UVec3, UVec4, i32, IVec2, IVec3, IVec4 or bool",
                        ty.get_ref()
                    );
                    report(ty.span(), message);
                    (None, ty.span())
                }
            },
            (storage, None, Some(components)) => {
                let count = *components.get_ref();
                let (scalar, most, what) = match storage {
                    Some(Storage::Word(format)) => (
                        format.scalar_kind(),
                        format.channels().len() as i64,
                        format!("`{format}`"),
                    ),
                    Some(Storage::Bits(bit_field)) => {
                        let scalar = bit_field.encoding.scalar_kind();
                        let most = if scalar == ScalarKind::Bool { 1 } else { 4 };
                        (scalar, most, format!("`{}`", bit_field.encoding))
                    }
                    None => (ScalarKind::Float, 0, String::new()),
                };
                match storage {
                    Some(_) if (1..=most).contains(&count) => (
                        Some(FieldType::new(scalar, count as usize)),
                        components.span(),
                    ),
                    Some(storage) => {
                        let plural = if most == 1 { "" } else { "s" };
                        let message = match storage {
                            Storage::Word(_) => format!("{what} has {most} channel{plural}: components must be 1 to {most}, not {count}"),
                            Storage::Bits(_) => format!("{what} takes 1 to {most} component{plural}, not {count}"),
                        };
                        report(components.span(), message);
                        (None, components.span())
                    }
                    None => (None, components.span()),
                }
            }
        };
        // A field in error still takes its word, so the budget check counts it.
        let (storage, ty) = match (storage, ty) {
            (Some(storage), Some(ty)) => (storage, ty),
            _ => (
                Storage::Word(Format::R32f),
                FieldType::new(ScalarKind::Float, 1),
            ),
        };
        layout.fields.push(Field {
            name: field.name.get_ref().clone(),
            storage,
            ty,
            conversions: field_conversions[layout.fields.len()],
        });
        field_spans.push([field.name.span(), storage_span, ty_span]);
    }

    for diagnostic in layout.check() {
        let span = match diagnostic.subject {
            Subject::Name => entry.name.span(),
            Subject::Budget => entry
                .budget
                .as_ref()
                .map_or(entry.name.span(), Spanned::span),
            Subject::FieldName(index) => field_spans[index][0].clone(),
            Subject::FieldFormat(index) => field_spans[index][1].clone(),
            Subject::FieldType(index) => field_spans[index][2].clone(),
        };
        diagnostics.push(FileDiagnostic::at(path, source, span, diagnostic.message));
    }
    if entry.fields.get_ref().is_empty() {
        // Point at the empty array rather than at the name.
        diagnostics.retain(|diagnostic| !diagnostic.message.contains("has no fields"));
        diagnostics.push(FileDiagnostic::at(
            path,
            source,
            entry.fields.span(),
            format!(
                "layout `{}` has no fields: a G-buffer needs at least one word",
                layout.name
            ),
        ));
    }
    diagnostics.sort_by_key(|diagnostic| (diagnostic.line, diagnostic.column));
    if diagnostics.is_empty() {
        Ok(LayoutFile {
            layout,
            conversions,
        })
    } else {
        Err(diagnostics)
    }
}

/// A field's storage from its `format`, or its `bits`, `encoding` and `range`, with the span
/// the model's storage diagnostics point at (the format, or the bits); problems go to
/// `report`.
fn storage_of(
    field: &FieldEntry,
    report: &mut impl FnMut(Range<usize>, String),
) -> (Option<Storage>, Option<Range<usize>>) {
    let name = field.name.get_ref();
    match (&field.format, &field.bits, &field.encoding) {
        (Some(format), None, None) => {
            if let Some(range) = &field.range {
                report(
                    range.span(),
                    format!(
                        "field `{name}`: `range` belongs to an rgbm bit field, not to a `format`"
                    ),
                );
            }
            let storage = match Format::from_name(format.get_ref()) {
                Some(format) => Some(Storage::Word(format)),
                None => {
                    let wrong = format.get_ref();
                    report(
                        format.span(),
                        format!(
                            "unknown pixel local storage format `{wrong}`; did you mean `{}`? The formats are: {}",
                            Format::nearest(wrong),
                            Format::names().join(", ")
                        ),
                    );
                    None
                }
            };
            (storage, Some(format.span()))
        }
        (Some(format), _, _) => {
            report(
                format.span(),
                format!(
                    "field `{name}` has both `format` (a whole word) and `bits`/`encoding` (a bit field): keep one"
                ),
            );
            (None, Some(format.span()))
        }
        (None, Some(bits), Some(encoding)) => {
            let range = field.range.as_ref().map(|range| *range.get_ref() as f32);
            let parsed = match Encoding::from_name(encoding.get_ref(), range) {
                Ok(parsed) => Some(parsed),
                Err(message) => {
                    // A known encoding with a range it cannot take (or rgbm's bad range):
                    // the range is wrong; otherwise the encoding is.
                    let known = Encoding::names().contains(&encoding.get_ref().as_str());
                    let span = match &field.range {
                        Some(range) if known => range.span(),
                        _ => encoding.span(),
                    };
                    report(span, format!("field `{name}`: {message}"));
                    None
                }
            };
            let width = *bits.get_ref();
            let storage = match u32::try_from(width) {
                Ok(width) => parsed.map(|encoding| {
                    Storage::Bits(BitField {
                        bits: width,
                        encoding,
                    })
                }),
                Err(_) => {
                    report(
                        bits.span(),
                        format!("field `{name}`: a bit field has 1 to 32 bits, not {width}"),
                    );
                    None
                }
            };
            (storage, Some(bits.span()))
        }
        (None, Some(bits), None) => {
            report(
                bits.span(),
                format!(
                    "field `{name}` has `bits` but no `encoding`: add one of {}",
                    Encoding::names().join(", ")
                ),
            );
            (None, Some(bits.span()))
        }
        (None, None, Some(encoding)) => {
            report(
                encoding.span(),
                format!(
                    "field `{name}` has an `encoding` but no `bits`: say how many bits it takes"
                ),
            );
            (None, Some(encoding.span()))
        }
        (None, None, None) => {
            report(
                field.name.span(),
                format!("field `{name}` needs `format` (a whole word, e.g. \"rgba8\") or `bits` and `encoding` (a bit field)"),
            );
            (None, None)
        }
    }
}

/// The layout file of a layout: what [`parse_layout`] reads back as the same layout (field
/// types written as `type`, whole words as `format`, bit fields as `bits`, `encoding` and, for
/// rgbm, `range`).
pub fn to_toml(layout: &Layout, conversions: Conversions) -> String {
    let mut out = format!("name = \"{}\"\nbudget = {}\n", layout.name, layout.budget);
    if conversions == Conversions::Fast {
        out.push_str("conversions = \"fast\"\n");
    }
    for field in &layout.fields {
        out.push_str(&format!("\n[[fields]]\nname = \"{}\"\n", field.name));
        match field.storage {
            Storage::Word(format) => out.push_str(&format!("format = \"{format}\"\n")),
            Storage::Bits(bit_field) => {
                out.push_str(&format!(
                    "bits = {}\nencoding = \"{}\"\n",
                    bit_field.bits,
                    bit_field.encoding.name()
                ));
                if let Encoding::Rgbm(range) = bit_field.encoding {
                    out.push_str(&format!("range = {:?}\n", range.get()));
                }
            }
        }
        out.push_str(&format!("type = \"{}\"\n", field.ty.rust_name()));
        if let Some(own) = field.conversions {
            out.push_str(&format!("conversions = \"{}\"\n", own.name()));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const MOBILE_METALLIC: &str = r#"
name = "MobileMetallic"
budget = 128

[[fields]]
name = "light_accumulation"
format = "rgb10a2"
components = 3

[[fields]]
name = "depth"
format = "r32f"
type = "f32"

[[fields]]
name = "normals_roughness"
format = "rgba8"
type = "Vec4"

[[fields]]
name = "albedo_metallic"
format = "rgba8"
components = 4
"#;

    #[test]
    fn reads_a_layout() {
        let layout = parse_layout(MOBILE_METALLIC, Path::new("mobile.toml"))
            .unwrap()
            .layout;
        assert_eq!((layout.bits(), layout.used_bits()), (128, 126));
        assert_eq!(
            layout.fields[0].ty,
            FieldType::from_rust_name("Vec3").unwrap()
        );
    }

    #[test]
    fn a_layout_chooses_fast_conversions() {
        let source =
            MOBILE_METALLIC.replace("budget = 128", "budget = 128\nconversions = \"fast\"");
        let file = parse_layout(&source, Path::new("mobile.toml")).unwrap();
        assert_eq!(file.conversions, Conversions::Fast);
        assert_eq!(file.layout.fields[0].conversions, None);
    }

    #[test]
    fn a_field_chooses_its_own_conversions() {
        let source =
            MOBILE_METALLIC.replace("\"rgba8\"\ntype", "\"rgba8\"\nconversions = \"fast\"\ntype");
        let file = parse_layout(&source, Path::new("mobile.toml")).unwrap();
        assert_eq!(file.conversions, Conversions::Exact);
        let fast = file
            .layout
            .fields
            .iter()
            .find(|field| field.conversions.is_some());
        assert_eq!(
            fast.map(|field| field.conversions),
            Some(Some(Conversions::Fast))
        );
        let source = MOBILE_METALLIC.replace(
            "\"rgba8\"\ntype",
            "\"rgba8\"\nconversions = \"quick\"\ntype",
        );
        let errors = parse_layout(&source, Path::new("mobile.toml")).unwrap_err();
        assert_eq!(
            (errors.len(), errors[0].line, errors[0].column),
            (1, 18, 15)
        );
        assert!(
            errors[0].message.starts_with("unknown conversions `quick`"),
            "{}",
            errors[0].message
        );
    }

    #[test]
    fn layouts_written_as_files_read_back_the_same() {
        let bits = |bits, encoding| Storage::Bits(BitField { bits, encoding });
        let field = |name: &str, storage, ty: &str| Field {
            name: name.into(),
            storage,
            ty: FieldType::from_rust_name(ty).unwrap(),
            conversions: None,
        };
        let mut layout = Layout {
            name: "Written".into(),
            budget: 192,
            fields: vec![
                field("colour", Storage::Word(Format::Rgba8), "Vec3"),
                field(
                    "light",
                    bits(32, Encoding::from_name("rgbm", Some(51.5)).unwrap()),
                    "Vec3",
                ),
                field("normal", bits(20, Encoding::Octahedral), "Vec3"),
                field("flag", bits(1, Encoding::Bool), "bool"),
                field("id", bits(11, Encoding::Sint), "i32"),
                field("luminance", bits(10, Encoding::LogLuminance), "f32"),
                field("tint", bits(30, Encoding::UnsignedFloat), "Vec3"),
            ],
        };
        assert_eq!(layout.check(), Vec::new());
        layout.fields[0].conversions = Some(Conversions::Exact);
        for conversions in [Conversions::Exact, Conversions::Fast] {
            let text = to_toml(&layout, conversions);
            let file = parse_layout(&text, Path::new("written.toml")).unwrap();
            assert_eq!(
                (file.layout, file.conversions),
                (layout.clone(), conversions),
                "{text}"
            );
        }
    }

    #[test]
    fn errors_point_at_the_value() {
        let source = MOBILE_METALLIC.replace("\"rgba8\"\ntype", "\"rgba9\"\ntype");
        let errors = parse_layout(&source, Path::new("mobile.toml")).unwrap_err();
        assert_eq!(errors.len(), 1);
        assert_eq!((errors[0].line, errors[0].column), (17, 10));
        assert_eq!(
            errors[0].to_string(),
            "mobile.toml:17:10: error: unknown pixel local storage format `rgba9`; did you mean `rgba8`? \
             The formats are: r11f_g11f_b10f, r32f, rg16f, rgb10_a2, rgba8, rg16, rgba8i, rg16i, rgb10_a2ui, rgba8ui, rg16ui, r32ui\n   |\n17 | format = \"rgba9\"\n   |          ^^^^^^^"
        );
    }
}
