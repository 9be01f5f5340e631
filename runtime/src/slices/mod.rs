//! The loops behind [`GBufferLayout::pack_slice`] and [`GBufferLayout::unpack_slice`], and
//! their copies compiled for AVX2.
//!
//! The derived loop converts eight texels at a time in three steps: the texels' components
//! become rows of lane bits, one row per texel, and are transposed to one array per component
//! over the eight texels; each channel is converted over its eight lanes at once (vector
//! instructions); the words are transposed back to one array per texel. The transposes are
//! the set of [`Isa`] the loop runs on: plain loops anywhere, or AVX2's shuffles, which move
//! eight lanes in a handful of instructions where the compiler, left alone, inserts and
//! extracts them one at a time.

mod transpose;

use std::marker::PhantomData;

use crate::GBufferLayout;

/// The instructions a loop over texels runs on: how it transposes a matrix of `u32`, rows
/// to columns. Implemented by this crate alone: the AVX2 form is only ever chosen after a run
/// time check.
pub trait Isa {
    /// `matrix` transposed: `[c][r]` of the result is `[r][c]` of `matrix`.
    fn transpose<const R: usize, const C: usize>(matrix: &[[u32; C]; R]) -> [[u32; R]; C];
}

/// Plain loops, for any CPU.
struct Portable;

impl Isa for Portable {
    #[inline(always)]
    fn transpose<const R: usize, const C: usize>(matrix: &[[u32; C]; R]) -> [[u32; R]; C] {
        transpose::portable(matrix)
    }
}

/// AVX2's shuffles. Only [`convert_lanes`] names it, after checking that the CPU has AVX2.
#[cfg(target_arch = "x86_64")]
struct Avx2;

#[cfg(target_arch = "x86_64")]
impl Isa for Avx2 {
    #[inline(always)]
    fn transpose<const R: usize, const C: usize>(matrix: &[[u32; C]; R]) -> [[u32; R]; C] {
        // SAFETY: `Avx2` is private to this module, which runs code generic over it only
        // inside `lanes_with_avx2`, after `convert_lanes` has checked that the CPU has AVX2.
        unsafe { transpose::avx2(matrix) }
    }
}

/// A conversion of texels `N` at a time, and of one: the two must agree on every texel.
/// A trait of static functions, not closures: called directly, the `#[inline(always)]`
/// implementations inline into the copy of the loop compiled for AVX2 and are compiled for
/// AVX2 with it (a closure stays a function of its own, compiled for the baseline).
pub trait Lanes<A, B, const N: usize> {
    /// `N` texels at once, written in place (a returned array would be copied there), with
    /// the transposes of `I`.
    fn many<I: Isa>(input: &[A; N], output: &mut [B; N]);
    /// One texel, for the ones left over.
    fn one(input: &A) -> B;
}

/// Writes `output[i] = L::one(&input[i])` for every i, `N` at a time through `L::many` and
/// the rest through `L::one`; on x86-64 CPUs with AVX2 (checked at run time) through a copy
/// compiled for AVX2, whose per-lane shifts, rounding, blends and shuffles the conversions and
/// transposes need.
#[inline(always)]
pub fn convert_lanes<L: Lanes<A, B, N>, A, B, const N: usize>(input: &[A], output: &mut [B]) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, checked just above.
        unsafe { lanes_with_avx2::<L, A, B, N>(input, output) };
        return;
    }
    lanes::<L, Portable, A, B, N>(input, output);
}

/// How many texels ahead of the one being converted [`lanes`] asks for the input's and the
/// output's cache lines (a few kilobytes at the layouts' 16 to 128 bytes a texel).
#[cfg(target_arch = "x86_64")]
const PREFETCH_TEXELS: usize = 64;

#[inline(always)]
fn lanes<L: Lanes<A, B, N>, I: Isa, A, B, const N: usize>(input: &[A], output: &mut [B]) {
    let whole = input.len() / N * N;
    #[cfg(target_arch = "x86_64")]
    let ahead = Ahead::of(input, output);
    let (head, tail) = input.split_at(whole);
    let (out_head, out_tail) = output.split_at_mut(whole);
    for (chunk, (from, to)) in head
        .chunks_exact(N)
        .zip(out_head.chunks_exact_mut(N))
        .enumerate()
    {
        #[cfg(target_arch = "x86_64")]
        ahead.prefetch::<N>(chunk * N + PREFETCH_TEXELS);
        let from: &[A; N] = from.try_into().expect("chunks of N");
        let to: &mut [B; N] = to.try_into().expect("chunks of N");
        L::many::<I>(from, to);
    }
    for (from, to) in tail.iter().zip(out_tail) {
        *to = L::one(from);
    }
}

/// The two slices of a conversion, as addresses to prefetch from.
///
/// Why: the conversions are a stream, each byte read once and each word written once, and the
/// hardware's own prefetcher, which follows a stream, falls behind while a chunk's arithmetic
/// runs; the conversion then waits for memory and computes in turn, and its time is the sum of
/// the two. Asking for the lines [`PREFETCH_TEXELS`] ahead overlaps them. Measured once, when
/// this was added, on a 2-core Xeon of CI's kind (2^20 texels, one thread, three runs each, ns
/// a texel), without and with: Listing
/// 2.2 packed in 7.7-8.3 and 5.6-5.7, unpacked in 5.4-5.5 and 4.6-4.8; the bench's eight-format
/// layout packed in 15.3-16.1 and 11.4-11.7, unpacked in 17.5-18.1 and 11.5-11.7; with every
/// byte in cache, 4.8 and 4.0, 10.2 and 9.7: what is left above those is memory. Elsewhere
/// the loop relies on the hardware's prefetcher (aarch64's prefetch intrinsic is not stable
/// Rust).
#[cfg(target_arch = "x86_64")]
struct Ahead<A, B> {
    input: *const A,
    inputs: usize,
    output: *const B,
    outputs: usize,
}

#[cfg(target_arch = "x86_64")]
impl<A, B> Ahead<A, B> {
    #[inline(always)]
    fn of(input: &[A], output: &[B]) -> Self {
        Ahead {
            input: input.as_ptr(),
            inputs: input.len(),
            output: output.as_ptr(),
            outputs: output.len(),
        }
    }

    /// Asks for the cache lines of the `N` texels from `index`, input (to read) and output
    /// (to write), where the slices reach so far.
    #[inline(always)]
    fn prefetch<const N: usize>(&self, index: usize) {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_ET0, _MM_HINT_T0};
        if index < self.inputs {
            for line in lines(self.input.wrapping_add(index), N * size_of::<A>()) {
                // SAFETY: a prefetch is a hint: it never faults and changes nothing a program
                // reads, whatever the address (the chunk's last lines may lie past the slice;
                // the pointer arithmetic wraps, never dereferenced).
                unsafe { _mm_prefetch::<_MM_HINT_T0>(line) };
            }
        }
        if index < self.outputs {
            for line in lines(self.output.wrapping_add(index), N * size_of::<B>()) {
                // SAFETY: as above; ET0 asks for the line to be written.
                unsafe { _mm_prefetch::<_MM_HINT_ET0>(line) };
            }
        }
    }
}

/// The addresses, 64 bytes apart, that cover `bytes` bytes from `start`.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn lines<T>(start: *const T, bytes: usize) -> impl Iterator<Item = *const i8> {
    (0..bytes)
        .step_by(64)
        .map(move |offset| start.cast::<i8>().wrapping_add(offset))
}

/// # Safety
///
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn lanes_with_avx2<L: Lanes<A, B, N>, A, B, const N: usize>(input: &[A], output: &mut [B]) {
    lanes::<L, Avx2, A, B, N>(input, output);
}

/// The trait's own `pack_slice`, for layouts implemented by hand: a texel at a time.
pub struct Pack<T>(PhantomData<T>);

impl<T: GBufferLayout> Lanes<T, T::Packed, 1> for Pack<T> {
    #[inline(always)]
    fn many<I: Isa>(input: &[T; 1], output: &mut [T::Packed; 1]) {
        output[0] = input[0].pack();
    }
    #[inline(always)]
    fn one(input: &T) -> T::Packed {
        input.pack()
    }
}

/// The trait's own `unpack_slice`.
pub struct Unpack<T>(PhantomData<T>);

impl<T: GBufferLayout> Lanes<T::Packed, T, 1> for Unpack<T> {
    #[inline(always)]
    fn many<I: Isa>(input: &[T::Packed; 1], output: &mut [T; 1]) {
        output[0] = T::unpack(&input[0]);
    }
    #[inline(always)]
    fn one(input: &T::Packed) -> T {
        T::unpack(input)
    }
}
