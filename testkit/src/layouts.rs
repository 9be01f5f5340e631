//! Random layouts for property tests: random formats and fitting types, and names drawn from
//! words that GLSL or naga treat specially (keywords, reserved words, built-in functions,
//! `main`, names ending in a digit or `_`, `gl_` prefixes, double underscores).

use gbuffer::packing::{Field, FieldType, Format, Layout};
use gbuffer::GBufferLayout;
use proptest::prelude::*;

/// Field names that are valid in WGSL but that GLSL reserves or that naga renames.
pub const AWKWARD_FIELD_NAMES: &[&str] = &[
    "sampler",
    "output",
    "input",
    "texture",
    "main",
    "in",
    "out",
    "inout",
    "flat",
    "smooth",
    "centroid",
    "sample",
    "buffer",
    "uniform",
    "varying",
    "attribute",
    "float",
    "int",
    "uint",
    "bool",
    "vec4",
    "mat2",
    "length",
    "normalize",
    "dot",
    "mix",
    "step",
    "subpassLoad",
    "sampler2D",
    "image2D",
    "half",
    "fixed",
    "long",
    "short",
    "double",
    "unsigned",
    "hvec2",
    "fvec3",
    "gl_thing",
    "a__b",
    "a_b",
    "target0",
    "x2",
    "albedo_",
    "albedo",
    "superp",
    "invariant",
    "lowp_value",
    "packed",
    "texel",
];

/// Layout names that are valid in WGSL but that GLSL reserves.
pub const AWKWARD_LAYOUT_NAMES: &[&str] = &[
    "main",
    "texture",
    "Main",
    "sampler2D",
    "output",
    "input",
    "float",
    "int",
    "buffer",
    "Layout2",
    "uniform",
];

/// A random valid layout of `1..=max_fields` fields, with awkward names about half the time.
pub fn random_layout_with(max_fields: usize) -> impl Strategy<Value = Layout> {
    let field = (
        0..Format::ALL.len(),
        1usize..=4,
        prop::option::of(0..AWKWARD_FIELD_NAMES.len()),
    )
        .prop_map(|(format_index, components, name)| {
            let format = Format::ALL[format_index];
            let components = components.min(format.channels().len());
            (
                format,
                FieldType::new(format.scalar_kind(), components),
                name,
            )
        });
    (
        prop::collection::vec(field, 1..=max_fields),
        0u32..3,
        0u32..1000,
        prop::option::of(0..AWKWARD_LAYOUT_NAMES.len()),
    )
        .prop_map(|(fields, extra_words, tag, layout_name)| {
            let mut named: Vec<Field> = Vec::new();
            for (index, (format, ty, name)) in fields.into_iter().enumerate() {
                let mut name = name.map_or(format!("field_{index}"), |pick| {
                    AWKWARD_FIELD_NAMES[pick].to_string()
                });
                if named.iter().any(|field| field.name == name) {
                    name = format!("{name}_{index}");
                }
                named.push(Field {
                    name,
                    format,
                    ty,
                    conversions: None,
                });
            }
            Layout {
                name: layout_name.map_or(format!("RandomLayout{tag}"), |pick| {
                    AWKWARD_LAYOUT_NAMES[pick].to_string()
                }),
                budget: 32 * (named.len() as u32 + extra_words),
                fields: named,
            }
        })
        .prop_filter("a valid layout", |layout| layout.check().is_empty())
}

/// A random valid layout of 1 to 8 fields (up to 256 bits).
pub fn random_layout() -> impl Strategy<Value = Layout> {
    random_layout_with(8)
}

/// The seed layouts and a layout of every format, also split in two for the native includes,
/// whose twelve attachments are more than GLES and Vulkan guarantee.
pub fn seeds_and_every_format() -> Vec<Layout> {
    let mut layouts: Vec<Layout> = gbuffer::seed_layouts::all()
        .into_iter()
        .map(|(layout, _)| layout)
        .collect();
    let every = crate::AllFormats::layout();
    layouts.push(every.clone());
    for (index, half) in every.fields.chunks(6).enumerate() {
        layouts.push(Layout {
            name: format!("EveryFormat{}", ["Low", "High"][index]),
            budget: 192,
            fields: half.to_vec(),
        });
    }
    layouts
}
