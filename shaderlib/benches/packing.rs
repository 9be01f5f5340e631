//! The CPU mirror's speed on a whole G-buffer: `pack_slice` and `unpack_slice` of a million
//! texels of each seed layout, against copying the same bytes (what an upload or a readback
//! costs at the least). Prints a table; run with `cargo bench -p gbuffer --bench packing`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use gbuffer::glam::{Vec2, Vec3, Vec4};
use gbuffer::seed_layouts::{ArmTileBlock, FutureMetallic, MobileMetallic, SpecularWorkflow};
use gbuffer::GBufferLayout;

const TEXELS: usize = 1 << 20;
const RUNS: usize = 9;

/// The median time of `RUNS` runs of `work`.
fn median(mut work: impl FnMut()) -> Duration {
    let mut times: Vec<Duration> = (0..RUNS)
        .map(|_| {
            let start = Instant::now();
            work();
            start.elapsed()
        })
        .collect();
    times.sort();
    times[RUNS / 2]
}

/// Texels of varied values: a deterministic walk over [0, 1) and a little beyond.
fn value(index: usize, lane: usize) -> f32 {
    ((index * 7919 + lane * 104_729) % 10_007) as f32 / 9_000.0
}

/// Millions of texels a second for `texels`, packing and unpacking, and copying as many bytes.
fn measure<L: GBufferLayout + Copy>(texels: &[L]) -> (f64, f64, f64) {
    let mut words = vec![0u32; texels.len() * L::WORDS];
    let mut back = texels.to_vec();
    let pack = median(|| L::pack_slice(black_box(texels), black_box(&mut words)));
    let unpack = median(|| L::unpack_slice(black_box(&words), black_box(&mut back)));
    let source = words.clone();
    let copy = median(|| black_box(&mut words).copy_from_slice(black_box(&source)));
    let rate = |time: Duration| texels.len() as f64 / time.as_secs_f64() / 1e6;
    (rate(pack), rate(unpack), rate(copy))
}

fn row<L: GBufferLayout + Copy>(make: impl Fn(usize) -> L) {
    let texels: Vec<L> = (0..TEXELS).map(make).collect();
    let (pack, unpack, copy) = measure(&texels);
    println!(
        "{:<18} {:>5} {:>12.1} {:>12.1} {:>12.1} {:>8.1}% {:>8.1}%",
        L::layout().name,
        L::WORDS,
        pack,
        unpack,
        copy,
        100.0 * pack / copy,
        100.0 * unpack / copy
    );
}

fn main() {
    println!("{TEXELS} texels, median of {RUNS} runs, one thread; Mtexel/s");
    println!(
        "{:<18} {:>5} {:>12} {:>12} {:>12} {:>9} {:>9}",
        "layout", "words", "pack_slice", "unpack_slice", "copy", "pack", "unpack"
    );
    let v3 = |i: usize| Vec3::new(value(i, 0), value(i, 1), value(i, 2));
    let v4 = |i: usize| Vec4::new(value(i, 0), value(i, 1), value(i, 2), value(i, 3));
    row(|i| MobileMetallic {
        light_accumulation: v3(i),
        depth: value(i, 4),
        normals_roughness: v4(i),
        albedo_metallic: v4(i + 1),
    });
    row(|i| SpecularWorkflow {
        light_accumulation: v3(i),
        depth: value(i, 4),
        normals_roughness: v4(i),
        base_colour: v3(i + 1),
        specular_colour: v3(i + 2),
    });
    row(|i| FutureMetallic {
        position_x: value(i, 0) * 100.0,
        position_y: value(i, 1) * 100.0,
        position_z: value(i, 2) * 100.0,
        light_accumulation_rg: Vec2::new(value(i, 3) * 8.0, value(i, 4)),
        light_accumulation_b_normal_x: Vec2::new(value(i, 5), value(i, 6) - 0.5),
        normal_yz: Vec2::new(value(i, 7) - 0.5, value(i, 8) - 0.5),
        roughness_metallic: Vec2::new(value(i, 9), value(i, 10)),
        albedo_or_reflectance: v3(i + 3),
    });
    row(|i| ArmTileBlock {
        light: v3(i) * 4.0,
        albedo: v3(i + 1),
        normal: v3(i + 2),
        metallic_roughness: Vec2::new(value(i, 3), value(i, 4)),
    });
}
