//! A layout lowered once: what every emitter reads instead of asking the model again. The model
//! ([`Layout`]) says what the user declared; the lowering asks it once which words the fields
//! fill (each word's members and their bit ranges), where each field lies, and the names of
//! the generated items ([`Symbols`]), and keeps the answers. The WGSL and Rust emitters take it
//! whole; the compile step ([`crate::CompiledLayout`]) holds one and hands it to every include.

use gbuffer_core::format::PackedTarget;
use gbuffer_core::layout::{field_locations_in, Layout, Member, Word};
use gbuffer_core::Symbols;

/// A checked layout with its words, its fields' places and its generated names worked out.
#[derive(Clone, Debug)]
pub struct LoweredLayout {
    layout: Layout,
    words: Vec<Word>,
    locations: Vec<(usize, Member)>,
    symbols: Symbols,
}

impl LoweredLayout {
    /// Lowers a layout that passed [`Layout::check`].
    pub fn new(layout: &Layout) -> LoweredLayout {
        let words = layout.word_contents();
        LoweredLayout {
            layout: layout.clone(),
            locations: field_locations_in(&words, layout.fields.len()),
            words,
            symbols: layout.symbols(),
        }
    }

    /// The layout as declared.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// The words the fields fill, in order: each word's format and its members from the least
    /// significant bit up.
    pub fn words(&self) -> &[Word] {
        &self.words
    }

    /// How many bits the words take: 32 a word.
    pub fn bits(&self) -> u32 {
        32 * self.words.len() as u32
    }

    /// How many packed render targets the words take ([`PackedTarget::count_for_words`]).
    pub fn targets(&self) -> usize {
        PackedTarget::count_for_words(self.words.len())
    }

    /// Where each field lies, in field order: its word's index and its member of that word.
    pub fn locations(&self) -> &[(usize, Member)] {
        &self.locations
    }

    /// The names of the items generated for the layout.
    pub fn symbols(&self) -> &Symbols {
        &self.symbols
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gbuffer_core::layout::Storage;
    use gbuffer_layout_file::read_layout_file;

    /// For every layout file of the package: each field lies in one member as wide as it
    /// declares, the word it names holds that member, a word's members follow one another from
    /// bit 0 without overlap, and there are as many words as the layout counts.
    #[test]
    fn each_field_lies_in_a_member_of_its_width_and_words_do_not_overlap() {
        let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("layouts");
        for entry in std::fs::read_dir(folder).unwrap() {
            let layout = read_layout_file(&entry.unwrap().path()).unwrap().layout;
            let lowered = LoweredLayout::new(&layout);
            assert_eq!(lowered.words().len(), layout.words(), "{}", layout.name);
            assert_eq!(lowered.bits(), layout.bits());
            assert_eq!(lowered.targets(), layout.targets());
            for (index, (field, &(word, member))) in
                layout.fields.iter().zip(lowered.locations()).enumerate()
            {
                let bits = match field.storage {
                    Storage::Word(_) => 32,
                    Storage::Bits(bit_field) => bit_field.bits,
                };
                assert_eq!((member.field, member.bits), (index, bits), "{}", field.name);
                assert!(
                    lowered.words()[word].members.contains(&member),
                    "{}",
                    field.name
                );
            }
            for word in lowered.words() {
                let mut next = 0;
                for member in &word.members {
                    assert!(
                        member.offset >= next,
                        "{}: overlapping members",
                        layout.name
                    );
                    next = member.offset + member.bits;
                }
                assert!(next <= 32, "{}: a word past 32 bits", layout.name);
            }
            assert_eq!(lowered.symbols().texel(), layout.symbols().texel());
        }
    }
}
