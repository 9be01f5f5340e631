//! `pack_slice` and `unpack_slice`: a whole G-buffer at once, texel by texel the same words as
//! `pack` and `unpack`, through each copy of the loop this CPU can run (AVX-512, AVX2, plain
//! loops), and a clear panic when the lengths disagree.

use gbuffer::__private::{force_simd, Simd};
use gbuffer::seed_layouts::{FutureMetallic, MobileMetallic};
use gbuffer::GBufferLayout;
use gbuffer_gpu::harness::scalars_per_texel;
use gbuffer_gpu::values::Values;
use gbuffer_testkit::texels::inputs;

/// Texels of `L` from the edge-first test values, through the mirror's own unpack.
fn texels<L: GBufferLayout + Copy>(count: usize) -> Vec<L> {
    let layout = L::layout();
    let scalars = inputs(&layout, 0, count, &mut Values::new(3));
    scalars
        .chunks_exact(scalars_per_texel(&layout))
        .map(|texel| {
            let words = gbuffer_gpu::harness::expected_words(&layout, texel);
            let Ok(packed) = L::Packed::try_from(words.as_slice()) else {
                unreachable!("one word per field")
            };
            L::unpack(&packed)
        })
        .collect()
}

fn check<L: GBufferLayout + Copy + PartialEq + std::fmt::Debug>(simd: Simd)
where
    L::Packed: PartialEq + std::fmt::Debug,
{
    // An odd count, so that a vectorised loop has a remainder to handle.
    let texels = texels::<L>(4099);
    let mut packed = vec![texels[0].pack(); texels.len()];
    L::pack_slice(&texels, &mut packed);
    for (texel, words) in texels.iter().zip(&packed) {
        assert_eq!(*words, texel.pack(), "{simd:?}");
    }
    let mut back = vec![texels[0]; texels.len()];
    L::unpack_slice(&packed, &mut back);
    // Compared by their words, so that NaN fields compare too: the texels were unpacked from
    // the mirror's words, so packing what came back gives the same words.
    for (words, texel) in packed.iter().zip(&back) {
        assert_eq!(texel.pack(), *words, "{simd:?}");
    }
}

#[test]
fn slices_pack_and_unpack_as_texels_do() {
    // The copy is forced for this test's thread alone.
    for simd in [Simd::Best, Simd::Avx2, Simd::Portable] {
        if !force_simd(simd) {
            eprintln!("{simd:?}: this CPU lacks it; its copy is not tested here");
            continue;
        }
        check::<MobileMetallic>(simd);
        check::<FutureMetallic>(simd);
        check::<gbuffer_testkit::AllFormats>(simd);
    }
}

#[test]
#[should_panic(expected = "pack_slice: 2 texels and 3 packed texels; the lengths must agree")]
fn lengths_that_disagree_are_named() {
    let texels = texels::<MobileMetallic>(2);
    MobileMetallic::pack_slice(&texels, &mut [[0; 4]; 3]);
}
