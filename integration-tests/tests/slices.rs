//! `pack_slice` and `unpack_slice`: a whole G-buffer at once, texel by texel the same words as
//! `pack` and `unpack`, and a clear panic when the lengths disagree.

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

fn check<L: GBufferLayout + Copy + PartialEq + std::fmt::Debug>()
where
    L::Packed: PartialEq + std::fmt::Debug,
{
    // An odd count, so that a vectorised loop has a remainder to handle.
    let texels = texels::<L>(4099);
    let mut packed = vec![texels[0].pack(); texels.len()];
    L::pack_slice(&texels, &mut packed);
    for (texel, words) in texels.iter().zip(&packed) {
        assert_eq!(*words, texel.pack());
    }
    let mut back = vec![texels[0]; texels.len()];
    L::unpack_slice(&packed, &mut back);
    // Compared by their words, so that NaN fields compare too: the texels were unpacked from
    // the mirror's words, so packing what came back gives the same words.
    for (words, texel) in packed.iter().zip(&back) {
        assert_eq!(texel.pack(), *words);
    }
}

#[test]
fn slices_pack_and_unpack_as_texels_do() {
    check::<MobileMetallic>();
    check::<FutureMetallic>();
    check::<gbuffer_testkit::AllFormats>();
}

#[test]
#[should_panic(expected = "pack_slice: 2 texels and 3 packed texels; the lengths must agree")]
fn lengths_that_disagree_are_named() {
    let texels = texels::<MobileMetallic>(2);
    MobileMetallic::pack_slice(&texels, &mut [[0; 4]; 3]);
}

/// One field of each unorm and float format, every channel of a texel holding the same value.
#[derive(gbuffer::GBufferLayout, Clone, Copy, Debug, PartialEq)]
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

/// Every f32 through every channel of every unorm and float format, by the slices (eight texels
/// at a time, in vector instructions) and by `pack` (a texel at a time): not one bit apart.
/// Then every 32-bit word through every channel's decode, compared by the bits of the floats.
/// The f32s run in two halves on two threads.
#[test]
fn the_slices_agree_with_the_texels_on_every_f32_and_every_word() {
    const CHUNK: u64 = 1 << 20;
    let half = |first: u64, end: u64| {
        let mut texels = vec![UnormsAndFloats::splat(0.0); CHUNK as usize];
        let mut packed = vec![[0; 6]; CHUNK as usize];
        let mut back = texels.clone();
        for start in (first..end).step_by(CHUNK as usize) {
            for (offset, texel) in texels.iter_mut().enumerate() {
                *texel = UnormsAndFloats::splat(f32::from_bits((start + offset as u64) as u32));
            }
            UnormsAndFloats::pack_slice(&texels, &mut packed);
            for (texel, words) in texels.iter().zip(&packed) {
                assert_eq!(*words, texel.pack(), "{texel:?}");
            }
            for (offset, words) in packed.iter_mut().enumerate() {
                *words = [(start + offset as u64) as u32; 6];
            }
            UnormsAndFloats::unpack_slice(&packed, &mut back);
            for (words, texel) in packed.iter().zip(&back) {
                // By their bits, so that NaNs compare too.
                assert_eq!(
                    texel.bits(),
                    UnormsAndFloats::unpack(words).bits(),
                    "{words:?}"
                );
            }
        }
    };
    let middle = 1u64 << 31;
    std::thread::scope(|scope| {
        let low = scope.spawn(|| half(0, middle));
        half(middle, 1 << 32);
        low.join().expect("the lower half");
    });
}
