//! A layout compiled once: what every include, the renderer and the tools take from the
//! codegen, made in one place and handed on, so that nothing lowers, parses or translates the
//! same layout twice.
//!
//! The flow is layout -> lowered layout -> compiled layout -> back ends -> consumers:
//! [`CompiledLayout::new`] lowers the layout ([`LoweredLayout`]: its words, its fields' places,
//! its generated names), writes its WGSL with the chosen conversions (the source every other
//! text derives from), takes it in through gbuffer-translate's front door
//! ([`gbuffer_translate::wgsl`]: naga's module and validation info), and prints its GLSL ES
//! declarations from that module with the names GLSL gives them ([`declarations`]) and the
//! GLSL names of its words ([`word_names`]). The back ends (`crate::emit::glsl`'s includes,
//! local read and WebGL host module, the Rust source) read this value and call nothing here but
//! its accessors; this module calls none of them.

mod declarations;
mod word_names;

pub use declarations::{GlslNames, Translation, TranslationError};

use naga::valid::ModuleInfo;

use crate::wgsl::{self, Target};
use crate::LoweredLayout;
use gbuffer_core::layout::Layout;
use gbuffer_core::Conversions;
use gbuffer_translate::printer::Item;

/// A checked layout with its conversions, compiled: the layout lowered, its WGSL and naga's
/// module of it, its GLSL ES translation with the names and items it declares, and the GLSL
/// names of its words.
#[derive(Debug)]
pub struct CompiledLayout {
    lowered: LoweredLayout,
    conversions: Conversions,
    /// The WGSL users include ([`wgsl::emit_with`]).
    wgsl: String,
    /// naga's module of [`Self::wgsl`], validated.
    module: (naga::Module, ModuleInfo),
    /// Its GLSL ES declarations, from the WGSL written for GLSL ES 3.00 (the same text but
    /// where fast rgba8 needs builtins GLSL ES 3.00 lacks).
    glsl: Translation,
    /// The bit fields' functions alone in GLSL ES (pixel local storage blocks put them
    /// beside their members), when the layout has bit fields.
    bit_field_glsl: Option<(String, Vec<Item>)>,
    /// What each word is called in GLSL ([`word_names::word_names`]).
    word_names: Vec<String>,
}

impl CompiledLayout {
    /// Compiles a checked layout with `conversions`. An error is a bug of the emitters (the
    /// WGSL is generated valid), named with naga's message.
    pub fn new(layout: &Layout, conversions: Conversions) -> Result<Self, TranslationError> {
        let lowered = LoweredLayout::new(layout);
        let wgsl = wgsl::emit_for(&lowered, conversions, Target::Wgsl);
        let module = validated(&wgsl)?;
        let for_glsl = wgsl::emit_for(&lowered, conversions, Target::GlslEs300);
        let own_module = (for_glsl != wgsl)
            .then(|| validated(&for_glsl))
            .transpose()?;
        let (glsl_module, glsl_info) = own_module.as_ref().unwrap_or(&module);
        let glsl =
            declarations::layout_declarations(&lowered, conversions, (glsl_module, glsl_info))?;
        let bit_field_glsl = match layout.has_bit_fields() {
            true => Some(declarations::bit_field_declarations(
                &wgsl::bit_field_functions(&lowered, conversions),
            )?),
            false => None,
        };
        let word_names = word_names::word_names(lowered.words(), &glsl.names);
        Ok(CompiledLayout {
            lowered,
            conversions,
            wgsl,
            module,
            glsl,
            bit_field_glsl,
            word_names,
        })
    }

    /// The layout as declared.
    pub fn layout(&self) -> &Layout {
        self.lowered.layout()
    }

    /// The layout lowered: its words, its fields' places and its generated names.
    pub fn lowered(&self) -> &LoweredLayout {
        &self.lowered
    }

    /// The conversions it was compiled with.
    pub fn conversions(&self) -> Conversions {
        self.conversions
    }

    /// Its WGSL, as the derive and `gbuffer codegen` write it (without the file's trailing
    /// newline).
    pub fn wgsl(&self) -> &str {
        &self.wgsl
    }

    /// naga's module of [`Self::wgsl`] and its validation info.
    pub fn module(&self) -> (&naga::Module, &ModuleInfo) {
        (&self.module.0, &self.module.1)
    }

    /// Its GLSL ES declarations, the names they were given and the items they declare.
    pub fn glsl(&self) -> &Translation {
        &self.glsl
    }

    /// What the layout's struct, fields and targets are called in GLSL.
    pub fn names(&self) -> &GlslNames {
        &self.glsl.names
    }

    /// What each word is called in GLSL (its pixel local storage member, its native
    /// attachment), in word order.
    pub fn word_names(&self) -> &[String] {
        &self.word_names
    }

    /// The bit fields' functions alone in GLSL ES, when the layout has bit fields.
    pub(crate) fn bit_field_glsl(&self) -> Option<&(String, Vec<Item>)> {
        self.bit_field_glsl.as_ref()
    }
}

/// `wgsl` through the front door, naga's message as the error.
fn validated(wgsl: &str) -> Result<(naga::Module, ModuleInfo), TranslationError> {
    gbuffer_translate::wgsl::validate(wgsl, gbuffer_translate::wgsl::GENERATED_CODE_CAPABILITIES)
        .map_err(TranslationError)
}

#[cfg(test)]
mod tests {
    use super::*;
    use gbuffer_core::Direction;
    use gbuffer_layout_file::read_layout_file;

    /// The compiled value holds what its parts say: naga's module of the WGSL declares the
    /// layout's functions, the translation names them in GLSL (`mobile_metallic` keeps its
    /// names: no keyword, no trailing digit), and the words are named as the fields are.
    #[test]
    fn the_compiled_layout_holds_the_module_the_translation_and_the_names() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("layouts/mobile_metallic.toml");
        let layout = read_layout_file(&path).unwrap().layout;
        let compiled = CompiledLayout::new(&layout, Conversions::Exact).unwrap();
        let symbols = layout.symbols();
        let (module, _) = compiled.module();
        let rgba8 = symbols.format_word(Direction::Encode, gbuffer_core::Format::Rgba8, "");
        for function in [symbols.pack(), symbols.unpack(), rgba8] {
            assert!(
                module
                    .functions
                    .iter()
                    .any(|(_, f)| f.name.as_deref() == Some(function.as_str())),
                "no `{function}` in the module"
            );
            assert_eq!(
                compiled.glsl().glsl_name(&function),
                Some(function.as_str())
            );
        }
        assert_eq!(compiled.names().layout, "MobileMetallic");
        let fields: Vec<&str> = layout
            .fields
            .iter()
            .map(|field| field.name.as_str())
            .collect();
        assert_eq!(compiled.word_names(), fields);
        assert!(compiled
            .wgsl()
            .starts_with("// G-buffer layout `MobileMetallic`"));
    }
}
