//! The CPU mirror's speed on a whole G-buffer: `pack_slice` and `unpack_slice` of a million
//! texels, against copying the packed bytes (what an upload or a readback costs at the least),
//! for Listing 2.2 (`MobileMetallic`), a 256-bit layout of eight formats, the other seed
//! layouts, and per format a layout of four words of that format alone; and, for the first two,
//! the same bytes moved with no conversion at all (the floor memory sets, `BytesOnly`).
//! Criterion prints each one's throughput in texels (elements) per second; the run ends with a
//! table of the rates and of pack's and unpack's shares of memcpy's, and one of the first two
//! layouts' pack and unpack rates as shares of their floor's, each conversion timed back to
//! back with the floor's two loops in rounds (`shares_of_floor`); it also writes both to
//! `target/figures/packing.md` for the guide. Run with `cargo bench -p gbuffer --bench
//! packing`.
// criterion_group! defines a public function it cannot document.
#![allow(missing_docs)]

use std::hint::black_box;
use std::marker::PhantomData;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, SystemTime};

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use gbuffer::__private::{convert_lanes, Isa, Lanes};
use gbuffer::glam::{IVec2, IVec4, UVec2, UVec4, Vec2, Vec3, Vec4};
use gbuffer::seed_layouts::{ArmTileBlock, FutureMetallic, MobileMetallic, SpecularWorkflow};
use gbuffer::GBufferLayout;

mod floor;
mod rounds;
use floor::fold_words;
use rounds::{quartiles, rounds, target_folder, time, write_figures, WARM_UP_ROUNDS};

const TEXELS: usize = 1 << 20;

/// Varied values: a deterministic walk over [0, 1) and a little beyond.
fn value(index: usize, lane: usize) -> f32 {
    ((index * 7919 + lane * 104_729) % 10_007) as f32 / 9_000.0
}

/// A field's value for texel `index`: floats from [`value`], integers that walk past their
/// formats' ranges (which saturate) and back.
trait Sample {
    fn sample(index: usize) -> Self;
}

impl Sample for f32 {
    fn sample(index: usize) -> f32 {
        value(index, 0)
    }
}

impl Sample for Vec2 {
    fn sample(index: usize) -> Vec2 {
        Vec2::new(value(index, 0), value(index, 1))
    }
}

impl Sample for Vec3 {
    fn sample(index: usize) -> Vec3 {
        Vec3::new(value(index, 0), value(index, 1), value(index, 2))
    }
}

impl Sample for Vec4 {
    fn sample(index: usize) -> Vec4 {
        Vec4::new(
            value(index, 0),
            value(index, 1),
            value(index, 2),
            value(index, 3),
        )
    }
}

fn integer(index: usize, lane: usize) -> i32 {
    ((index * 31 + lane * 7919) % 140_001) as i32 - 70_000
}

impl Sample for u32 {
    fn sample(index: usize) -> u32 {
        integer(index, 0).unsigned_abs()
    }
}

impl Sample for UVec2 {
    fn sample(index: usize) -> UVec2 {
        UVec2::new(u32::sample(index), u32::sample(index + 1))
    }
}

impl Sample for UVec4 {
    fn sample(index: usize) -> UVec4 {
        UVec4::new(
            u32::sample(index),
            u32::sample(index + 1),
            u32::sample(index + 2),
            u32::sample(index + 3),
        )
    }
}

impl Sample for IVec2 {
    fn sample(index: usize) -> IVec2 {
        IVec2::new(integer(index, 0), integer(index, 1))
    }
}

impl Sample for IVec4 {
    fn sample(index: usize) -> IVec4 {
        IVec4::new(
            integer(index, 0),
            integer(index, 1),
            integer(index, 2),
            integer(index, 3),
        )
    }
}

/// The floor of a pack and an unpack: a layout's bytes moved with no conversion. A texel is
/// read as the `u32`s of its fields (`T` of them, a multiple of its `W` words; a layout
/// qualifies when its fields fill it, with no padding) and folded into its words, word `j` the
/// exclusive or of the texel's `u32`s `j`, `j + W`, ... (pack), or written back from them, each
/// run of `W` `u32`s a copy of the words (unpack): every byte read and written once, in order,
/// in loops the compiler turns into vector loads, exclusive ors and stores.
///
/// Two loops move them ([`Mover`]), because neither is the faster on every CPU: the
/// conversions' own loop, with its software prefetches, and a plain loop that leaves the
/// fetching to the hardware's prefetcher. [`shares_of_floor`] times both each round and takes
/// the faster as the floor.
trait BytesOnly: GBufferLayout + Sized {
    fn move_in(mover: Mover, texels: &[Self], packed: &mut [Self::Packed]);
    fn move_out(mover: Mover, packed: &[Self::Packed], texels: &mut [Self]);
}

/// A loop that moves a layout's bytes with no conversion ([`BytesOnly`]).
#[derive(Clone, Copy, Debug)]
enum Mover {
    /// Through the conversions' loop (`__private::convert_lanes`: the same chunks of texels,
    /// the same copy for the CPU, the same prefetches), so that what differs from a
    /// conversion is the conversion alone.
    ConversionsLoop,
    /// One pass over the slices, with no software prefetch.
    Plain,
}

fn spread_words<const T: usize, const W: usize>(packed: &[[u32; W]], texels: &mut [[u32; T]]) {
    for (words, texel) in packed.iter().zip(texels) {
        for run in texel.chunks_exact_mut(W) {
            run.copy_from_slice(words);
        }
    }
}

/// [`fold_words`] as the conversions' loop runs a pack ([`Lanes`]).
struct Fold<L>(PhantomData<L>);

/// [`spread_words`] as the conversions' loop runs an unpack.
struct Spread<L>(PhantomData<L>);

/// [`BytesOnly`] for a layout of f32, u32 and i32 components: its size in `u32`s, and its
/// words.
macro_rules! bytes_only {
    ($layout:ident) => {
        impl BytesOnly for $layout {
            fn move_in(mover: Mover, texels: &[$layout], packed: &mut [Self::Packed]) {
                assert_no_padding::<$layout, { size_of::<$layout>() / 4 }>();
                match mover {
                    Mover::ConversionsLoop => convert_lanes::<Fold<$layout>, _, _>(texels, packed),
                    // SAFETY: no padding, just asserted.
                    Mover::Plain => fold_words(unsafe { Fold::<$layout>::u32s(texels) }, packed),
                }
            }

            fn move_out(mover: Mover, packed: &[Self::Packed], texels: &mut [$layout]) {
                assert_no_padding::<$layout, { size_of::<$layout>() / 4 }>();
                match mover {
                    Mover::ConversionsLoop => {
                        convert_lanes::<Spread<$layout>, _, _>(packed, texels)
                    }
                    // SAFETY: no padding, just asserted.
                    Mover::Plain => {
                        spread_words(packed, unsafe { Fold::<$layout>::u32s_mut(texels) })
                    }
                }
            }
        }

        impl Fold<$layout> {
            /// `texels` as arrays of their `u32`s.
            ///
            /// # Safety
            ///
            /// The layout must have no padding ([`assert_no_padding`]; `move_in` and
            /// `move_out` assert it before they call anything that calls this).
            #[inline(always)]
            unsafe fn u32s(texels: &[$layout]) -> &[[u32; size_of::<$layout>() / 4]] {
                // SAFETY: a texel is exactly its fields' u32s (the caller's promise: no
                // padding, so every byte is initialised), aligned for u32 (its fields are).
                unsafe { std::slice::from_raw_parts(texels.as_ptr().cast(), texels.len()) }
            }

            /// [`Self::u32s`], to write.
            ///
            /// # Safety
            ///
            /// As [`Self::u32s`].
            #[inline(always)]
            unsafe fn u32s_mut(texels: &mut [$layout]) -> &mut [[u32; size_of::<$layout>() / 4]] {
                // SAFETY: as in `u32s`; and any bits are a valid f32, u32 or i32 component.
                unsafe { std::slice::from_raw_parts_mut(texels.as_mut_ptr().cast(), texels.len()) }
            }
        }

        impl Lanes<$layout, <$layout as GBufferLayout>::Packed> for Fold<$layout> {
            #[inline(always)]
            fn many<I: Isa, const N: usize>(
                texels: &[$layout; N],
                packed: &mut [<$layout as GBufferLayout>::Packed; N],
            ) {
                // SAFETY: the callers of `convert_lanes` asserted no padding (`move_in`).
                fold_words(unsafe { Self::u32s(texels) }, packed);
            }

            #[inline(always)]
            fn one(texel: &$layout) -> <$layout as GBufferLayout>::Packed {
                let mut packed = [Default::default()];
                // SAFETY: as in `many`.
                fold_words(
                    unsafe { Self::u32s(std::slice::from_ref(texel)) },
                    &mut packed,
                );
                packed[0]
            }
        }

        impl Lanes<<$layout as GBufferLayout>::Packed, $layout> for Spread<$layout> {
            #[inline(always)]
            fn many<I: Isa, const N: usize>(
                packed: &[<$layout as GBufferLayout>::Packed; N],
                texels: &mut [$layout; N],
            ) {
                // SAFETY: the callers of `convert_lanes` asserted no padding (`move_out`).
                spread_words(packed, unsafe { Fold::<$layout>::u32s_mut(texels) });
            }

            #[inline(always)]
            fn one(packed: &<$layout as GBufferLayout>::Packed) -> $layout {
                // SAFETY: the texel's fields are f32, u32 and i32 components, for which zero
                // bits are a value.
                let mut texel: [$layout; 1] = unsafe { std::mem::zeroed() };
                // SAFETY: as in `many`.
                let words = unsafe { Fold::<$layout>::u32s_mut(&mut texel) };
                spread_words(std::slice::from_ref(packed), words);
                texel[0]
            }
        }
    };
}

/// `L` is `T` u32s, a multiple of its words: its fields' components number `T` and fill its
/// size.
fn assert_no_padding<L: GBufferLayout, const T: usize>() {
    let components: usize = L::layout()
        .fields
        .iter()
        .map(|field| field.ty.components)
        .sum();
    assert!(
        components == T
            && size_of::<L>() == 4 * T
            && align_of::<L>() >= 4
            && T.is_multiple_of(L::WORDS),
        "{} is not {T} u32s, a multiple of its words",
        L::layout().name
    );
}

/// The 256-bit layout of eight formats the speed goal names.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 256)]
struct EightFormats {
    #[pls(r11f_g11f_b10f)]
    small_floats: Vec3,
    #[pls(rg16f)]
    halves: Vec2,
    #[pls(rg16)]
    unorm_16: Vec2,
    #[pls(rgba8i)]
    sint_8: IVec4,
    #[pls(rgb10_a2ui)]
    uint_10_10_10_2: UVec4,
    #[pls(rgba8)]
    unorm_8: Vec4,
    #[pls(r32f)]
    single: f32,
    #[pls(rgb10_a2)]
    unorm_10_10_10_2: Vec4,
}

bytes_only!(MobileMetallic);
bytes_only!(EightFormats);

/// Layouts of four words of one format each, named after it: each format's own rate; and
/// `one_format_groups`, which measures them in the order listed.
macro_rules! one_formats {
    ($($name:ident, $format:ident, $type:ident;)+) => {
        $(
            #[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
            struct $name {
                #[pls($format)]
                a: $type,
                #[pls($format)]
                b: $type,
                #[pls($format)]
                c: $type,
                #[pls($format)]
                d: $type,
            }

            impl Sample for $name {
                fn sample(index: usize) -> $name {
                    let at = |word: usize| <$type>::sample(index * 4 + word);
                    $name {
                        a: at(0),
                        b: at(1),
                        c: at(2),
                        d: at(3),
                    }
                }
            }
        )+

        /// The one-format layouts' rows of the table.
        fn one_format_groups(criterion: &mut Criterion) {
            $(
                layout_group(
                    criterion,
                    concat!("4 words of `", stringify!($format), "`"),
                    $name::sample,
                );
            )+
        }
    };
}

one_formats! {
    R11fG11fB10f, r11f_g11f_b10f, Vec3;
    R32f, r32f, f32;
    Rg16f, rg16f, Vec2;
    Rgb10A2, rgb10_a2, Vec4;
    Rgba8, rgba8, Vec4;
    Rg16, rg16, Vec2;
    Rgba8i, rgba8i, IVec4;
    Rg16i, rg16i, IVec2;
    Rgb10A2ui, rgb10_a2ui, UVec4;
    Rgba8ui, rgba8ui, UVec4;
    Rg16ui, rg16ui, UVec2;
    R32ui, r32ui, u32;
}

/// The functions measured per layout, in the table's order.
const FUNCTIONS: [&str; 3] = ["pack_slice", "unpack_slice", "memcpy"];

/// Criterion's group name of layout `L`.
fn group_name<L: GBufferLayout>() -> String {
    format!("{} ({} words)", L::layout().name, L::WORDS)
}

/// A row of the tables: a layout's criterion group, its name in the tables and, for a layout
/// measured beside its floor ([`floor_groups`]), its conversions' shares of the floor.
struct Row {
    group: String,
    label: &'static str,
    floor: Option<Floor>,
}

/// The tables' rows, in the order the layouts were measured.
static ROWS: Mutex<Vec<Row>> = Mutex::new(Vec::new());

/// Adds `row` to [`ROWS`].
fn push_row(group: String, label: &'static str, floor: Option<Floor>) {
    let row = Row {
        group,
        label,
        floor,
    };
    ROWS.lock().expect("one thread").push(row);
}

/// Pack, unpack and copy `TEXELS` texels of `make(i)`, the row `label` of the tables.
fn layout_group<L: GBufferLayout + Copy>(
    criterion: &mut Criterion,
    label: &'static str,
    make: impl Fn(usize) -> L,
) {
    let group = group_name::<L>();
    measure_layout(criterion, &group, make);
    push_row(group, label, None);
}

/// `L`'s conversions in criterion's group `group` ([`measure`] of its `pack_slice` and
/// `unpack_slice`): whether the filter let it run.
fn measure_layout<L: GBufferLayout + Copy>(
    criterion: &mut Criterion,
    group: &str,
    make: impl Fn(usize) -> L,
) -> bool {
    measure(
        criterion,
        group.to_owned(),
        L::pack_slice,
        L::unpack_slice,
        make,
    )
}

/// [`layout_group`], the row `labels[0]`, and the same of the layout's bytes moved with no
/// conversion through the conversions' loop ([`BytesOnly`]), the row `labels[1]`; then, where
/// criterion's filter let the layout's group run, the conversions' shares of the floor, timed
/// back to back ([`shares_of_floor`]).
fn floor_groups<L: BytesOnly + Copy>(
    criterion: &mut Criterion,
    labels: [&'static str; 2],
    make: impl Fn(usize) -> L + Copy,
) {
    let group = group_name::<L>();
    let ran = measure_layout(criterion, &group, make);
    let bytes_only = format!("{group} bytes only");
    let move_in =
        |texels: &[L], packed: &mut [L::Packed]| L::move_in(Mover::ConversionsLoop, texels, packed);
    let move_out = |packed: &[L::Packed], texels: &mut [L]| {
        L::move_out(Mover::ConversionsLoop, packed, texels)
    };
    measure(criterion, bytes_only.clone(), move_in, move_out, make);
    push_row(group, labels[0], ran.then(|| shares_of_floor(make)));
    push_row(bytes_only, labels[1], None);
}

/// A conversion's rate as shares of its floor's: pack's and unpack's `[lower quartile,
/// median, upper quartile]`, each a share (1.0: as fast as the floor).
type Shares = [[f64; 3]; 2];

/// What [`shares_of_floor`] measured of a layout.
struct Floor {
    shares: Shares,
    /// The median times, nanoseconds a texel: pack's and unpack's, each `[the conversion, the
    /// floor through the conversions' loop, the floor through the plain loop]` ([`Mover`]).
    nanoseconds: [[f64; 3]; 2],
}

/// Pack's and unpack's rates as shares of the floor's ([`BytesOnly`]), timed in rounds: each
/// round times one pass of `TEXELS` texels through the conversion and one through each of the
/// floor's loops ([`Mover`]), back to back (the unpack's in the pack's order reversed, so that
/// neither side always goes first), and its share is the faster loop's time over the
/// conversion's; the shares are the median and quartiles over the rounds.
///
/// Why rounds, not criterion's two means: a machine shared with others (a virtual machine's
/// neighbours, its memory bus) changes speed from second to second; two rates measured several
/// seconds apart then differ by that change as much as by the conversion (on CI's kind of
/// machine the same layout's floor moved by 3x between runs), while passes a few milliseconds
/// apart see the same machine. The median ignores the rounds a burst of other load hit.
fn shares_of_floor<L: BytesOnly + Copy>(make: impl Fn(usize) -> L) -> Floor {
    let texels: Vec<L> = (0..TEXELS).map(make).collect();
    let mut packed = vec![texels[0].pack(); TEXELS];
    let mut unpacked = texels.clone();
    let mut shares = [Vec::new(), Vec::new()];
    let mut times: [[Vec<f64>; 3]; 2] = Default::default();
    const MOVERS: [Mover; 2] = [Mover::ConversionsLoop, Mover::Plain];
    for round in 0..WARM_UP_ROUNDS + rounds() {
        let pack = time(|| L::pack_slice(black_box(&texels), black_box(&mut packed)));
        let floor = MOVERS
            .map(|mover| time(|| L::move_in(mover, black_box(&texels), black_box(&mut packed))));
        // The unpack in the other order, so that neither side always goes first.
        let mut floor_out = [0.0; 2];
        for (at, mover) in MOVERS.into_iter().enumerate().rev() {
            floor_out[at] =
                time(|| L::move_out(mover, black_box(&packed), black_box(&mut unpacked)));
        }
        let unpack = time(|| L::unpack_slice(black_box(&packed), black_box(&mut unpacked)));
        if round >= WARM_UP_ROUNDS {
            shares[0].push(floor[0].min(floor[1]) / pack);
            shares[1].push(floor_out[0].min(floor_out[1]) / unpack);
            let measured = [
                [pack, floor[0], floor[1]],
                [unpack, floor_out[0], floor_out[1]],
            ];
            for (times, measured) in times.iter_mut().zip(measured) {
                for (times, seconds) in times.iter_mut().zip(measured) {
                    times.push(seconds * 1e9 / TEXELS as f64);
                }
            }
        }
    }
    Floor {
        shares: shares.map(quartiles),
        nanoseconds: times.map(|direction| direction.map(|times| quartiles(times)[1])),
    }
}

/// Pack through `pack`, unpack through `unpack`, and copy `TEXELS` texels of `make(i)`:
/// criterion's group `group`. Returns whether criterion ran them (its filter may skip them).
fn measure<L: GBufferLayout + Copy>(
    criterion: &mut Criterion,
    group: String,
    pack: impl Fn(&[L], &mut [L::Packed]),
    unpack: impl Fn(&[L::Packed], &mut [L]),
    make: impl Fn(usize) -> L,
) -> bool {
    let texels: Vec<L> = (0..TEXELS).map(make).collect();
    let mut packed = vec![texels[0].pack(); TEXELS];
    let mut unpacked = texels.clone();
    let mut ran = false;
    let mut group = criterion.benchmark_group(group);
    group.throughput(Throughput::Elements(TEXELS as u64));
    group.bench_function(BenchmarkId::from_parameter(FUNCTIONS[0]), |bench| {
        ran = true;
        bench.iter(|| pack(black_box(&texels), black_box(&mut packed)))
    });
    group.bench_function(BenchmarkId::from_parameter(FUNCTIONS[1]), |bench| {
        bench.iter(|| unpack(black_box(&packed), black_box(&mut unpacked)))
    });
    let source = packed.clone();
    group.bench_function(BenchmarkId::from_parameter(FUNCTIONS[2]), |bench| {
        bench.iter(|| black_box(&mut packed).copy_from_slice(black_box(&source)))
    });
    group.finish();
    ran
}

fn mobile_metallic(i: usize) -> MobileMetallic {
    MobileMetallic {
        light_accumulation: Vec3::sample(i),
        depth: value(i, 4),
        normals_roughness: Vec4::sample(i),
        albedo_metallic: Vec4::sample(i + 1),
    }
}

fn eight_formats(i: usize) -> EightFormats {
    EightFormats {
        small_floats: Vec3::sample(i) * 100.0,
        halves: Vec2::sample(i) * 300.0,
        unorm_16: Vec2::sample(i + 1),
        sint_8: IVec4::sample(i),
        uint_10_10_10_2: UVec4::sample(i),
        unorm_8: Vec4::sample(i + 2),
        single: value(i, 3) - 0.5,
        unorm_10_10_10_2: Vec4::sample(i + 3),
    }
}

fn slices(criterion: &mut Criterion) {
    floor_groups(
        criterion,
        [
            "MobileMetallic (Listing 2.2)",
            "Listing 2.2's bytes, no conversion",
        ],
        mobile_metallic,
    );
    floor_groups(
        criterion,
        [
            "eight formats, 256 bits",
            "eight formats' bytes, no conversion",
        ],
        eight_formats,
    );
    layout_group(criterion, "SpecularWorkflow", |i| SpecularWorkflow {
        light_accumulation: Vec3::sample(i),
        depth: value(i, 4),
        normals_roughness: Vec4::sample(i),
        base_colour: Vec3::sample(i + 1),
        specular_colour: Vec3::sample(i + 2),
    });
    layout_group(criterion, "FutureMetallic", |i| FutureMetallic {
        position_x: value(i, 0) * 100.0,
        position_y: value(i, 1) * 100.0,
        position_z: value(i, 2) * 100.0,
        light_accumulation_rg: Vec2::new(value(i, 3) * 8.0, value(i, 4)),
        light_accumulation_b_normal_x: Vec2::new(value(i, 5), value(i, 6) - 0.5),
        normal_yz: Vec2::new(value(i, 7) - 0.5, value(i, 8) - 0.5),
        roughness_metallic: Vec2::new(value(i, 9), value(i, 10)),
        albedo_or_reflectance: Vec3::sample(i + 3),
    });
    layout_group(criterion, "ArmTileBlock", |i| ArmTileBlock {
        light: Vec3::sample(i) * 4.0,
        albedo: Vec3::sample(i + 1),
        normal: Vec3::sample(i + 2),
        metallic_roughness: Vec2::new(value(i, 3), value(i, 4)),
    });
    one_format_groups(criterion);
}

/// Short runs: the throughputs settle well within them. Shorter still where
/// `GBUFFER_TIMING=short` asks, as it does for the GPU's timing protocol
/// (`gbuffer_gpu::timing::Protocol::chosen`): CI checks the table's shape, not its rates.
fn config() -> Criterion {
    let (warm_up, measurement, samples) = match std::env::var_os("GBUFFER_TIMING") {
        None => (500, 2000, 20),
        Some(value) if value == "full" => (500, 2000, 20),
        Some(value) if value == "short" => (50, 200, 10),
        Some(value) => {
            eprintln!("GBUFFER_TIMING={value:?}: the timing protocol is `full` or `short`");
            std::process::exit(1)
        }
    };
    Criterion::default()
        .warm_up_time(Duration::from_millis(warm_up))
        .measurement_time(Duration::from_millis(measurement))
        .sample_size(samples)
}

criterion_group! {
    name = benches;
    config = config();
    targets = slices
}

/// Criterion's mean time of one iteration, in nanoseconds, from the estimates it saved, if it
/// saved them during this run (from `started` on): a filter that skips a group leaves an older
/// run's estimates, which the tables must not put beside this run's.
fn mean_nanoseconds(
    folder: &Path,
    group: &str,
    function: &str,
    started: SystemTime,
) -> Option<f64> {
    let path = folder.join(group).join(function).join("new/estimates.json");
    if std::fs::metadata(&path).ok()?.modified().ok()? < started {
        return None;
    }
    let estimates: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()?;
    estimates["mean"]["point_estimate"].as_f64()
}

/// The rates of `group`'s functions ([`FUNCTIONS`]) in millions of texels a second, if this
/// run measured them all.
fn rates(criterion_folder: &Path, group: &str, started: SystemTime) -> Option<[f64; 3]> {
    let rates: Option<Vec<f64>> = FUNCTIONS
        .iter()
        .map(|function| {
            mean_nanoseconds(criterion_folder, group, function, started)
                .map(|ns| TEXELS as f64 / ns * 1e3)
        })
        .collect();
    rates?.try_into().ok()
}

/// The side-by-side tables, as Markdown, for the layouts this run measured: millions of texels
/// a second, and pack's and unpack's shares of memcpy's rate; then, for the layouts measured
/// beside their bytes moved with no conversion ([`floor_groups`]), pack's and unpack's
/// rates as shares of that floor's, timed back to back ([`shares_of_floor`]): the medians, and
/// the quartiles, over the rounds.
fn tables(criterion_folder: &Path, started: SystemTime) -> String {
    let mut table = String::from(
        "| layout | pack_slice | unpack_slice | memcpy | pack / memcpy | unpack / memcpy |\n\
         |---|---|---|---|---|---|\n",
    );
    let mut floors = String::from(
        "| layout | pack / floor | unpack / floor | pack, quartiles | unpack, quartiles |\n\
         |---|---|---|---|---|\n",
    );
    let percent = |share: f64| 100.0 * share;
    for Row {
        group,
        label: name,
        floor,
    } in ROWS.lock().expect("one thread").iter()
    {
        if let Some([pack, unpack, memcpy]) = rates(criterion_folder, group, started) {
            table += &format!(
                "| {name} | {pack:.0} Mtexel/s | {unpack:.0} Mtexel/s | {memcpy:.0} Mtexel/s | {:.0}% | {:.0}% |\n",
                100.0 * pack / memcpy,
                100.0 * unpack / memcpy
            );
        }
        if let Some(Floor {
            shares: [pack, unpack],
            ..
        }) = floor
        {
            floors += &format!(
                "| {name} | {:.0}% | {:.0}% | {:.0}% to {:.0}% | {:.0}% to {:.0}% |\n",
                percent(pack[1]),
                percent(unpack[1]),
                percent(pack[0]),
                percent(pack[2]),
                percent(unpack[0]),
                percent(unpack[2]),
            );
        }
    }
    format!("{table}\n{floors}")
}

/// The median times behind the shares, for the layouts measured beside their floor, a line
/// each: the conversion's, and the floor's through each loop (which of them was the floor, on
/// this CPU).
fn floor_times() -> String {
    let mut lines = String::new();
    for row in ROWS.lock().expect("one thread").iter() {
        if let Some(Floor { nanoseconds, .. }) = row.floor {
            lines += &format!(
                "{}, ns a texel (the conversion; the floor through the conversions' loop, \
                 through the plain loop):",
                row.label
            );
            for (direction, [conversion, conversions_loop, plain]) in
                ["pack", "unpack"].into_iter().zip(nanoseconds)
            {
                lines +=
                    &format!(" {direction} {conversion:.2}; {conversions_loop:.2}, {plain:.2}.");
            }
            lines += "\n";
        }
    }
    lines
}

fn main() {
    let started = SystemTime::now();
    benches();
    Criterion::default().configure_from_args().final_summary();
    let Some(target) = target_folder() else {
        return;
    };
    let criterion_folder = std::env::var_os("CRITERION_HOME")
        .map(PathBuf::from)
        .unwrap_or_else(|| target.join("criterion"));
    let table = tables(&criterion_folder, started);
    println!(
        "\n{TEXELS} texels, one thread; criterion's means, then shares of the floor over {} rounds\n\n{table}",
        rounds()
    );
    println!("{}", floor_times());
    write_figures(&target, "packing.md", &table);
}
