//! The floor of a pack, which both benches time: a texel's `u32`s folded into its words with no
//! conversion (`packing.rs` puts each conversion beside it; `stream.rs` adds arithmetic to it).

/// Each texel's `T` `u32`s (a multiple of its `W` words) folded into its words: word `j` the
/// exclusive or of the texel's `u32`s `j`, `j + W`, ... (`packing.rs`'s `BytesOnly` says why).
pub fn fold_words<const T: usize, const W: usize>(texels: &[[u32; T]], packed: &mut [[u32; W]]) {
    for (texel, words) in texels.iter().zip(packed) {
        let mut folded = [0; W];
        for run in texel.chunks_exact(W) {
            for (word, value) in folded.iter_mut().zip(run) {
                *word ^= value;
            }
        }
        *words = folded;
    }
}
