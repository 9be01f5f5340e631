//! The names of what the emitters generate for a layout, spelled once.
//!
//! The WGSL emitter defines its items under these names, the GLSL includes theirs, and every
//! package that calls generated code (the wgpu targets, the renderer, the harnesses, the
//! solver's texel code, the Bevy module) asks a layout's [`Symbols`] for the name it calls.
//! A rename here renames both sides; `integration-tests/tests/symbols.rs` holds every name
//! against the items each output defines, so a caller cannot name an item no emitter makes.
//!
//! The GLSL includes carry the WGSL functions as naga translates them, under the names the
//! GLSL printer gives (the one GLSL naming view: naga's writer's rules, which rename a GLSL
//! keyword or a name ending in a digit; the compiled layout's translation maps each WGSL name
//! to its GLSL one, `Translation::glsl_name` in `gbuffer-codegen`); the functions the GLSL
//! emitter writes itself ([`Symbols::load`], [`Symbols::store`]) and the attachments keep the
//! names below.

use crate::format::Format;
use crate::naming::{glsl_identifier, snake_case};
use crate::Named;

/// Which way a generated conversion goes: a value to its code or word, or back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// A value to its code (a bit field's) or word (a format's).
    Encode,
    /// A code or word back to the value.
    Decode,
}

crate::named!(
    Direction {
        Encode => "encode",
        Decode => "decode",
    }
);

/// The generated names of one layout ([`crate::Layout::symbols`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symbols {
    texel: String,
    snake: String,
}

impl Symbols {
    /// The names generated for the layout called `layout_name` (`MobileMetallic`).
    pub fn new(layout_name: &str) -> Symbols {
        Symbols {
            texel: layout_name.to_string(),
            snake: snake_case(layout_name),
        }
    }

    /// The layout's name in snake_case (`mobile_metallic`), which prefixes every generated
    /// function and names the generated files and the WESL module.
    pub fn snake(&self) -> &str {
        &self.snake
    }

    /// The texel struct, WGSL and GLSL: the layout's own name (`MobileMetallic`).
    pub fn texel(&self) -> &str {
        &self.texel
    }

    /// The WGSL constant holding the number of 32-bit words of a texel (`MOBILE_METALLIC_WORDS`).
    pub fn words_constant(&self) -> String {
        format!("{}_WORDS", self.snake.to_uppercase())
    }

    /// `pack_<snake>(texel) -> array<u32, N>`, WGSL (GLSL: as the printer names it).
    pub fn pack(&self) -> String {
        format!("pack_{}", self.snake)
    }

    /// `unpack_<snake>(words) -> texel`, WGSL (GLSL: as the printer names it).
    pub fn unpack(&self) -> String {
        format!("unpack_{}", self.snake)
    }

    /// `load_<snake>_<field>(words) -> value`, WGSL: one field decoded alone (GLSL: as the
    /// printer names it).
    pub fn load_field(&self, field: &str) -> String {
        format!("load_{}_{field}", self.snake)
    }

    /// The fragment-output struct, one `vec4<u32>` per four words (`MobileMetallicTargets`),
    /// WGSL and GLSL.
    pub fn targets(&self) -> String {
        format!("{}Targets", self.texel)
    }

    /// `pack_<snake>_targets(texel) -> <Layout>Targets`, WGSL and GLSL.
    pub fn pack_targets(&self) -> String {
        format!("pack_{}_targets", self.snake)
    }

    /// `unpack_<snake>_targets(targets) -> texel`, WGSL and GLSL.
    pub fn unpack_targets(&self) -> String {
        format!("unpack_{}_targets", self.snake)
    }

    /// `<snake>_words_from_targets(targets) -> array<u32, N>`, WGSL and GLSL.
    pub fn words_from_targets(&self) -> String {
        format!("{}_words_from_targets", self.snake)
    }

    /// Packed target `index` as the lighting pass binds it: the WGSL texture of the wgpu
    /// targets' lighting source and the GLSL attachment of the packed includes
    /// (`mobile_metallic_target0`).
    pub fn target(&self, index: usize) -> String {
        format!("{}_target{index}", self.snake)
    }

    /// `load_<snake>_targets(pixel) -> <Layout>Targets`, the wgpu targets' lighting source.
    pub fn load_targets(&self) -> String {
        format!("load_{}_targets", self.snake)
    }

    /// `read_<snake>_targets(pixel) -> texel`, the wgpu targets' lighting source.
    pub fn read_targets(&self) -> String {
        format!("read_{}_targets", self.snake)
    }

    /// `<snake>_<direction>_<format><suffix>_word`, WGSL (`mobile_metallic_encode_rgba8_word`):
    /// a whole word of `format` from a field's value or back, what the pack and unpack
    /// functions, the WebGL include's planes and GLSL ES 3.10's builtin wrappers call.
    /// `suffix` is a field's own conversions (`_fast`, `_exact`) where they differ from the
    /// layout's, else empty.
    pub fn format_word(&self, direction: Direction, format: Format, suffix: &str) -> String {
        format!(
            "{}_{}_{}{suffix}_word",
            self.snake,
            direction.name(),
            format.name()
        )
    }

    /// `<snake>_<direction>_field_<index>_bits`, WGSL (`bevy_like_decode_field_6_bits`): bit
    /// field `index`'s value to its code in the low bits, or back. Named by the field's place
    /// in the layout, not its name: naga's GLSL writer would rename a name with `__` or one
    /// that another collapses into, and the GLSL includes call these by their WGSL names.
    pub fn bit_field(&self, direction: Direction, index: usize) -> String {
        format!("{}_{}_field_{index}_bits", self.snake, direction.name())
    }

    /// `<snake>_<lanes>_<name>`, WGSL: a codec's helper on `lanes` f32 lanes, as its template
    /// spells it `PREFIX_LANES_<name>` (`mobile_metallic_f32x4_to_unorm`), the lanes as
    /// [`Symbols::lanes`] spells them. The WGSL back end's codec files define these helpers
    /// and name the ones they call from outside a template here.
    pub fn codec_helper(&self, lanes: usize, name: &str) -> String {
        format!("{}_{}_{name}", self.snake, Symbols::lanes(lanes))
    }

    /// `<snake>_<name>`, WGSL: a codec's function of one fixed shape, as its template spells it
    /// `PREFIX_<name>` (`mobile_metallic_rgbm_from_f32x3`).
    pub fn codec_function(&self, name: &str) -> String {
        format!("{}_{name}", self.snake)
    }

    /// A lane count as codec helpers' names spell it: `f32`, `f32x2`, `f32x3`, `f32x4`. Never
    /// at a name's end: naga_oil refuses a name that ends in a digit.
    pub fn lanes(lanes: usize) -> String {
        match lanes {
            1 => "f32".to_string(),
            n => format!("f32x{n}"),
        }
    }

    /// `shade_<snake>(values, view, position) -> vec3<f32>`, the solver's lighting WGSL
    /// (`gbuffer_solver::lighting`): a solved scene's shading with only the terms it uses.
    pub fn shade(&self) -> String {
        format!("shade_{}", self.snake)
    }

    /// `load_<snake>() -> texel`, every GLSL include that reads: the texel in the
    /// attachments, the planes or the pixel local storage.
    pub fn load(&self) -> String {
        format!("load_{}", self.snake)
    }

    /// `store_<snake>(texel)`, every GLSL include that writes.
    pub fn store(&self) -> String {
        format!("store_{}", self.snake)
    }

    /// `encode_<snake>(values) -> texel`, the solver's texel WGSL
    /// (`gbuffer_solver::texel`): a solved scene's values stored in the layout.
    pub fn encode_values(&self) -> String {
        format!("encode_{}", self.snake)
    }

    /// `decode_<snake>(texel) -> values`, the solver's texel WGSL: the inverse of
    /// [`Symbols::encode_values`].
    pub fn decode_values(&self) -> String {
        format!("decode_{}", self.snake)
    }

    /// `load_pls_<snake>_<field>() -> value`, the pixel local storage includes' (EXT and WebGL)
    /// load of one field, from the field's GLSL name (naga's: a keyword takes a `_`, which the
    /// join drops).
    pub fn load_pls(&self, glsl_field: &str) -> String {
        glsl_identifier(&["load_pls", &self.snake, glsl_field])
    }

    /// `store_pls_<snake>_<word>(...)`, the EXT pixel local storage includes' write of a word
    /// of bit fields whole, from the word's GLSL name.
    pub fn store_pls(&self, glsl_word: &str) -> String {
        glsl_identifier(&["store_pls", &self.snake, glsl_word])
    }

    /// `<snake>_<word>_plane`, the WebGL include's pixel local storage plane of a word.
    pub fn plane(&self, glsl_word: &str) -> String {
        glsl_identifier(&[&self.snake, glsl_word, "plane"])
    }

    /// `<snake>_<word>_attachment`, the native fetch and subpass includes' attachment of a word.
    pub fn attachment(&self, glsl_word: &str) -> String {
        glsl_identifier(&[&self.snake, glsl_word, "attachment"])
    }

    /// What a word of bit fields is called in GLSL (its PLS member, its native attachment, its
    /// WebGL plane's stem), from its fields' GLSL names: joined and ending in `_bits`
    /// (`normal_roughness_bits`), or with `word` (the word's index) where the joined name
    /// would meet another word's (`a_1_word2_bits`). A whole word is called after its field.
    /// A field's name ending in `_` (naga's `field_0_`) is trimmed, so that no `__` appears.
    pub fn bit_fields_word(glsl_fields: &[&str], word: Option<usize>) -> String {
        let fields: Vec<&str> = glsl_fields
            .iter()
            .map(|field| field.trim_end_matches('_'))
            .collect();
        let joined = fields.join("_");
        match word {
            None => format!("{joined}_bits"),
            Some(index) => format!("{joined}_word{index}_bits"),
        }
    }

    /// The pixel local storage block of the EXT includes (`MobileMetallicPixelLocalStorage`),
    /// from the texel struct's GLSL name (naga's, which may differ from [`Symbols::texel`]
    /// only where that is a GLSL keyword).
    pub fn pixel_local_storage_block(glsl_texel: &str) -> String {
        format!("{glsl_texel}PixelLocalStorage")
    }

    /// The file the WGSL is written to (`mobile_metallic.wgsl`).
    pub fn wgsl_file(&self) -> String {
        format!("{}.wgsl", self.snake)
    }

    /// A generated file other than the WGSL: `<snake>.<suffix>` (`mobile_metallic.fetch.glsl`).
    pub fn file(&self, suffix: &str) -> String {
        format!("{}.{suffix}", self.snake)
    }

    /// The WESL module path the layout's WGSL is published under (`gbuffer::mobile_metallic`).
    pub fn module_path(&self) -> String {
        format!("gbuffer::{}", self.snake)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_documented_forms() {
        let symbols = Symbols::new("MobileMetallic");
        assert_eq!(symbols.snake(), "mobile_metallic");
        assert_eq!(symbols.texel(), "MobileMetallic");
        assert_eq!(symbols.words_constant(), "MOBILE_METALLIC_WORDS");
        assert_eq!(symbols.pack(), "pack_mobile_metallic");
        assert_eq!(symbols.unpack(), "unpack_mobile_metallic");
        assert_eq!(symbols.load_field("albedo"), "load_mobile_metallic_albedo");
        assert_eq!(symbols.targets(), "MobileMetallicTargets");
        assert_eq!(symbols.pack_targets(), "pack_mobile_metallic_targets");
        assert_eq!(symbols.unpack_targets(), "unpack_mobile_metallic_targets");
        assert_eq!(
            symbols.words_from_targets(),
            "mobile_metallic_words_from_targets"
        );
        assert_eq!(symbols.target(1), "mobile_metallic_target1");
        assert_eq!(symbols.load_targets(), "load_mobile_metallic_targets");
        assert_eq!(symbols.read_targets(), "read_mobile_metallic_targets");
        assert_eq!(symbols.load(), "load_mobile_metallic");
        assert_eq!(symbols.store(), "store_mobile_metallic");
        assert_eq!(symbols.load_pls("in_"), "load_pls_mobile_metallic_in");
        assert_eq!(
            symbols.store_pls("normal_bits"),
            "store_pls_mobile_metallic_normal_bits"
        );
        assert_eq!(symbols.plane("albedo"), "mobile_metallic_albedo_plane");
        assert_eq!(
            symbols.attachment("albedo"),
            "mobile_metallic_albedo_attachment"
        );
        assert_eq!(
            symbols.format_word(Direction::Encode, Format::Rgba8, ""),
            "mobile_metallic_encode_rgba8_word"
        );
        assert_eq!(
            symbols.format_word(Direction::Decode, Format::Rg16f, "_fast"),
            "mobile_metallic_decode_rg16f_fast_word"
        );
        assert_eq!(
            symbols.bit_field(Direction::Decode, 6),
            "mobile_metallic_decode_field_6_bits"
        );
        assert_eq!(
            symbols.codec_helper(4, "to_unorm"),
            "mobile_metallic_f32x4_to_unorm"
        );
        assert_eq!(
            symbols.codec_helper(1, "to_half"),
            "mobile_metallic_f32_to_half"
        );
        assert_eq!(
            symbols.codec_function("rgbm_from_f32x3"),
            "mobile_metallic_rgbm_from_f32x3"
        );
        assert_eq!(symbols.shade(), "shade_mobile_metallic");
        assert_eq!(symbols.encode_values(), "encode_mobile_metallic");
        assert_eq!(symbols.decode_values(), "decode_mobile_metallic");
        assert_eq!(
            Symbols::bit_fields_word(&["normal", "roughness"], None),
            "normal_roughness_bits"
        );
        assert_eq!(
            Symbols::bit_fields_word(&["a_", "b"], Some(2)),
            "a_b_word2_bits"
        );
        assert_eq!(
            Symbols::pixel_local_storage_block("MobileMetallic"),
            "MobileMetallicPixelLocalStorage"
        );
        assert_eq!(symbols.wgsl_file(), "mobile_metallic.wgsl");
        assert_eq!(symbols.file("fetch.glsl"), "mobile_metallic.fetch.glsl");
        assert_eq!(symbols.module_path(), "gbuffer::mobile_metallic");
    }
}
