//! The CPU mirror's speed on a whole G-buffer: `pack_slice` and `unpack_slice` of a million
//! texels, against copying the packed bytes (what an upload or a readback costs at the
//! least), for Listing 2.2 (`MobileMetallic`), the other seed layouts and a layout of every
//! format. `pack, plain loop` is the per-texel `pack` in a loop compiled for the default
//! target, what `pack_slice` does without AVX2. Criterion prints each one's throughput in
//! texels (elements) per second, and a table of each layout's rates and their shares of
//! memcpy's closes the run; run with `cargo bench -p gbuffer --bench packing`.

// criterion_group! defines a public function it cannot document.
#![allow(missing_docs)]

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use gbuffer::glam::{IVec2, IVec4, UVec2, UVec4, Vec2, Vec3, Vec4};
use gbuffer::seed_layouts::{ArmTileBlock, FutureMetallic, MobileMetallic, SpecularWorkflow};
use gbuffer::GBufferLayout;

const TEXELS: usize = 1 << 20;

/// One field of each of the twelve formats.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 384)]
struct EveryFormat {
    #[pls(r11f_g11f_b10f)]
    small_floats: Vec3,
    #[pls(r32f)]
    single: f32,
    #[pls(rg16f)]
    halves: Vec2,
    #[pls(rgb10_a2)]
    unorm_10_10_10_2: Vec4,
    #[pls(rgba8)]
    unorm_8: Vec4,
    #[pls(rg16)]
    unorm_16: Vec2,
    #[pls(rgba8i)]
    sint_8: IVec4,
    #[pls(rg16i)]
    sint_16: IVec2,
    #[pls(rgb10_a2ui)]
    uint_10_10_10_2: UVec4,
    #[pls(rgba8ui)]
    uint_8: UVec4,
    #[pls(rg16ui)]
    uint_16: UVec2,
    #[pls(r32ui)]
    uint_32: u32,
}

/// Varied values: a deterministic walk over [0, 1) and a little beyond.
fn value(index: usize, lane: usize) -> f32 {
    ((index * 7919 + lane * 104_729) % 10_007) as f32 / 9_000.0
}

fn v3(index: usize) -> Vec3 {
    Vec3::new(value(index, 0), value(index, 1), value(index, 2))
}

fn v4(index: usize) -> Vec4 {
    Vec4::new(
        value(index, 0),
        value(index, 1),
        value(index, 2),
        value(index, 3),
    )
}

/// Pack, unpack and copy `TEXELS` texels of `make(i)`.
fn layout_group<L: GBufferLayout + Copy>(criterion: &mut Criterion, make: impl Fn(usize) -> L) {
    let texels: Vec<L> = (0..TEXELS).map(make).collect();
    let mut packed = vec![texels[0].pack(); TEXELS];
    let mut unpacked = texels.clone();
    let name = L::layout().name;
    let mut group = criterion.benchmark_group(format!("{name} ({} words)", L::WORDS));
    group.throughput(Throughput::Elements(TEXELS as u64));
    group.bench_function(BenchmarkId::from_parameter("pack_slice"), |bench| {
        bench.iter(|| L::pack_slice(black_box(&texels), black_box(&mut packed)))
    });
    group.bench_function(BenchmarkId::from_parameter("unpack_slice"), |bench| {
        bench.iter(|| L::unpack_slice(black_box(&packed), black_box(&mut unpacked)))
    });
    group.bench_function(BenchmarkId::from_parameter("pack, plain loop"), |bench| {
        bench.iter(|| {
            for (texel, out) in black_box(&texels)
                .iter()
                .zip(black_box(&mut packed).iter_mut())
            {
                *out = texel.pack();
            }
        })
    });
    let source = packed.clone();
    group.bench_function(BenchmarkId::from_parameter("memcpy"), |bench| {
        bench.iter(|| black_box(&mut packed).copy_from_slice(black_box(&source)))
    });
    group.finish();
}

fn slices(criterion: &mut Criterion) {
    layout_group(criterion, |i| MobileMetallic {
        light_accumulation: v3(i),
        depth: value(i, 4),
        normals_roughness: v4(i),
        albedo_metallic: v4(i + 1),
    });
    layout_group(criterion, |i| SpecularWorkflow {
        light_accumulation: v3(i),
        depth: value(i, 4),
        normals_roughness: v4(i),
        base_colour: v3(i + 1),
        specular_colour: v3(i + 2),
    });
    layout_group(criterion, |i| FutureMetallic {
        position_x: value(i, 0) * 100.0,
        position_y: value(i, 1) * 100.0,
        position_z: value(i, 2) * 100.0,
        light_accumulation_rg: Vec2::new(value(i, 3) * 8.0, value(i, 4)),
        light_accumulation_b_normal_x: Vec2::new(value(i, 5), value(i, 6) - 0.5),
        normal_yz: Vec2::new(value(i, 7) - 0.5, value(i, 8) - 0.5),
        roughness_metallic: Vec2::new(value(i, 9), value(i, 10)),
        albedo_or_reflectance: v3(i + 3),
    });
    layout_group(criterion, |i| ArmTileBlock {
        light: v3(i) * 4.0,
        albedo: v3(i + 1),
        normal: v3(i + 2),
        metallic_roughness: Vec2::new(value(i, 3), value(i, 4)),
    });
    layout_group(criterion, |i| {
        let integer = |lane: usize| (i * 31 + lane * 7) as u32;
        EveryFormat {
            small_floats: v3(i) * 100.0,
            single: value(i, 3) - 0.5,
            halves: Vec2::new(value(i, 4) * 300.0, -value(i, 5)),
            unorm_10_10_10_2: v4(i + 1),
            unorm_8: v4(i + 2),
            unorm_16: Vec2::new(value(i, 6), value(i, 7)),
            sint_8: IVec4::new(integer(0) as i32 - 300, integer(1) as i32, -7, 100),
            sint_16: IVec2::new(-(integer(2) as i32), integer(3) as i32),
            uint_10_10_10_2: UVec4::new(integer(4), integer(5), 1023, 2),
            uint_8: UVec4::new(integer(6), 255, 0, integer(7)),
            uint_16: UVec2::new(integer(8), 70_000),
            uint_32: integer(9),
        }
    });
}

criterion_group! {
    name = benches;
    // Short runs: the throughputs settle well within them.
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20);
    targets = slices
}
/// The functions measured per layout, in the table's order.
const FUNCTIONS: [&str; 4] = ["pack_slice", "unpack_slice", "pack, plain loop", "memcpy"];

/// Criterion's mean time of one iteration, in nanoseconds, from the estimates it saved.
fn mean_nanoseconds(folder: &std::path::Path, group: &str, function: &str) -> Option<f64> {
    let path = folder.join(group).join(function).join("new/estimates.json");
    let estimates: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()?;
    estimates["mean"]["point_estimate"].as_f64()
}

/// The side-by-side table: millions of texels a second, and pack's and unpack's shares of
/// memcpy's rate, for the layouts criterion has measured.
fn print_table() {
    // Criterion writes under the target folder; the bench runs from target/<profile>/deps.
    let folder = std::env::var_os("CRITERION_HOME")
        .map(std::path::PathBuf::from)
        .or_else(|| {
            let exe = std::env::current_exe().ok()?;
            Some(exe.parent()?.parent()?.parent()?.join("criterion"))
        });
    let Some(folder) = folder else { return };
    println!(
        "\n{TEXELS} texels, one thread; Mtexel/s (criterion's mean), pack and unpack as shares of memcpy"
    );
    println!(
        "{:<28} {:>10} {:>12} {:>16} {:>8} {:>6} {:>7}",
        "layout", FUNCTIONS[0], FUNCTIONS[1], FUNCTIONS[2], FUNCTIONS[3], "pack", "unpack"
    );
    let groups = [
        "MobileMetallic (4 words)",
        "SpecularWorkflow (5 words)",
        "FutureMetallic (8 words)",
        "ArmTileBlock (4 words)",
        "EveryFormat (12 words)",
    ];
    for group in groups {
        let rates: Option<Vec<f64>> = FUNCTIONS
            .iter()
            .map(|function| {
                mean_nanoseconds(&folder, group, function).map(|ns| TEXELS as f64 / ns * 1e3)
            })
            .collect();
        if let Some(rates) = rates {
            println!(
                "{group:<28} {:>10.0} {:>12.0} {:>16.0} {:>8.0} {:>5.0}% {:>6.0}%",
                rates[0],
                rates[1],
                rates[2],
                rates[3],
                100.0 * rates[0] / rates[3],
                100.0 * rates[1] / rates[3]
            );
        }
    }
}

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    print_table();
}
