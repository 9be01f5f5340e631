//! The loops behind [`GBufferLayout::pack_slice`] and [`GBufferLayout::unpack_slice`], and
//! their copies compiled for AVX2 and for AVX-512.
//!
//! The derived loop converts `N` texels at a time in three steps: the texels' components
//! become rows of lane bits, one row per texel ([`Row`]), and are turned into one array per
//! component over the `N` texels (lanes); each channel is converted over its lanes at once
//! (vector instructions); the words' lanes are turned back into one array per texel. The set of
//! instructions the loop runs on ([`Isa`]) does the turning, with its shuffles, and may
//! convert a channel in a form of its own, exact as the mirror is: plain loops anywhere (eight
//! texels at a time); AVX2's shuffles (eight), which move eight lanes in a handful of
//! instructions where the compiler, left alone, inserts and extracts them one at a time; or
//! AVX-512 (sixteen), whose rounding control makes the unorm conversions a few instructions
//! each, and whose own instructions encode the integer, half and small-float channels
//! ([`avx512`]).

#[cfg(target_arch = "x86_64")]
mod avx512;
mod transpose;

use std::marker::PhantomData;

use gbuffer_core::convert::Scalar;
use gbuffer_core::format::Channel;

use crate::GBufferLayout;

/// A texel's components as a row of `u32` bits, `C` of them, one per column: what
/// [`Isa::lanes`] turns into lanes. The derive implements it per group of a layout's fields
/// ([`Words`] for a packed texel's words), with `#[inline(always)]`: a static function, not a
/// closure, so that it inlines into the loop's copies compiled for AVX2 and AVX-512 however
/// often they call it, and the AVX-512 copy reads each texel's components straight into its
/// registers.
pub trait Row<T, const C: usize> {
    /// `texel`'s row.
    fn row(texel: &T) -> [u32; C];
}

/// A packed texel's words as its row: the unpacking loops' [`Row`].
pub struct Words;

impl<const C: usize> Row<[u32; C], C> for Words {
    #[inline(always)]
    fn row(words: &[u32; C]) -> [u32; C] {
        *words
    }
}

/// `texels`' rows, as an array: what the AVX2 and plain transposes take (the AVX-512 form reads
/// the rows itself, four at a time).
#[inline(always)]
fn rows_of<T, W: Row<T, C>, const R: usize, const C: usize>(texels: &[T; R]) -> [[u32; C]; R] {
    std::array::from_fn(|texel| W::row(&texels[texel]))
}

/// The instructions a loop over texels runs on: how it turns rows of `u32` (one per texel)
/// into lanes (one array per column) and back, and how it converts a channel over its lanes.
/// Implemented by this crate alone: the AVX2 and AVX-512 forms are only ever chosen after a
/// run time check.
pub trait Isa {
    /// The rows of `texels` ([`Row::row`] of each) as lanes: `[c]` holds column `c` of every
    /// row, each row in a lane of the Isa's choosing (the lanes are converted one by one, so
    /// their order is free; [`Isa::rows`] puts them back).
    fn lanes<T, W: Row<T, C>, const R: usize, const C: usize>(texels: &[T; R]) -> [[u32; R]; C];
    /// The rows of `lanes`, in the order [`Isa::lanes`] took them: `rows(&lanes(m)) == m`
    /// (for `m` read through [`Words`]).
    fn rows<const R: usize, const C: usize>(lanes: &[[u32; R]; C]) -> [[u32; C]; R];

    /// ORs `channel`'s codes of `N` values, in place, into `words`: the codes
    /// [`Channel::encode_lanes`] gives, bit for bit.
    #[inline(always)]
    fn encode<S: Scalar, const N: usize>(channel: Channel, values: [S; N], words: &mut [u32; N]) {
        for (word, code) in words.iter_mut().zip(channel.encode_lanes(values)) {
            *word |= code;
        }
    }

    /// `channel`'s values in `N` words, as [`Channel::decode_lanes`] gives them, bit for bit.
    #[inline(always)]
    fn decode<S: Scalar, const N: usize>(channel: Channel, words: [u32; N]) -> [S; N] {
        channel.decode_lanes(words)
    }
}

/// Plain loops, for any CPU; the lanes in the rows' order.
struct Portable;

impl Isa for Portable {
    #[inline(always)]
    fn lanes<T, W: Row<T, C>, const R: usize, const C: usize>(texels: &[T; R]) -> [[u32; R]; C] {
        transpose::portable(&rows_of::<T, W, R, C>(texels))
    }

    #[inline(always)]
    fn rows<const R: usize, const C: usize>(lanes: &[[u32; R]; C]) -> [[u32; C]; R] {
        transpose::portable(lanes)
    }
}

/// AVX2's shuffles; the lanes in the rows' order. Only [`convert_lanes`] names it, after
/// checking that the CPU has AVX2.
#[cfg(target_arch = "x86_64")]
struct Avx2;

#[cfg(target_arch = "x86_64")]
impl Isa for Avx2 {
    #[inline(always)]
    fn lanes<T, W: Row<T, C>, const R: usize, const C: usize>(texels: &[T; R]) -> [[u32; R]; C] {
        let rows = rows_of::<T, W, R, C>(texels);
        // SAFETY: `Avx2` is private to this module, which runs code generic over it only
        // inside `lanes_with_avx2`, after `convert_lanes` has checked that the CPU has AVX2.
        unsafe { transpose::avx2(&rows) }
    }

    #[inline(always)]
    fn rows<const R: usize, const C: usize>(lanes: &[[u32; R]; C]) -> [[u32; C]; R] {
        // SAFETY: as above.
        unsafe { transpose::avx2(lanes) }
    }
}

/// Which copy of the loop runs: [`Simd::Best`] (the default) picks the widest the CPU has.
/// Tests force the others ([`force_simd`]), to hold each to the mirror on a CPU that has them
/// all.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Simd {
    /// The widest the CPU has: AVX-512, AVX2, or plain loops.
    Best,
    /// Plain loops.
    Portable,
    /// AVX2 (plain loops on a CPU without it, where [`force_simd`] says so).
    Avx2,
}

thread_local! {
    /// The copy [`convert_lanes`] runs in this thread: [`Simd::Best`] unless a test forced
    /// another.
    static FORCED: std::cell::Cell<Simd> = const { std::cell::Cell::new(Simd::Best) };
}

/// Makes [`convert_lanes`] run `simd`'s copy from now on, in the calling thread. For tests
/// that hold each copy to the mirror. Returns whether this CPU has that copy: where it does
/// not (AVX2 on a CPU without it), the loop runs plain loops, and a test of that copy would
/// test those instead: it should say so and skip it.
#[must_use = "a copy the CPU lacks runs plain loops: a test of it should skip"]
pub fn force_simd(simd: Simd) -> bool {
    FORCED.set(simd);
    match simd {
        Simd::Best | Simd::Portable => true,
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => std::is_x86_feature_detected!("avx2"),
        #[cfg(not(target_arch = "x86_64"))]
        Simd::Avx2 => false,
    }
}

/// A conversion of texels `N` at a time, and of one: the two must agree on every texel.
/// A trait of static functions, not closures: called directly, the `#[inline(always)]`
/// implementations inline into the copies of the loop compiled for AVX2 and AVX-512 and are
/// compiled for them with it (a closure stays a function of its own, compiled for the
/// baseline).
pub trait Lanes<A, B> {
    /// `N` texels at once, written in place (a returned array would be copied there), with
    /// the lanes and conversions of `I`.
    fn many<I: Isa, const N: usize>(input: &[A; N], output: &mut [B; N]);
    /// One texel, for the ones left over.
    fn one(input: &A) -> B;
}

/// Writes `output[i] = L::one(&input[i])` for every i, many at a time through `L::many` and
/// the rest through `L::one`: on x86-64 CPUs with AVX-512 (checked at run time) sixteen at a
/// time through a copy compiled for it, with AVX2 eight at a time through a copy compiled for
/// AVX2 (the per-lane shifts, rounding, blends and shuffles the conversions and turns need),
/// elsewhere eight at a time in plain loops.
#[inline(always)]
pub fn convert_lanes<L: Lanes<A, B>, A, B>(input: &[A], output: &mut [B]) {
    #[cfg(target_arch = "x86_64")]
    {
        let forced = FORCED.get();
        if forced == Simd::Best && avx512::available() {
            // SAFETY: the CPU has the features `lanes_with_avx512` is compiled for, checked
            // just above.
            unsafe { lanes_with_avx512::<L, A, B>(input, output) };
            return;
        }
        if forced != Simd::Portable && std::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, checked just above.
            unsafe { lanes_with_avx2::<L, A, B>(input, output) };
            return;
        }
    }
    lanes::<L, Portable, A, B, 8>(input, output);
}

/// How many texels ahead of the one being converted [`lanes`] asks for the input's and the
/// output's cache lines, into the first-level cache (a few kilobytes at the layouts' 16 to 128
/// bytes a texel).
#[cfg(target_arch = "x86_64")]
const PREFETCH_TEXELS: usize = 64;

/// How many texels ahead [`lanes`] asks for the input's lines into the second-level cache
/// (tens of kilobytes), from where the nearer prefetch takes them.
#[cfg(target_arch = "x86_64")]
const PREFETCH_FAR_TEXELS: usize = 256;

#[inline(always)]
fn lanes<L: Lanes<A, B>, I: Isa, A, B, const N: usize>(input: &[A], output: &mut [B]) {
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
        if let Some(ahead) = &ahead {
            ahead.prefetch::<N>(chunk * N);
        }
        let from: &[A; N] = from.try_into().expect("chunks of N");
        let to: &mut [B; N] = to.try_into().expect("chunks of N");
        L::many::<I, N>(from, to);
    }
    for (from, to) in tail.iter().zip(out_tail) {
        *to = L::one(from);
    }
}

/// The two slices of a conversion, as addresses to prefetch from.
///
/// Why: the conversions are a stream, each byte read once and each word written once, and on
/// Intel's CPUs the hardware's own prefetcher, which follows a stream, falls behind while a chunk's
/// arithmetic runs; the conversion then waits for memory and computes in turn, and its time is the
/// sum of the two. Asking for the lines [`PREFETCH_TEXELS`] ahead overlaps them. Measured once,
/// when this was added, on a 2-core Xeon (2^20 texels, one thread, three runs each, ns a texel),
/// without and with: Listing 2.2 packed in 7.7-8.3 and 5.6-5.7, unpacked in 5.4-5.5 and 4.6-4.8;
/// the bench's eight-format layout packed in 15.3-16.1 and 11.4-11.7, unpacked in 17.5-18.1 and
/// 11.5-11.7; with every byte in cache, 4.8 and 4.0, 10.2 and 9.7: what is left above those is
/// memory.
///
/// A first-level prefetch holds one of the core's few outstanding first-level misses until its line
/// arrives, so those alone keep only a few kilobytes in flight; the input's lines are also asked
/// for [`PREFETCH_FAR_TEXELS`] ahead into the second-level cache, which keeps many more. The
/// first-level requests go first: asked after the far ones, they measured no gain. Measured when
/// that was added (the same machine, pack's rate as a share of the same bytes moved by a plain loop
/// with no prefetch, three runs, each a median of 31 rounds), without and with: Listing 2.2 packed
/// at 98-103% and 112-118%, the eight-format layout at 94-98% and 107-112%.
///
/// On AMD's CPUs the same prefetches made every conversion slower: measured on a 2-core EPYC of Zen
/// 4 (the packing bench's printed medians of 31 rounds, ns a texel, three runs with and three
/// without, alternating): Listing 2.2 packed in 3.4-3.6 and 2.3-2.6, unpacked in 2.6-3.1 and
/// 2.3-2.5; the eight-format layout packed in 8.2-8.4 and 5.5-5.6, unpacked in 4.9-5.2 and 4.4-4.9.
/// Its hardware prefetcher seems to keep up with the streams by itself, the software's requests
/// only crowding it (that virtual machine had no counters to tell). So the loop asks ahead on
/// Intel's CPUs alone ([`Ahead::of`]); elsewhere it relies on the hardware's prefetcher (aarch64's
/// prefetch intrinsic is not stable Rust).
#[cfg(target_arch = "x86_64")]
struct Ahead<A, B> {
    input: *const A,
    inputs: usize,
    output: *const B,
    outputs: usize,
}

#[cfg(target_arch = "x86_64")]
impl<A, B> Ahead<A, B> {
    /// The slices to prefetch from, on a CPU where prefetching was measured to pay (Intel's);
    /// `None` elsewhere.
    #[inline(always)]
    fn of(input: &[A], output: &[B]) -> Option<Self> {
        intel().then_some(Ahead {
            input: input.as_ptr(),
            inputs: input.len(),
            output: output.as_ptr(),
            outputs: output.len(),
        })
    }

    /// Asks for the cache lines of the `N` texels [`PREFETCH_TEXELS`] past `index`, input (to
    /// read) and output (to write), and of the input's [`PREFETCH_FAR_TEXELS`] past it, where
    /// the slices reach so far.
    #[inline(always)]
    fn prefetch<const N: usize>(&self, index: usize) {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_ET0, _MM_HINT_T0, _MM_HINT_T1};
        let near = index + PREFETCH_TEXELS;
        if near < self.inputs {
            for line in lines(self.input.wrapping_add(near), N * size_of::<A>()) {
                // SAFETY: a prefetch is a hint: it never faults and changes nothing a program
                // reads, whatever the address (the chunk's last lines may lie past the slice;
                // the pointer arithmetic wraps, never dereferenced).
                unsafe { _mm_prefetch::<_MM_HINT_T0>(line) };
            }
        }
        if near < self.outputs {
            for line in lines(self.output.wrapping_add(near), N * size_of::<B>()) {
                // SAFETY: as above; ET0 asks for the line to be written.
                unsafe { _mm_prefetch::<_MM_HINT_ET0>(line) };
            }
        }
        let far = index + PREFETCH_FAR_TEXELS;
        if far < self.inputs {
            for line in lines(self.input.wrapping_add(far), N * size_of::<A>()) {
                // SAFETY: as above.
                unsafe { _mm_prefetch::<_MM_HINT_T1>(line) };
            }
        }
    }
}

/// Whether the CPU is Intel's: its vendor string (`cpuid` leaf 0, in EBX, EDX, ECX) is
/// "GenuineIntel". Read once.
#[cfg(target_arch = "x86_64")]
fn intel() -> bool {
    static INTEL: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *INTEL.get_or_init(|| {
        // SAFETY: `cpuid` runs on every x86-64 CPU, and leaf 0 on every one. (A safe function
        // in newer Rust than the crate's `rust-version`, where it is not: hence the allow.)
        #[allow(unused_unsafe)]
        let leaf = unsafe { std::arch::x86_64::__cpuid(0) };
        // The twelve bytes, four to a register, little-endian.
        [leaf.ebx, leaf.edx, leaf.ecx] == [*b"Genu", *b"ineI", *b"ntel"].map(u32::from_le_bytes)
    })
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
unsafe fn lanes_with_avx2<L: Lanes<A, B>, A, B>(input: &[A], output: &mut [B]) {
    lanes::<L, Avx2, A, B, 8>(input, output);
}

/// # Safety
///
/// The CPU must have what [`avx512::available`] checks.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx512bw,avx512dq,avx2,fma")]
unsafe fn lanes_with_avx512<L: Lanes<A, B>, A, B>(input: &[A], output: &mut [B]) {
    lanes::<L, avx512::Avx512, A, B, 16>(input, output);
}

/// The trait's own `pack_slice`, for layouts implemented by hand: a texel at a time.
pub struct Pack<T>(PhantomData<T>);

impl<T: GBufferLayout> Lanes<T, T::Packed> for Pack<T> {
    #[inline(always)]
    fn many<I: Isa, const N: usize>(input: &[T; N], output: &mut [T::Packed; N]) {
        for (texel, packed) in input.iter().zip(output) {
            *packed = texel.pack();
        }
    }
    #[inline(always)]
    fn one(input: &T) -> T::Packed {
        input.pack()
    }
}

/// The trait's own `unpack_slice`.
pub struct Unpack<T>(PhantomData<T>);

impl<T: GBufferLayout> Lanes<T::Packed, T> for Unpack<T> {
    #[inline(always)]
    fn many<I: Isa, const N: usize>(input: &[T::Packed; N], output: &mut [T; N]) {
        for (packed, texel) in input.iter().zip(output) {
            *texel = T::unpack(packed);
        }
    }
    #[inline(always)]
    fn one(input: &T::Packed) -> T {
        T::unpack(input)
    }
}

#[cfg(all(test, target_arch = "x86_64", target_os = "linux"))]
mod tests {
    /// [`super::intel`] against the vendor the kernel read (`/proc/cpuinfo`'s `vendor_id`).
    #[test]
    fn the_vendor_is_the_kernels() {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").expect("Linux's /proc/cpuinfo");
        let vendor = cpuinfo
            .lines()
            .find_map(|line| line.strip_prefix("vendor_id"))
            .and_then(|rest| rest.split(':').nth(1))
            .expect("a vendor_id line")
            .trim();
        assert_eq!(
            super::intel(),
            vendor == "GenuineIntel",
            "vendor_id {vendor}"
        );
    }
}
