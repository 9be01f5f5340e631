//! `pack_slice` and `unpack_slice`: a whole G-buffer at once, texel by texel the same words as
//! `pack` and `unpack`, and a clear panic when the lengths disagree.

use gbuffer::seed_layouts::{FutureMetallic, MobileMetallic};
use gbuffer::GBufferLayout;
use gbuffer_testkit::harness::scalars_per_texel;
use gbuffer_testkit::texels::inputs;
use gbuffer_testkit::values::Values;

/// Texels of `L` from the edge-first test values, through the mirror's own unpack.
fn texels<L: GBufferLayout + Copy>(count: usize) -> Vec<L> {
    let layout = L::layout();
    let scalars = inputs(&layout, 0, count, &mut Values::new(3));
    scalars
        .chunks_exact(scalars_per_texel(&layout))
        .map(|texel| {
            let words = gbuffer_testkit::harness::expected_words(&layout, texel);
            let Ok(packed) = L::Packed::try_from(words.as_slice()) else {
                unreachable!("one word per field")
            };
            L::unpack(&packed)
        })
        .collect()
}

fn check<L: GBufferLayout + Copy + PartialEq + std::fmt::Debug>() {
    let texels = texels::<L>(4099);
    let mut words = vec![0u32; texels.len() * L::WORDS];
    L::pack_slice(&texels, &mut words);
    for (texel, chunk) in texels.iter().zip(words.chunks_exact(L::WORDS)) {
        assert_eq!(chunk, texel.pack().as_ref());
    }
    let mut back = vec![texels[0]; texels.len()];
    L::unpack_slice(&words, &mut back);
    // Compared by their words, so that NaN fields compare too: the texels were unpacked from
    // the mirror's words, so packing what came back gives the same words.
    for (chunk, texel) in words.chunks_exact(L::WORDS).zip(&back) {
        assert_eq!(texel.pack().as_ref(), chunk);
    }
}

#[test]
fn slices_pack_and_unpack_as_texels_do() {
    check::<MobileMetallic>();
    check::<FutureMetallic>();
}

#[test]
#[should_panic(expected = "pack_slice: 2 texels of 4 words need 8 words, not 7")]
fn a_short_buffer_is_named() {
    let texels = texels::<MobileMetallic>(2);
    MobileMetallic::pack_slice(&texels, &mut [0; 7]);
}
