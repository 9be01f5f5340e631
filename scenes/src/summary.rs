//! A solution in words: the layout's words and each quantity's encoding, predicted error and
//! allowance, as `gbuffer solve` prints it.

use std::fmt;

use crate::solver::{describe_error, Slot, Solution};

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
        writeln!(out, "  word  field                         format")?;
        for (index, field) in layout.fields.iter().enumerate() {
            writeln!(
                out,
                "  {index:<4}  {:<28}  {} {}",
                field.name,
                field.storage_name(),
                field.ty.rust_name()
            )?;
        }
        writeln!(
            out,
            "  {:<16} {:<36} {:<34} {:<34} needed by",
            "quantity", "encoding", "predicted error", "allowed"
        )?;
        for placement in &self.placements {
            let needed_by: Vec<&str> = placement.needed_by.iter().map(|f| f.name()).collect();
            let where_: Vec<String> = placement
                .locations
                .iter()
                .map(|location| {
                    let field = &layout.fields[location.field].name;
                    match &location.slot {
                        Slot::Bits(bits) => {
                            let ranges: Vec<String> = bits
                                .iter()
                                .map(|(offset, width)| format!("{}..{}", offset, offset + width))
                                .collect();
                            format!("{field}[bits {}]", ranges.join(", "))
                        }
                        _ => field.clone(),
                    }
                })
                .collect();
            let mut where_ = where_;
            where_.dedup();
            writeln!(
                out,
                "  {:<16} {:<36} {:<34} {:<34} {} (in {})",
                placement.quantity.name(),
                placement.encoding.to_string(),
                describe_error(placement.quantity, placement.predicted_error),
                if placement.allowed_error.is_finite() {
                    describe_error(placement.quantity, placement.allowed_error)
                } else {
                    "exact".to_string()
                },
                needed_by.join(", "),
                where_.join(", ")
            )?;
        }
        Ok(())
    }
}
