//! TOML tables read into typed, spanned values: the shape checks of this project's files
//! (layout files, scene files), over `toml`'s parser alone.
//!
//! A file is parsed into `toml`'s spanned tree ([`parse`]); a [`Table`] of it names the keys it
//! allows and hands out each value as the type asked for, with its span. The first problem
//! (a syntax error, an unknown key, a missing key, a value of the wrong type or out of range)
//! is a [`ShapeError`] at its span, worded as serde's derive words it, with "key" for "field".
//! Serde itself is not needed, which keeps the command-line tool's build small.

use std::ops::Range;

use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// A problem with a file's shape, at a byte span of its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShapeError {
    /// What it is about: the key, the value, or the table that misses a key.
    pub span: Range<usize>,
    /// What is wrong.
    pub message: String,
}

impl ShapeError {
    fn new(span: Range<usize>, message: String) -> Self {
        ShapeError { span, message }
    }
}

/// Parses TOML text into its spanned tree; a syntax error is at its span.
pub fn parse(source: &str) -> Result<Spanned<DeTable<'_>>, ShapeError> {
    DeTable::parse(source).map_err(|error| {
        ShapeError::new(
            error.span().unwrap_or(0..0),
            error.message().trim_end().replace('\n', " "),
        )
    })
}

/// A key and its value, each with its span.
pub type Entry<T> = (Spanned<String>, Spanned<T>);

/// A table whose keys are checked against those it allows.
pub struct Table<'a, 'i> {
    entries: &'a DeTable<'i>,
    span: Range<usize>,
}

impl<'a, 'i> Table<'a, 'i> {
    /// The table `value` (an error if it is not one), refusing any key not in `keys` (the
    /// first such key in the file).
    pub fn new(value: &'a Spanned<DeValue<'i>>, keys: &[&str]) -> Result<Self, ShapeError> {
        match value.get_ref() {
            DeValue::Table(entries) => Self::of(entries, value.span(), keys),
            other => Err(invalid_type(value.span(), other, "a table")),
        }
    }

    /// The table `value`, whatever its keys (a map from names the caller checks).
    pub fn with_any_keys(value: &'a Spanned<DeValue<'i>>) -> Result<Self, ShapeError> {
        match value.get_ref() {
            DeValue::Table(entries) => Ok(Table {
                entries,
                span: value.span(),
            }),
            other => Err(invalid_type(value.span(), other, "a table")),
        }
    }

    /// The document's top-level table, as [`Table::new`] checks it.
    pub fn root(document: &'a Spanned<DeTable<'i>>, keys: &[&str]) -> Result<Self, ShapeError> {
        Self::of(document.get_ref(), document.span(), keys)
    }

    fn of(entries: &'a DeTable<'i>, span: Range<usize>, keys: &[&str]) -> Result<Self, ShapeError> {
        let unknown = entries
            .keys()
            .filter(|key| !keys.contains(&key.get_ref().as_ref()))
            .min_by_key(|key| key.span().start);
        if let Some(key) = unknown {
            let expected: Vec<String> = keys.iter().map(|key| format!("`{key}`")).collect();
            let expected = match expected.as_slice() {
                [] => "there are none".to_string(),
                [one] => format!("expected {one}"),
                _ => format!("expected one of {}", expected.join(", ")),
            };
            return Err(ShapeError::new(
                key.span(),
                format!("unknown key `{}`, {expected}", key.get_ref()),
            ));
        }
        Ok(Table { entries, span })
    }

    /// The table's span (the whole document for the top level).
    pub fn span(&self) -> Range<usize> {
        self.span.clone()
    }

    /// The raw value of `key`, if it is there.
    pub fn value(&self, key: &str) -> Option<&'a Spanned<DeValue<'i>>> {
        self.entries.get(key)
    }

    /// The raw value of `key`; a missing key is an error at the table.
    pub fn required_value(&self, key: &str) -> Result<&'a Spanned<DeValue<'i>>, ShapeError> {
        self.value(key)
            .ok_or_else(|| ShapeError::new(self.span(), format!("missing key `{key}`")))
    }

    /// The value of `key` as a `T`, if it is there.
    pub fn optional<T: FromValue>(&self, key: &str) -> Result<Option<Spanned<T>>, ShapeError> {
        self.value(key).map(read).transpose()
    }

    /// The value of `key` as a `T`; a missing key is an error at the table.
    pub fn required<T: FromValue>(&self, key: &str) -> Result<Spanned<T>, ShapeError> {
        read(self.required_value(key)?)
    }

    /// The key-value pairs of the table in file order, each value read as a `T`.
    pub fn entries<T: FromValue>(&self) -> Result<Vec<Entry<T>>, ShapeError> {
        let mut pairs: Vec<_> = self.entries.iter().collect();
        pairs.sort_by_key(|(key, _)| key.span().start);
        pairs
            .into_iter()
            .map(|(key, value)| {
                let key = Spanned::new(key.span(), key.get_ref().to_string());
                Ok((key, read(value)?))
            })
            .collect()
    }
}

/// The array `value`'s items (an error if it is not an array).
pub fn array<'a, 'i>(
    value: &'a Spanned<DeValue<'i>>,
) -> Result<&'a [Spanned<DeValue<'i>>], ShapeError> {
    match value.get_ref() {
        DeValue::Array(items) => Ok(items),
        other => Err(invalid_type(value.span(), other, "a sequence")),
    }
}

/// Reads `value` as a `T`, keeping its span.
pub fn read<T: FromValue>(value: &Spanned<DeValue<'_>>) -> Result<Spanned<T>, ShapeError> {
    T::from_value(value.get_ref())
        .map(|read| Spanned::new(value.span(), read))
        .map_err(|message| ShapeError::new(value.span(), message))
}

/// A type a TOML value reads as.
pub trait FromValue: Sized {
    /// The value as this type, or why it is not one.
    fn from_value(value: &DeValue<'_>) -> Result<Self, String>;
}

impl FromValue for String {
    fn from_value(value: &DeValue<'_>) -> Result<Self, String> {
        match value {
            DeValue::String(text) => Ok(text.to_string()),
            other => Err(type_message(other, "a string")),
        }
    }
}

impl FromValue for bool {
    fn from_value(value: &DeValue<'_>) -> Result<Self, String> {
        match value {
            DeValue::Boolean(flag) => Ok(*flag),
            other => Err(type_message(other, "a boolean")),
        }
    }
}

impl FromValue for f64 {
    /// A float, or an integer (`range = 8` means 8.0).
    fn from_value(value: &DeValue<'_>) -> Result<Self, String> {
        match value {
            DeValue::Float(float) => float
                .as_str()
                .parse()
                .map_err(|_| format!("invalid value: `{}`, expected f64", float.as_str())),
            DeValue::Integer(_) => Ok(i64::from_value(value)? as f64),
            other => Err(type_message(other, "f64")),
        }
    }
}

impl FromValue for i64 {
    fn from_value(value: &DeValue<'_>) -> Result<Self, String> {
        match value {
            DeValue::Integer(integer) => i64::from_str_radix(integer.as_str(), integer.radix())
                .map_err(|_| format!("invalid value: integer `{integer}`, expected i64")),
            other => Err(type_message(other, "i64")),
        }
    }
}

impl FromValue for u32 {
    fn from_value(value: &DeValue<'_>) -> Result<Self, String> {
        match value {
            DeValue::Integer(integer) => i128::from_str_radix(integer.as_str(), integer.radix())
                .ok()
                .and_then(|wide| u32::try_from(wide).ok())
                .ok_or_else(|| format!("invalid value: integer `{integer}`, expected u32")),
            other => Err(type_message(other, "u32")),
        }
    }
}

fn invalid_type(span: Range<usize>, value: &DeValue<'_>, expected: &str) -> ShapeError {
    ShapeError::new(span, type_message(value, expected))
}

/// `invalid type: integer `5`, expected a string`, as serde says it.
fn type_message(value: &DeValue<'_>, expected: &str) -> String {
    let found = match value {
        DeValue::String(text) => format!("string {:?}", text.as_ref()),
        DeValue::Integer(integer) => format!("integer `{integer}`"),
        DeValue::Float(float) => format!("floating point `{}`", float.as_str()),
        DeValue::Boolean(flag) => format!("boolean `{flag}`"),
        DeValue::Datetime(datetime) => format!("datetime `{datetime}`"),
        DeValue::Array(_) => "sequence".to_string(),
        DeValue::Table(_) => "map".to_string(),
    };
    format!("invalid type: {found}, expected {expected}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn first_problem(source: &str, read: impl Fn(&Table) -> Result<(), ShapeError>) -> String {
        let document = parse(source).unwrap();
        let table = Table::root(&document, &["name", "budget", "range", "flags"]);
        match table.and_then(|table| read(&table)) {
            Ok(()) => String::new(),
            Err(problem) => format!(
                "{}..{}: {}",
                problem.span.start, problem.span.end, problem.message
            ),
        }
    }

    #[test]
    fn values_read_as_their_types_with_their_spans() {
        let document = parse("name = \"A\"\nbudget = 0x80\nrange = 8\n").unwrap();
        let table = Table::root(&document, &["name", "budget", "range"]).unwrap();
        let name: Spanned<String> = table.required("name").unwrap();
        assert_eq!((name.get_ref().as_str(), name.span()), ("A", 7..10));
        assert_eq!(*table.required::<u32>("budget").unwrap().get_ref(), 128);
        assert_eq!(*table.required::<f64>("range").unwrap().get_ref(), 8.0);
        assert_eq!(table.optional::<bool>("flags").unwrap(), None);
    }

    #[test]
    fn problems_are_worded_as_serde_words_them_at_their_spans() {
        let cases = [
            (
                "budjet = 1",
                "0..6: unknown key `budjet`, expected one of `name`, `budget`, `range`, `flags`",
            ),
            ("budget = 1", "0..0: missing key `name`"),
            (
                "name = 5",
                "7..8: invalid type: integer `5`, expected a string",
            ),
            (
                "name = \"A\"\nbudget = -32",
                "20..23: invalid value: integer `-32`, expected u32",
            ),
            (
                "name = \"A\"\nbudget = 4294967296",
                "20..30: invalid value: integer `4294967296`, expected u32",
            ),
            (
                "name = \"A\"\nrange = \"x\"",
                "19..22: invalid type: string \"x\", expected f64",
            ),
            (
                "name = \"A\"\nflags = [1]",
                "19..22: invalid type: sequence, expected a boolean",
            ),
        ];
        for (source, expected) in cases {
            let found = first_problem(source, |table| {
                table.required::<String>("name")?;
                table.optional::<u32>("budget")?;
                table.optional::<f64>("range")?;
                table.optional::<bool>("flags")?;
                Ok(())
            });
            assert_eq!(found, expected, "{source}");
        }
    }

    #[test]
    fn syntax_errors_are_at_their_span() {
        let problem = parse("name = \"open").unwrap_err();
        assert!(
            problem.message.contains("invalid basic string"),
            "{problem:?}"
        );
        // At the end of the line the string never closes on.
        assert_eq!(problem.span.start, 12);
    }
}
