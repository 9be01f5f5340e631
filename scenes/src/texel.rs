//! The WGSL between a solved layout and the values it stores: a `<Name>Values` struct with one
//! member per stored quantity, `encode_<name>` (values to the layout's struct, which the
//! layout's own `pack_<name>` turns into words) and `decode_<name>` (the inverse).
//!
//! It calls the shading library's encodings (octahedral, pseudo-gamma, RGBM, rgb9e5, ...); compose
//! [`Solution::modules`] before it, or take [`standalone_wgsl`].

use std::fmt::Write as _;

use crate::solver::{describe_error, Placement, Slot, Solution};

impl Solution {
    /// The shading library modules the encode and decode functions call.
    pub fn modules(&self) -> Vec<&'static str> {
        let mut modules: Vec<&'static str> = self
            .placements
            .iter()
            .flat_map(|placement| placement.encoding.modules().iter().copied())
            .collect();
        modules.sort();
        modules.dedup();
        modules
    }

    /// The name of the values struct: `<Name>Values`.
    pub fn values_type(&self) -> String {
        format!("{}Values", self.layout.name)
    }
}

/// The layout's WGSL (struct, pack and unpack), then the values struct and the encode and
/// decode functions.
pub fn texel_wgsl(solution: &Solution) -> String {
    let layout = &solution.layout;
    let name = &layout.name;
    let snake = layout.snake_name();
    let values = solution.values_type();
    let mut out = gbuffer_codegen::emit::wgsl::emit(layout);

    let _ = writeln!(
        out,
        "\n// ---- {name}: what the scene stores, and how (solved by `scenes`) ----"
    );
    let _ = writeln!(out, "struct {values} {{");
    for placement in &solution.placements {
        let _ = writeln!(
            out,
            "    // {}: {}, within {}.",
            placement.quantity.name(),
            placement.encoding,
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

    if solution.custom_words() > 0 {
        let _ = write!(
            out,
            "
// A value in [0, 1] as a `bits`-bit unsigned normalized code, rounded to nearest.
fn {snake}_unorm_to_bits(value: f32, bits: u32) -> u32 {{
    return u32(clamp(value, 0.0, 1.0) * f32((1u << bits) - 1u) + 0.5);
}}

// The `bits`-bit code at `offset` in `word`, as a value in [0, 1].
fn {snake}_bits_to_unorm(word: u32, offset: u32, bits: u32) -> f32 {{
    return f32(extractBits(word, offset, bits)) / f32((1u << bits) - 1u);
}}
"
        );
    }

    // Encode: each quantity's stored form, then each field from its pieces.
    let _ = write!(
        out,
        "\n// Stores the values in the {name} layout (pack the result with pack_{snake}).\nfn encode_{snake}(values: {values}) -> {name} {{\n"
    );
    for placement in &solution.placements {
        let quantity = placement.quantity.name();
        let _ = writeln!(
            out,
            "    let {quantity} = {};",
            placement
                .encoding
                .encode_wgsl(&format!("values.{quantity}"))
        );
    }
    let fields: Vec<String> = (0..layout.fields.len())
        .map(|field| field_from_pieces(solution, field))
        .collect();
    let _ = write!(out, "    return {name}({});\n}}\n", fields.join(", "));

    // Decode: each quantity's stored form from its pieces, then the quantity.
    let _ = write!(
        out,
        "\n// The values stored in a {name} texel (from unpack_{snake}).\nfn decode_{snake}(texel: {name}) -> {values} {{\n"
    );
    let mut members = Vec::new();
    for placement in &solution.placements {
        let quantity = placement.quantity.name();
        let _ = writeln!(
            out,
            "    let {quantity} = {};",
            stored_from_fields(solution, placement)
        );
        members.push(placement.encoding.decode_wgsl(quantity));
    }
    let _ = write!(out, "    return {values}({});\n}}\n", members.join(", "));
    out
}

/// The solution's modules composed, then [`texel_wgsl`]: a WGSL module that validates alone.
pub fn standalone_wgsl(solution: &Solution) -> String {
    let modules = gbuffer::modules::compose(&solution.modules())
        .expect("the encodings name modules that exist");
    format!("{modules}\n{}", texel_wgsl(solution))
}

fn component(name: &str, count: usize, index: usize) -> String {
    if count == 1 {
        name.to_string()
    } else {
        format!("{name}.{}", ["x", "y", "z", "w"][index])
    }
}

/// The WGSL value of field `field` built from the stored forms of the quantities in it.
fn field_from_pieces(solution: &Solution, field: usize) -> String {
    let layout_field = &solution.layout.fields[field];
    let snake = solution.layout.snake_name();
    let mut channels = vec!["0.0".to_string(); layout_field.ty.components];
    let mut bit_fields = Vec::new();
    for placement in &solution.placements {
        let name = placement.quantity.name();
        let count = placement.encoding.stored_components(placement.quantity);
        let split = placement.locations.len() > 1;
        for (part, location) in placement.locations.iter().enumerate() {
            if location.field != field {
                continue;
            }
            match &location.slot {
                Slot::Word => return name.to_string(),
                Slot::Channels(list) => {
                    for (index, &channel) in list.iter().enumerate() {
                        let component_index = if split { part } else { index };
                        channels[channel] = component(name, count, component_index);
                    }
                }
                Slot::Bits(list) => {
                    for (index, &(offset, bits)) in list.iter().enumerate() {
                        let value = component(name, count, index);
                        bit_fields.push(if offset == 0 {
                            format!("{snake}_unorm_to_bits({value}, {bits}u)")
                        } else {
                            format!("({snake}_unorm_to_bits({value}, {bits}u) << {offset}u)")
                        });
                    }
                }
            }
        }
    }
    if !bit_fields.is_empty() {
        return bit_fields.join(" | ");
    }
    if channels.len() == 1 {
        channels.remove(0)
    } else {
        format!("{}({})", layout_field.ty.wgsl(), channels.join(", "))
    }
}

/// The WGSL value of a quantity's stored form read from the texel's fields.
fn stored_from_fields(solution: &Solution, placement: &Placement) -> String {
    let snake = solution.layout.snake_name();
    let mut components = Vec::new();
    for location in &placement.locations {
        let field = &solution.layout.fields[location.field];
        let access = format!("texel.{}", field.name);
        match &location.slot {
            Slot::Word => return access,
            Slot::Channels(list) => {
                for &channel in list {
                    components.push(component(&access, field.ty.components, channel));
                }
            }
            Slot::Bits(list) => {
                for &(offset, bits) in list {
                    components.push(format!(
                        "{snake}_bits_to_unorm({access}, {offset}u, {bits}u)"
                    ));
                }
            }
        }
    }
    match components.len() {
        1 => components.remove(0),
        count => format!("vec{count}<f32>({})", components.join(", ")),
    }
}
