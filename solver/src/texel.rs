//! The WGSL between a solved layout and the values it stores: a `<Name>Values` struct with one
//! member per stored quantity, `encode_<name>` (values to the layout's struct, which the
//! layout's own `pack_<name>` turns into words) and `decode_<name>` (the inverse).
//!
//! Every quantity is one field of the layout and every representation is the layout's own (a format,
//! or a bit field's representation in the generated WGSL), so these only move values between the two
//! structs: the scene's code stores nothing itself.

use std::fmt::Write as _;

use gbuffer_core::Named;

use crate::solver::{describe_error, Solution};

impl Solution {
    /// The name of the values struct: `<Name>Values`.
    pub fn values_type(&self) -> String {
        format!("{}Values", self.layout.name)
    }
}

/// The layout's WGSL (struct, pack and unpack), then the values struct and the encode and
/// decode functions. Valid WGSL alone.
pub fn texel_wgsl(solution: &Solution) -> String {
    let layout = &solution.layout;
    let name = &layout.name;
    let symbols = layout.symbols();
    let values = solution.values_type();
    let mut out = gbuffer_codegen::wgsl::emit(layout);

    let _ = writeln!(
        out,
        "\n// ---- {name}: what the scene stores, and how (solved by `scenes`) ----"
    );
    let _ = writeln!(out, "struct {values} {{");
    for placement in &solution.placements {
        let storage: Vec<String> = placement
            .fields
            .iter()
            .map(|&field| layout.fields[field].storage_name())
            .collect();
        let _ = writeln!(
            out,
            "    // {}: {} ({}), within {}.",
            placement.quantity.name(),
            placement.representation,
            storage.join(" and "),
            describe_error(placement.quantity, placement.predicted_error)
        );
        let _ = writeln!(
            out,
            "    {}: {},",
            placement.quantity.name(),
            placement.quantity.wgsl_type()
        );
    }
    out.push_str("}\n");

    // Each field holds a quantity, or some of its components: moved, never converted here.
    let mut fields = vec![String::new(); layout.fields.len()];
    for placement in &solution.placements {
        let quantity = placement.quantity;
        let pieces = placement.representation.pieces(quantity);
        for (piece, &field) in pieces.iter().zip(&placement.fields) {
            let count = piece.ty.components;
            fields[field] = if count == quantity.components() {
                format!("values.{}", quantity.name())
            } else {
                let lanes = &"xyzw"[piece.first_component..piece.first_component + count];
                format!("values.{}.{lanes}", quantity.name())
            };
        }
    }
    let _ = write!(
        out,
        "\n// Stores the values in the {name} layout (pack the result with {}).\nfn {}(values: {values}) -> {name} {{\n    return {name}({});\n}}\n",
        symbols.pack(),
        symbols.encode_values(),
        fields.join(", ")
    );
    let members: Vec<String> = solution
        .placements
        .iter()
        .map(|placement| {
            let parts: Vec<String> = placement
                .fields
                .iter()
                .map(|&field| format!("texel.{}", layout.fields[field].name))
                .collect();
            match parts.as_slice() {
                [whole] => whole.clone(),
                _ => format!("{}({})", placement.quantity.wgsl_type(), parts.join(", ")),
            }
        })
        .collect();
    let _ = write!(
        out,
        "\n// The values stored in a {name} texel (from {}).\nfn {}(texel: {name}) -> {values} {{\n    return {values}({});\n}}\n",
        symbols.unpack(),
        symbols.decode_values(),
        members.join(", ")
    );
    out
}
