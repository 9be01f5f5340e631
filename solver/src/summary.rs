//! A solution in words: the layout's words and each quantity's representation, predicted error and
//! allowance, as `gbuffer solve` prints it.

use std::fmt;

use gbuffer_core::report::FieldTable;
use gbuffer_core::Named;

use crate::solver::{describe_error, Solution};

impl fmt::Display for Solution {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let layout = &self.layout;
        writeln!(
            out,
            "{}: {} of {} bits ({} words, {} used bits, {} of them r32ui converted by shader code)",
            layout.name,
            layout.bits(),
            layout.budget,
            layout.words(),
            layout.used_bits(),
            self.custom_words()
        )?;
        write!(out, "{}", FieldTable(layout))?;
        writeln!(
            out,
            "  {:<16} {:<36} {:<34} {:<34} needed by",
            "quantity", "representation", "predicted error", "allowed"
        )?;
        for placement in &self.placements {
            let needed_by: Vec<&str> = placement.needed_by.iter().map(|f| f.name()).collect();
            let names: Vec<&str> = placement
                .fields
                .iter()
                .map(|&field| layout.fields[field].name.as_str())
                .collect();
            let where_ = names.join(", ");
            writeln!(
                out,
                "  {:<16} {:<36} {:<34} {:<34} {} (in {})",
                placement.quantity.name(),
                placement.representation.to_string(),
                describe_error(placement.quantity, placement.predicted_error),
                if placement.allowed_error.is_finite() {
                    describe_error(placement.quantity, placement.allowed_error)
                } else {
                    "exact".to_string()
                },
                needed_by.join(", "),
                where_
            )?;
        }
        Ok(())
    }
}
