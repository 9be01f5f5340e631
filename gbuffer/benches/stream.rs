//! Why a conversion can stand under its floor: what arithmetic beside a stream of loads does
//! to the stream. Listing 2.2's bytes are folded into its words by the packing bench's floor
//! (`floor::fold_words`: each word the exclusive or of the texel's `u32`s that fall on it, no
//! conversion), sixteen texels at a time, with rounds of arithmetic added
//! to each chunk of sixteen: either beside the fold (on numbers no load feeds) or on the
//! folded words before they are stored (as a pack's arithmetic is). Each form is timed with
//! every byte in cache, which gives what its arithmetic costs, and from memory, which gives
//! what that arithmetic does to the stream; Listing 2.2's `pack_slice` is timed the same way
//! beside them. The run ends with a table of both, which it also writes to
//! `target/figures/stream.md` for the guide. Run with `cargo bench -p gbuffer --bench stream`.
//!
//! Where the stream hides the arithmetic, a form's time from memory is the fold's, whatever its
//! arithmetic costs in cache; where it does not, the stream slows by part of that cost. A
//! conversion that stands where the fold with as much arithmetic stands is held under its floor
//! by how much arithmetic it does, not by how it loads.
// A bench's `main` needs no documentation of its own.
#![allow(missing_docs)]

use std::hint::black_box;

use gbuffer::glam::{Vec3, Vec4};
use gbuffer::seed_layouts::MobileMetallic;
use gbuffer::GBufferLayout;

mod floor;
mod rounds;
use floor::fold_words;
use rounds::{quartiles, rounds, target_folder, time, write_figures, WARM_UP_ROUNDS};

/// Texels a pass from memory: 48 MiB of texels and 16 of words, beyond the caches of the
/// machines this runs on.
const TEXELS: usize = 1 << 20;

/// Texels a pass with every byte in cache (96 KiB of texels and 32 of words: a core's
/// second-level cache), passed over again until it has converted [`TEXELS`].
const CACHED: usize = 2048;

/// Texels a chunk, as the AVX-512 copy of the conversions' loop takes them.
const CHUNK: usize = 16;

/// Listing 2.2's texel as its `u32`s, and its words.
type Texel = [u32; 12];
type Words = [u32; 4];

/// The forms timed: the fold, with or without arithmetic, and Listing 2.2's `pack_slice`.
#[derive(Clone, Copy)]
enum Form {
    Fold(Arithmetic),
    Pack,
}

/// What the fold does beside its bytes, a chunk of sixteen texels at a time.
#[derive(Clone, Copy)]
enum Arithmetic {
    None,
    /// Rounds on numbers no load feeds.
    Beside(usize),
    /// Rounds on the chunk's folded words, before they are stored.
    OnTheWords(usize),
}

impl Form {
    /// The table's first cell.
    fn label(self) -> String {
        match self {
            Form::Fold(Arithmetic::None) => "the fold alone".into(),
            Form::Fold(Arithmetic::Beside(rounds)) => {
                format!("the fold, {rounds} rounds beside it")
            }
            Form::Fold(Arithmetic::OnTheWords(rounds)) => {
                format!("the fold, {rounds} rounds on its words")
            }
            Form::Pack => "MobileMetallic (Listing 2.2), pack_slice".into(),
        }
    }
}

/// The forms, in the table's order: the fold alone first (the others' shares are of it).
const FORMS: [Form; 8] = [
    Form::Fold(Arithmetic::None),
    Form::Fold(Arithmetic::Beside(4)),
    Form::Fold(Arithmetic::Beside(8)),
    Form::Fold(Arithmetic::Beside(16)),
    Form::Fold(Arithmetic::OnTheWords(4)),
    Form::Fold(Arithmetic::OnTheWords(8)),
    Form::Fold(Arithmetic::OnTheWords(16)),
    Form::Pack,
];

/// One round of arithmetic on sixteen numbers: a multiply and an add each, which no compiler
/// may fold across rounds (floating-point arithmetic does not reassociate).
#[inline(always)]
fn round_of_arithmetic(numbers: &mut [f32; CHUNK]) {
    for number in numbers {
        *number = *number * 0.999 + 0.001;
    }
}

/// The fold with `arithmetic` over `texels` into `words`; `beside` carries the numbers of
/// [`Arithmetic::Beside`] from one call to the next, so that no round is dead code.
#[inline(never)]
fn fold_with(
    arithmetic: Arithmetic,
    texels: &[Texel],
    words: &mut [Words],
    beside: &mut [f32; CHUNK],
) {
    for (chunk, out) in texels
        .chunks_exact(CHUNK)
        .zip(words.chunks_exact_mut(CHUNK))
    {
        fold_words(chunk, out);
        match arithmetic {
            Arithmetic::None => {}
            Arithmetic::Beside(rounds) => {
                for _ in 0..rounds {
                    round_of_arithmetic(beside);
                }
            }
            Arithmetic::OnTheWords(rounds) => {
                // The first word of each texel, as a number below 2^30, through the rounds
                // and back into the word.
                let mut numbers: [f32; CHUNK] =
                    std::array::from_fn(|texel| (out[texel][0] & 0x3fff_ffff) as f32);
                for _ in 0..rounds {
                    round_of_arithmetic(&mut numbers);
                }
                for (words, number) in out.iter_mut().zip(numbers) {
                    words[0] ^= number.to_bits();
                }
            }
        }
    }
}

/// `form` over all of `texels`, into `words`, `passes` times: the seconds it took.
fn seconds(
    form: Form,
    texels: &[MobileMetallic],
    words: &mut [Words],
    passes: usize,
    beside: &mut [f32; CHUNK],
) -> f64 {
    // SAFETY: `MobileMetallic` is twelve f32 and no padding (its size is theirs, asserted in
    // `table`), so its bytes are twelve u32, in some order, which the fold does not mind.
    let raw: &[Texel] = unsafe { std::slice::from_raw_parts(texels.as_ptr().cast(), texels.len()) };
    time(|| {
        for _ in 0..passes {
            match form {
                Form::Pack => MobileMetallic::pack_slice(black_box(texels), black_box(&mut *words)),
                Form::Fold(arithmetic) => {
                    fold_with(arithmetic, black_box(raw), black_box(&mut *words), beside)
                }
            }
        }
    })
}

fn listing_2_2(index: usize) -> MobileMetallic {
    // A deterministic walk over [0, 1), different in each component.
    let value = |lane: usize| ((index * 7919 + lane * 104_729) % 10_007) as f32 / 10_007.0;
    MobileMetallic {
        light_accumulation: Vec3::new(value(0), value(1), value(2)),
        depth: value(3),
        normals_roughness: Vec4::new(value(4), value(5), value(6), value(7)),
        albedo_metallic: Vec4::new(value(8), value(9), value(10), value(11)),
    }
}

/// Each form's time in cache and from memory, timed in rounds (each round times every form
/// once in cache and once from memory, back to back, so that a change in the machine's speed
/// lands on all of them), as the table's rows: the medians over the rounds, nanoseconds a
/// texel, each also less the fold's (what the form's arithmetic costs in cache, and what it
/// costs the stream), and from memory the fold's time over the form's (its share of the
/// fold), the median of each round's.
fn table() -> String {
    assert_eq!(
        size_of::<MobileMetallic>(),
        size_of::<Texel>(),
        "no padding"
    );
    let texels: Vec<MobileMetallic> = (0..TEXELS).map(listing_2_2).collect();
    let mut words = vec![[0; 4]; TEXELS];
    let mut beside = [0.5; CHUNK];
    let nanoseconds = |seconds: f64| seconds * 1e9 / TEXELS as f64;
    // Per form: in cache, from memory, share of the fold from memory.
    let mut times: Vec<[Vec<f64>; 3]> = FORMS.iter().map(|_| Default::default()).collect();
    for round in 0..WARM_UP_ROUNDS + rounds() {
        let mut fold_from_memory = 0.0;
        for (form, times) in FORMS.into_iter().zip(&mut times) {
            let cached = seconds(
                form,
                &texels[..CACHED],
                &mut words[..CACHED],
                TEXELS / CACHED,
                &mut beside,
            );
            let from_memory = seconds(form, &texels, &mut words, 1, &mut beside);
            if let Form::Fold(Arithmetic::None) = form {
                fold_from_memory = from_memory;
            }
            if round >= WARM_UP_ROUNDS {
                times[0].push(nanoseconds(cached));
                times[1].push(nanoseconds(from_memory));
                times[2].push(fold_from_memory / from_memory);
            }
        }
    }
    black_box(beside);
    let medians: Vec<[f64; 3]> = times
        .into_iter()
        .map(|form| form.map(|times| quartiles(times)[1]))
        .collect();
    let [fold_in_cache, fold_from_memory, _] = medians[0];
    let mut table = String::from(
        "| form | in cache, a texel | above the fold, in cache | from memory, a texel | \
         above the fold, from memory | from memory, share of the fold |\n\
         |---|---|---|---|---|---|\n",
    );
    for (form, [cached, from_memory, share]) in FORMS.into_iter().zip(medians) {
        table += &format!(
            "| {} | {cached:.2} ns | {:.2} ns | {from_memory:.2} ns | {:.2} ns | {:.0}% |\n",
            form.label(),
            cached - fold_in_cache,
            from_memory - fold_from_memory,
            100.0 * share
        );
    }
    table
}

fn main() {
    // `cargo bench` passes `--bench` and any filter; this bench has one table and no filter.
    let table = table();
    println!(
        "\nListing 2.2's bytes folded into its words, {CHUNK} texels a chunk, with rounds of \
         arithmetic a chunk; ns a texel, medians of {} rounds ({TEXELS} texels from memory, \
         {CACHED} in cache), one thread\n\n{table}",
        rounds()
    );
    let Some(target) = target_folder() else {
        return;
    };
    write_figures(&target, "stream.md", &table);
}
