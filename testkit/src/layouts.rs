//! Random layouts for property tests: whole words of random formats and bit fields of random
//! encodings and widths, with fitting types, and names drawn from words that GLSL or naga
//! treat specially (keywords, reserved words, built-in functions, `main`, names ending in a
//! digit or `_`, `gl_` prefixes, double underscores).

use gbuffer::GBufferLayout;
use gbuffer_core::Named;
use gbuffer_core::{BitField, Encoding, Field, FieldType, Format, Layout, RgbmRange, Storage};
use proptest::prelude::*;

/// Field names that are valid in WGSL and Rust but that GLSL reserves or that naga renames;
/// [`awkward_field_names`] adds every word GLSL reserves that the name check accepts.
pub const AWKWARD_FIELD_NAMES: &[&str] = &[
    "sampler",
    "output",
    "input",
    "texture",
    "main",
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

/// [`AWKWARD_FIELD_NAMES`] and every word GLSL reserves ([`gbuffer_translate::printer::GLSL_RESERVED`],
/// naga's list) that a field may be named (not WGSL's or Rust's too).
pub fn awkward_field_names() -> Vec<&'static str> {
    let mut names: Vec<&str> = AWKWARD_FIELD_NAMES.to_vec();
    for name in gbuffer_translate::printer::GLSL_RESERVED {
        if gbuffer_core::naming::check_identifier(name).is_ok() && !names.contains(name) {
            names.push(name);
        }
    }
    names
}

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

/// A random bit field and a type that fits it: `encoding` picks one of
/// [`Encoding::names`], `components` and `width` (any values) are folded into what the
/// encoding allows.
pub fn bit_field(encoding: usize, components: usize, width: u32) -> (Storage, FieldType) {
    let float = |components| FieldType::new(gbuffer_core::ScalarKind::Float, components);
    let per_component = |encoding: Encoding, lowest: u32, highest: u32| {
        let components = components % 4 + 1;
        let most = highest.min(32 / components as u32);
        let each = lowest + width % (most - lowest + 1);
        (
            BitField {
                bits: each * components as u32,
                encoding,
            },
            FieldType::new(encoding.scalar_kind(), components),
        )
    };
    let names = Encoding::names();
    let (bit_field, ty) = match names[encoding % names.len()] {
        "unorm" => per_component(Encoding::Unorm, 1, 23),
        "snorm" => per_component(Encoding::Snorm, 2, 24),
        "uint" => per_component(Encoding::Uint, 1, 32),
        "sint" => per_component(Encoding::Sint, 1, 32),
        "unsigned_float" => per_component(Encoding::UnsignedFloat, 6, 15),
        "log_luminance" => per_component(Encoding::LogLuminance, 6, 24),
        "float32" => (
            BitField {
                bits: 32,
                encoding: Encoding::Float32,
            },
            float(1),
        ),
        "half" => {
            let components = components % 2 + 1;
            (
                BitField {
                    bits: 16 * components as u32,
                    encoding: Encoding::Half,
                },
                float(components),
            )
        }
        "rgb9e5" => (
            BitField {
                bits: 32,
                encoding: Encoding::Rgb9e5,
            },
            float(3),
        ),
        "octahedral" => (
            BitField {
                bits: 2 * (1 + width % 16),
                encoding: Encoding::Octahedral,
            },
            float(3),
        ),
        "rgbm" => {
            let range = [6.0, 8.0, 16.0, 51.5][width as usize % 4];
            (
                BitField {
                    bits: 32,
                    encoding: Encoding::Rgbm(RgbmRange::new(range).expect("a valid range")),
                },
                float(3),
            )
        }
        "bool" => (
            BitField {
                bits: 1,
                encoding: Encoding::Bool,
            },
            FieldType::new(gbuffer_core::ScalarKind::Bool, 1),
        ),
        other => panic!("random layouts do not know codec `{other}` yet: add it here"),
    };
    (Storage::Bits(bit_field), ty)
}

/// A random valid layout of `1..=max_fields` fields, whole words and bit fields, with awkward
/// names about half the time.
pub fn random_layout_with(max_fields: usize) -> impl Strategy<Value = Layout> {
    let word = (0..Format::ALL.len(), 1usize..=4).prop_map(|(format_index, components)| {
        let format = Format::ALL[format_index];
        let components = components.min(format.channels().len());
        (
            Storage::Word(format),
            FieldType::new(format.scalar_kind(), components),
        )
    });
    let bits = (0..Encoding::CODECS.len(), 0usize..4, 0u32..64)
        .prop_map(|(encoding, components, width)| bit_field(encoding, components, width));
    let awkward = awkward_field_names();
    let field = (prop_oneof![word, bits], prop::option::of(0..awkward.len()));
    (
        prop::collection::vec(field, 1..=max_fields),
        0u32..3,
        0u32..1000,
        prop::option::of(0..AWKWARD_LAYOUT_NAMES.len()),
    )
        .prop_map(move |(fields, extra_words, tag, layout_name)| {
            let mut named: Vec<Field> = Vec::new();
            for (index, ((storage, ty), name)) in fields.into_iter().enumerate() {
                let mut name =
                    name.map_or(format!("field_{index}"), |pick| awkward[pick].to_string());
                if named.iter().any(|field| field.name == name) {
                    name = format!("{name}_{index}");
                }
                named.push(Field {
                    name,
                    storage,
                    ty,
                    conversions: None,
                });
            }
            let mut layout = Layout {
                name: layout_name.map_or(format!("RandomLayout{tag}"), |pick| {
                    AWKWARD_LAYOUT_NAMES[pick].to_string()
                }),
                budget: 0,
                fields: named,
            };
            layout.budget = 32 * (layout.words() as u32 + extra_words);
            layout
        })
        .prop_filter("a valid layout", |layout| layout.check().is_empty())
}

/// A random valid layout of 1 to 8 fields (up to 256 bits).
pub fn random_layout() -> impl Strategy<Value = Layout> {
    random_layout_with(8)
}

/// The seed and engine layouts, a layout of every bit-field encoding, and a layout of every
/// format, also split in two for the native includes, whose twelve attachments are more than
/// GLES and Vulkan guarantee.
pub fn seeds_and_every_format() -> Vec<Layout> {
    let mut layouts: Vec<Layout> = gbuffer::seed_layouts::all()
        .into_iter()
        .chain(gbuffer::engine_layouts::all())
        .map(|(layout, _)| layout)
        .collect();
    layouts.push(crate::EveryEncoding::layout());
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
