//! What the words of a layout are called in GLSL: a pixel local storage member, a native
//! attachment, a WebGL plane is named after the word's fields, each name declared once.

use gbuffer_core::layout::Word;
use gbuffer_core::Symbols;

use super::GlslNames;

/// What each word is called in GLSL (its PLS member, its native attachment): a whole word its
/// field's name, a word of bit fields [`Symbols::bit_fields_word`]. Joined names can meet
/// another word's (fields `a_1` and `a_`, trimmed, both give `a_1_bits`; a field may be called
/// `a_bits`): such a word takes its index, so every name is declared once.
pub(super) fn word_names(words: &[Word], names: &GlslNames) -> Vec<String> {
    let whole: Vec<&str> = words
        .iter()
        .filter(|word| !word.is_bit_fields)
        .map(|word| names.fields[word.members[0].field].as_str())
        .collect();
    let mut taken: Vec<String> = Vec::new();
    for (index, word) in words.iter().enumerate() {
        if !word.is_bit_fields {
            taken.push(names.fields[word.members[0].field].clone());
            continue;
        }
        let fields: Vec<&str> = word
            .members
            .iter()
            .map(|member| names.fields[member.field].as_str())
            .collect();
        let name = Symbols::bit_fields_word(&fields, None);
        let clashes = whole.contains(&name.as_str()) || taken.contains(&name);
        taken.push(match clashes {
            true => Symbols::bit_fields_word(&fields, Some(index)),
            false => name,
        });
    }
    taken
}
