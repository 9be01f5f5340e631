//! What makes a layout valid, and the messages that say why one is not: names, the budget,
//! the number of fields, each field's type against its storage.

use std::fmt::Write as _;

use crate::field_type::{FieldType, ScalarKind};
use crate::format::Format;
use crate::naming;

use super::{Layout, Storage};

/// What a diagnostic is about, so each front end can point at it (a span, a file position).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Subject {
    /// The layout's name.
    Name,
    /// The budget setting (or the name, where the budget is the default).
    Budget,
    /// Field `index`'s name.
    FieldName(usize),
    /// Field `index`'s storage: its format, or its bit field's width and encoding.
    FieldFormat(usize),
    /// Field `index`'s type.
    FieldType(usize),
}

/// One problem with a layout.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// What the problem is about: the name, the budget or a field.
    pub subject: Subject,
    /// What is wrong, in one sentence.
    pub message: String,
}

/// The most fields a layout may have: far more than a G-buffer holds (eight render targets of
/// 128 bits), and few enough that every output generates in well under a second (naga's
/// translation grows faster than linearly with the number of functions, one a bit field).
pub const MAX_FIELDS: usize = 256;

/// Why `budget` bits cannot be a budget, if they cannot: a budget is whole 32-bit words.
pub fn check_budget(budget: u32) -> Result<(), String> {
    match budget != 0 && budget.is_multiple_of(32) {
        true => Ok(()),
        false => Err(format!(
            "budget must be a positive multiple of 32 bits (the fields fill 32-bit words), not \
             {budget}"
        )),
    }
}

impl Layout {
    /// Every problem with the layout, in source order; empty when it is valid.
    pub fn check(&self) -> Vec<Diagnostic> {
        let mut diagnostics = Vec::new();
        let mut report =
            |subject, message: String| diagnostics.push(Diagnostic { subject, message });

        if let Err(reason) = naming::check_layout_name(&self.name) {
            report(
                Subject::Name,
                format!("layout name `{}` {reason}", self.name),
            );
        }
        if let Err(problem) = check_budget(self.budget) {
            report(Subject::Budget, problem);
        }
        if self.fields.len() > MAX_FIELDS {
            // The per-field checks are not run: their cost is what the limit bounds.
            report(
                Subject::Name,
                format!(
                    "layout `{}` has {} fields; layouts are limited to {MAX_FIELDS}",
                    self.name,
                    self.fields.len()
                ),
            );
            return diagnostics;
        }
        if self.fields.is_empty() {
            report(
                Subject::Name,
                format!(
                    "layout `{}` has no fields: a G-buffer needs at least one word",
                    self.name
                ),
            );
        }
        for (index, field) in self.fields.iter().enumerate() {
            if let Err(reason) = naming::check_identifier(&field.name) {
                report(
                    Subject::FieldName(index),
                    format!("field name `{}` {reason}", field.name),
                );
            }
            if let Some(first) = self.fields[..index]
                .iter()
                .position(|other| other.name == field.name)
            {
                report(
                    Subject::FieldName(index),
                    format!(
                        "field `{}` is declared twice (first as field {first})",
                        field.name
                    ),
                );
            }
            match field.storage {
                Storage::Word(format) => {
                    if let Some(reason) = type_mismatch(format, field.ty) {
                        report(Subject::FieldType(index), reason);
                    }
                }
                Storage::Bits(bit_field) => {
                    if let Some(reason) = bit_field.mismatch(field.ty) {
                        report(
                            Subject::FieldFormat(index),
                            format!("field `{}`: {reason}", field.name),
                        );
                    }
                }
            }
        }
        if self.budget > 0 && self.budget.is_multiple_of(32) && self.bits() > self.budget {
            report(Subject::Budget, self.over_budget_message());
        }
        diagnostics
    }

    fn over_budget_message(&self) -> String {
        let mut message = format!(
            "layout `{}` needs {} bits but the budget is {}: ",
            self.name,
            self.bits(),
            self.budget
        );
        let terms: Vec<String> = self
            .word_contents()
            .iter()
            .map(|word| {
                let names = self.field_names(word);
                match names.as_slice() {
                    [name] if !word.is_bit_fields => format!("{name} 32"),
                    _ => format!("({}) 32", names.join(" | ")),
                }
            })
            .collect();
        let spill = self.bits() - self.budget;
        let _ = write!(
            message,
            "{} = {} > {}; {} bits ({} word{}) would spill to main memory",
            terms.join(" + "),
            self.bits(),
            self.budget,
            spill,
            spill / 32,
            if spill == 32 { "" } else { "s" }
        );
        message
    }
}

/// Why a type cannot be stored in a format, if it cannot.
fn type_mismatch(format: Format, ty: FieldType) -> Option<String> {
    let channels = format.channels().len();
    let fitting = fitting_types(format);
    if ty.scalar != format.scalar_kind() {
        let holds = match format.scalar_kind() {
            ScalarKind::Float => "floats",
            ScalarKind::Uint => "unsigned integers",
            ScalarKind::Sint => "signed integers",
            ScalarKind::Bool => "booleans",
        };
        return Some(format!(
            "`{}` cannot be stored in `{format}`, which holds {holds}: use {fitting}",
            ty.rust_name()
        ));
    }
    if ty.components > channels {
        return Some(format!(
            "`{}` has {} components but `{format}` has {channels} channel{}: use {fitting}",
            ty.rust_name(),
            ty.components,
            if channels == 1 { "" } else { "s" }
        ));
    }
    None
}

/// The types that fit a format, as a phrase: "`f32`, `Vec2` or `Vec3`".
pub fn fitting_types(format: Format) -> String {
    let names: Vec<String> = (1..=format.channels().len())
        .map(|components| {
            format!(
                "`{}`",
                FieldType::new(format.scalar_kind(), components).rust_name()
            )
        })
        .collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.concat(),
    }
}
