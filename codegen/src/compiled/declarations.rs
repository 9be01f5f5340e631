//! The layout's declarations in GLSL ES, fit to paste into a user's shader: naga parses and
//! validates the layout's WGSL, and gbuffer-translate's printer ([`gbuffer_translate::printer`])
//! prints the module's declarations from naga's IR with explicit `highp`, and no `#version`,
//! default precision or entry point.
//!
//! GLSL reserves identifiers WGSL allows (`sampler` becomes `sampler_`, `main` becomes `main_`,
//! names ending in a digit get a `_`, `__` is collapsed): the printer names each item as naga's
//! writer does, and [`GlslNames`] hands the hand-written parts of an include (blocks,
//! attachments, accessors) the names it gave the layout's structs.

use crate::LoweredLayout;
use gbuffer_core::format::Format;
use gbuffer_core::{Conversions, Direction};
use gbuffer_translate::items::ItemKind;
use gbuffer_translate::printer::{self, Choice, FromVersion310, Item, Printed};
use gbuffer_translate::wgsl;
use naga::valid::ModuleInfo;

/// Why a layout's WGSL did not become GLSL: naga refused it, or the printer met a construct
/// it has no form for (a bug either way, since the WGSL is generated valid).
#[derive(Debug)]
pub struct TranslationError(pub String);

impl std::fmt::Display for TranslationError {
    fn fmt(&self, out: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            out,
            "the generated WGSL could not be translated to GLSL: {}",
            self.0
        )
    }
}

impl std::error::Error for TranslationError {}

/// The layout's types and functions in GLSL ES, and the names they were given.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Translation {
    /// Declarations only: no `#version`, `#extension` or precision statement.
    pub text: String,
    /// The names the layout's struct, fields and targets were given.
    pub names: GlslNames,
    /// What the text declares, in its order: each item's kind, WGSL and GLSL names and text.
    pub items: Vec<Item>,
}

impl Translation {
    /// The GLSL name of the struct, constant or function called `wgsl` in the WGSL: the
    /// printer's, as naga's GLSL writer names it (a GLSL keyword, or a name ending in a digit,
    /// takes a `_`). None for a name the translation does not declare.
    pub fn glsl_name(&self, wgsl: &str) -> Option<&str> {
        self.items
            .iter()
            .find(|item| item.wgsl.as_deref() == Some(wgsl))
            .map(|item| item.glsl.as_str())
    }

    /// Checks that the translation defines function `name` (a WGSL name that is no GLSL
    /// keyword and does not end in a digit keeps its name, as the generated helpers' do): the
    /// includes call it by that name.
    pub fn check_defines(&self, name: &str) -> Result<(), TranslationError> {
        let defined = self
            .items
            .iter()
            .any(|item| item.kind == ItemKind::Function && item.glsl == name);
        match defined {
            true => Ok(()),
            false => Err(TranslationError(format!(
                "the GLSL of `{}` has no function `{name}`",
                self.names.layout
            ))),
        }
    }
}

/// What the layout's identifiers are called in GLSL.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GlslNames {
    /// The texel struct (the layout's name, renamed if GLSL reserves it).
    pub layout: String,
    /// Its members, one per field, in field order.
    pub fields: Vec<String>,
    /// The `<Name>Targets` struct.
    pub targets: String,
    /// Its `vec4<u32>` members, one per `Rgba32Uint` target.
    pub target_members: Vec<String>,
}

/// Prints the layout's WGSL for GLSL ES 3.00 (`module`, validated) as GLSL ES declarations.
/// GLSL ES 3.00 has no `packUnorm4x8`: under fast conversions that WGSL writes rgba8 in f32
/// arithmetic, and the builtins take over from GLSL ES 3.10 up (`#if __VERSION__ >= 310`).
pub(super) fn layout_declarations(
    lowered: &LoweredLayout,
    conversions: Conversions,
    (module, info): (&naga::Module, &ModuleInfo),
) -> Result<Translation, TranslationError> {
    // rgba8's fast functions: the layout's own where its conversions are fast, and those of
    // fields that choose fast conversions against exact ones.
    let symbols = lowered.symbols();
    let fast_suffixes: &[&str] = match conversions {
        Conversions::Fast => &[""],
        Conversions::Exact => &["_fast"],
    };
    let mut wrapped = Vec::new();
    for suffix in fast_suffixes {
        for (direction, builtin) in [
            (Direction::Encode, "packUnorm4x8"),
            (Direction::Decode, "unpackUnorm4x8"),
        ] {
            wrapped.push((
                symbols.format_word(direction, Format::Rgba8, suffix),
                builtin,
            ));
        }
    }
    let from_310: Vec<FromVersion310> = wrapped
        .iter()
        .map(|(function, builtin)| FromVersion310 { function, builtin })
        .collect();
    let printed = print((module, info), &from_310)?;
    let (Some((layout_name, fields)), Some((targets, target_members))) = (
        printed.struct_names(module, symbols.texel()),
        printed.struct_names(module, &symbols.targets()),
    ) else {
        return Err(TranslationError(format!(
            "the WGSL of `{}` declares no texel or targets struct",
            lowered.layout().name
        )));
    };
    let translation = Translation {
        text: printed.text,
        names: GlslNames {
            layout: layout_name,
            fields,
            targets,
            target_members,
        },
        items: printed.items,
    };
    check_bit_field_functions(&translation, lowered)?;
    Ok(translation)
}

/// The bit fields' functions and their helpers alone (`wgsl`, their WGSL), in GLSL ES
/// declarations with explicit precision (for pixel local storage includes, whose block members
/// share the global namespace with whatever the include declares).
pub(super) fn bit_field_declarations(wgsl: &str) -> Result<(String, Vec<Item>), TranslationError> {
    let (module, info) =
        wgsl::validate(wgsl, wgsl::GENERATED_CODE_CAPABILITIES).map_err(TranslationError)?;
    let printed = print((&module, &info), &[])?;
    Ok((printed.text, printed.items))
}

/// The declarations of a validated module, printed from its IR.
fn print(
    (module, info): (&naga::Module, &ModuleInfo),
    from_310: &[FromVersion310],
) -> Result<Printed, TranslationError> {
    let choice = Choice {
        from_310,
        ..Choice::default()
    };
    printer::print(module, info, &choice).map_err(TranslationError)
}

/// Checks that the bit fields' functions kept their WGSL names, which name no field and hold
/// no `__` (the includes call them by those names).
fn check_bit_field_functions(
    translation: &Translation,
    lowered: &LoweredLayout,
) -> Result<(), TranslationError> {
    let symbols = lowered.symbols();
    for (index, _) in lowered
        .layout()
        .fields
        .iter()
        .enumerate()
        .filter(|(_, field)| field.bit_field().is_some())
    {
        for direction in [Direction::Encode, Direction::Decode] {
            translation.check_defines(&symbols.bit_field(direction, index))?;
        }
    }
    Ok(())
}
