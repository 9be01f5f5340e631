//! `pack_slice` and `unpack_slice` against `pack` and `unpack` for every f32 and every word:
//! the slices' vector code (each copy of it the CPU can run: AVX-512's sixteen texels at a
//! time and AVX2's eight on every f32 and word, plain loops' eight on one in eight) and the
//! texel code, not one bit apart.
//! Exhaustive, so it runs in an optimised build: `cargo test --release -p gbuffer --test
//! slices_every_f32` (CI's `exhaustive` step). In a debug build it is ignored, saying so.
//! `integration-tests/tests/slices.rs` holds the slices to the texels on the edge cases and the
//! seed layouts in every build.

use gbuffer::__private::{force_simd, Simd};
use gbuffer::GBufferLayout;

/// One field of each unorm and float format, every channel of a texel holding the same value.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 256)]
struct UnormsAndFloats {
    #[pls(rgba8)]
    unorm_8: gbuffer::glam::Vec4,
    #[pls(rg16)]
    unorm_16: gbuffer::glam::Vec2,
    #[pls(rgb10_a2)]
    unorm_10_10_10_2: gbuffer::glam::Vec4,
    #[pls(rg16f)]
    halves: gbuffer::glam::Vec2,
    #[pls(r11f_g11f_b10f)]
    small_floats: gbuffer::glam::Vec3,
    #[pls(r32f)]
    single: f32,
}

impl UnormsAndFloats {
    /// Every component's bits.
    fn bits(&self) -> [u32; 16] {
        let (a, b, c) = (self.unorm_8, self.unorm_16, self.unorm_10_10_10_2);
        let (d, e) = (self.halves, self.small_floats);
        [
            a.x,
            a.y,
            a.z,
            a.w,
            b.x,
            b.y,
            c.x,
            c.y,
            c.z,
            c.w,
            d.x,
            d.y,
            e.x,
            e.y,
            e.z,
            self.single,
        ]
        .map(f32::to_bits)
    }

    fn splat(value: f32) -> Self {
        use gbuffer::glam::{Vec2, Vec3, Vec4};
        UnormsAndFloats {
            unorm_8: Vec4::splat(value),
            unorm_16: Vec2::splat(value),
            unorm_10_10_10_2: Vec4::splat(value),
            halves: Vec2::splat(value),
            small_floats: Vec3::splat(value),
            single: value,
        }
    }
}

/// Every f32 through every channel of every unorm and float format, by the slices (many texels
/// at a time, in vector instructions, through each copy) and by `pack` (a texel at a time):
/// not one bit apart.
/// Then every 32-bit word through every channel's decode, compared by the bits of the floats.
/// The f32s run on two threads.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "exhaustive: run optimised, `cargo test --release -p gbuffer --test slices_every_f32`"
)]
fn the_slices_agree_with_the_texels_on_every_f32_and_every_word() {
    // Whether any pair of a chunk differs: the XOR of every word of each pair, ORed together,
    // with no branch per texel (a tenth faster than an assertion per texel); a chunk that
    // differs is compared again texel by texel, to name the first.
    fn differ<const N: usize>(pairs: impl Iterator<Item = ([u32; N], [u32; N])>) -> bool {
        let differences = pairs.fold([0; N], |mut differences, (a, b)| {
            for ((difference, a), b) in differences.iter_mut().zip(a).zip(b) {
                *difference |= a ^ b;
            }
            differences
        });
        differences != [0; N]
    }

    // Each copy of the loop this CPU can run: the widest it has (AVX-512 where it has it) and
    // AVX2, forced, on every chunk; plain loops, forced, on one chunk in eight, spread over
    // the f32s (the same source as the AVX2 copy's, compiled for the baseline CPU, whose
    // missing rounding instructions make it as slow as the other two together). Each chunk's
    // texel results are computed once for all.
    // A copy this CPU lacks would run plain loops under its name: skipped, saying so.
    let here: Vec<Simd> = [Simd::Best, Simd::Avx2, Simd::Portable]
        .into_iter()
        .filter(|&simd| {
            let runs = force_simd(simd);
            if !runs {
                eprintln!("{simd:?}: this CPU lacks it; its copy is not tested here");
            }
            runs
        })
        .collect();
    let copies = |start: u64| {
        let portable = (start / CHUNK) % 16 < 2;
        here.clone()
            .into_iter()
            .filter(move |&simd| simd != Simd::Portable || portable)
    };
    const CHUNK: u64 = 1 << 20;
    // Worker 0 takes the even chunks and worker 1 the odd, so that both end together.
    let worker = |worker: u64| {
        let mut texels = vec![UnormsAndFloats::splat(0.0); CHUNK as usize];
        let mut packed = vec![[0; 6]; CHUNK as usize];
        let mut expected = packed.clone();
        let mut back = texels.clone();
        let mut expected_bits = vec![[0; 16]; CHUNK as usize];
        for start in (worker * CHUNK..1 << 32).step_by(2 * CHUNK as usize) {
            for (offset, texel) in texels.iter_mut().enumerate() {
                *texel = UnormsAndFloats::splat(f32::from_bits((start + offset as u64) as u32));
            }
            for (texel, words) in texels.iter().zip(&mut expected) {
                *words = texel.pack();
            }
            for simd in copies(start) {
                // A copy of `here`, which this CPU has: the answer is known.
                let _ = force_simd(simd);
                UnormsAndFloats::pack_slice(&texels, &mut packed);
                if differ(expected.iter().copied().zip(packed.iter().copied())) {
                    for (texel, words) in texels.iter().zip(&packed) {
                        assert_eq!(*words, texel.pack(), "{simd:?}: {texel:?}");
                    }
                }
            }
            for (offset, words) in packed.iter_mut().enumerate() {
                *words = [(start + offset as u64) as u32; 6];
            }
            // By their bits, so that NaNs compare too.
            for (words, bits) in packed.iter().zip(&mut expected_bits) {
                *bits = UnormsAndFloats::unpack(words).bits();
            }
            for simd in copies(start) {
                // A copy of `here`, which this CPU has: the answer is known.
                let _ = force_simd(simd);
                UnormsAndFloats::unpack_slice(&packed, &mut back);
                let unpacked = back.iter().map(UnormsAndFloats::bits);
                if differ(expected_bits.iter().copied().zip(unpacked)) {
                    for (words, texel) in packed.iter().zip(&back) {
                        let bits = UnormsAndFloats::unpack(words).bits();
                        assert_eq!(texel.bits(), bits, "{simd:?}: {words:?}");
                    }
                }
            }
        }
    };
    std::thread::scope(|scope| {
        let odd = scope.spawn(|| worker(1));
        worker(0);
        odd.join().expect("the odd chunks' worker");
    });
}
