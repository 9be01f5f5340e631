//! The loop's copy for AVX-512: sixteen texels at a time, the rows turned into lanes 4x4 at a
//! time within each 128-bit quarter of a register, and the unorm channels converted in a few
//! instructions each, exact as the mirror is; so are the encodes of the integer channels
//! (clamps) and of the halves (AVX-512's own conversion, clamped), each beside its function
//! below.
//!
//! Why the unorm conversions differ from the mirror's algorithm (`codecs::unorm`), and why it
//! is the same result:
//! - Encode. The code is `floor(x * max + 0.5)` of the clamped value. AVX-512 rounds a fused
//!   multiply-add in the direction an instruction names (Intel's SDM, "static rounding
//!   mode"); rounded down, `RD(x * max + 0.5)` lies between the exact sum and the largest
//!   integer below it (that integer is a float: it is at most 2^23), so its integer part,
//!   which truncation gives, is the exact floor. The mirror, which has only rounding to
//!   nearest, needs a second product to check its candidate; here one instruction suffices.
//! - Decode. The code is `code / max` correctly rounded. Rounding to nearest, `q = code * r`
//!   with `r` the rounded reciprocal is within an ulp of the quotient; the remainder
//!   `code - q * max` is then exact in one fused multiply-add, and `q + remainder * r`,
//!   rounded once, is the correctly rounded quotient (Markstein's correction, "IA-64 and
//!   Elementary Functions", 2000; the division chapter of Muller et al.'s "Handbook of
//!   Floating-Point Arithmetic"). The mirror computes it in f64 instead, which takes twice
//!   the registers.
//!
//! All are held to the mirror: the unorm decode on every code of every width, the unorm
//! encode on both sides of every code's boundaries at every width, the half encode on both
//! sides of every half's midpoints, the integer clamps at every width's edges
//! (the tests below); and the float formats on every f32 and every word in the derived slices
//! (`gbuffer/tests/slices_every_f32.rs`).
//!
//! A register of sixteen floats is sixteen texels; with 512-bit registers only two of the
//! CPU's vector ports run (Intel's optimisation manual, "Skylake server microarchitecture"),
//! so the wider registers pay where they save instructions, as these conversions do.

use std::arch::x86_64::*;

use gbuffer_core::codecs::max_code;
use gbuffer_core::convert::Scalar;
use gbuffer_core::format::Channel;
use gbuffer_core::{Encoding, ScalarKind};

use super::{Isa, Row};

/// Whether the CPU has what [`super::lanes_with_avx512`] is compiled for.
#[inline(always)]
pub fn available() -> bool {
    std::is_x86_feature_detected!("avx512f")
        && std::is_x86_feature_detected!("avx512vl")
        && std::is_x86_feature_detected!("avx512bw")
        && std::is_x86_feature_detected!("avx512dq")
        && std::is_x86_feature_detected!("avx2")
        && std::is_x86_feature_detected!("fma")
}

/// The AVX-512 form: rows to lanes within 128-bit quarters, and the unorm conversions above.
/// Only [`super::convert_lanes`] runs code generic over it, after [`available`].
///
/// Its lane order: in each block of sixteen rows, row `4j + k` goes to lane `4k + j` (a 4x4
/// transpose of the row's index), which is what the in-quarter shuffles give without a
/// shuffle across quarters; rows past the last whole block keep their place.
pub struct Avx512;

impl Isa for Avx512 {
    #[inline(always)]
    fn lanes<T, W: Row<T, C>, const R: usize, const C: usize>(texels: &[T; R]) -> [[u32; R]; C] {
        // SAFETY: see `Avx512`: the CPU has AVX-512F.
        unsafe { lanes::<T, W, R, C>(texels) }
    }

    #[inline(always)]
    fn rows<const R: usize, const C: usize>(lanes: &[[u32; R]; C]) -> [[u32; C]; R] {
        // SAFETY: as above.
        unsafe { rows(lanes) }
    }

    #[inline(always)]
    fn encode<S: Scalar, const N: usize>(channel: Channel, values: [S; N], words: &mut [u32; N]) {
        if let Ok(words) = <&mut [u32; 16]>::try_from(&mut words[..]) {
            let bits = channel.bits;
            // Each value as its codec's lane, as `Scalar::encode` takes it: an f32's bits for
            // the float codecs (for an f32 field, itself), a u32 or an i32's bits for the
            // integer ones.
            let lanes = |kind: ScalarKind| sixteen(values, |value| value.to_lane(kind));
            // SAFETY (each call): see `Avx512`: the CPU has AVX-512F.
            let codes = match channel.encoding {
                Encoding::Unorm => Some(unsafe { unorm_codes(lanes(ScalarKind::Float), bits) }),
                Encoding::Uint => Some(unsafe { uint_codes(lanes(ScalarKind::Uint), bits) }),
                Encoding::Sint => Some(unsafe { sint_codes(lanes(ScalarKind::Sint), bits) }),
                Encoding::Half => Some(unsafe { half_codes(lanes(ScalarKind::Float)) }),
                _ => None,
            };
            if let Some(codes) = codes {
                // SAFETY: as above.
                unsafe { or_codes(codes, channel.offset, words) };
                return;
            }
        }
        eight_at_a_time(channel, values, words);
    }

    #[inline(always)]
    fn decode<S: Scalar, const N: usize>(channel: Channel, words: [u32; N]) -> [S; N] {
        if N == 16 {
            let bits = channel.bits;
            let codes = || sixteen(words, |word| (word >> channel.offset) & channel.mask());
            // SAFETY (each call): see `Avx512`: the CPU has AVX-512F.
            let floats = match channel.encoding {
                Encoding::Unorm => Some(unsafe { f32_from_unorm(codes(), bits) }),
                Encoding::Half => Some(unsafe { f32_from_half(codes()) }),
                // A code shifted up to ten mantissa bits is a half's bit pattern (the codec's
                // module says so): the same conversion.
                Encoding::UnsignedFloat => {
                    Some(unsafe { f32_from_half(codes().map(|code| code << (15 - bits))) })
                }
                _ => None,
            };
            if let Some(floats) = floats {
                let mut values = [S::default(); N];
                for (value, float) in values.iter_mut().zip(floats) {
                    *value = S::from_lane(float.to_bits(), ScalarKind::Float);
                }
                return values;
            }
        }
        channel.decode_lanes(words)
    }
}

/// The first sixteen of `values`, each through `lane`: a register's lanes. (The callers call
/// it where `N` is 16.)
#[inline(always)]
fn sixteen<T: Copy, const N: usize>(values: [T; N], lane: impl Fn(T) -> u32) -> [u32; 16] {
    let mut lanes = [0u32; 16];
    for (lane_value, value) in lanes.iter_mut().zip(values) {
        *lane_value = lane(value);
    }
    lanes
}

/// [`Isa::encode`] through the mirror's own code ([`Channel::encode_lanes`]), eight lanes at
/// a time where `N` allows: the codecs this module has no form of its own for (the small floats,
/// `snorm`, the shared exponent and the other bit-field codecs), whose per-lane code the
/// compiler vectorises better over eight lanes than over sixteen (about three times as fast
/// for the small floats when this was written). The small floats stay here because a form of
/// AVX-512's own (its half conversion rounding to odd, then an integer rounding to nearest
/// even) measured a fifth slower than this, in cache, the two compiled side by side.
#[inline(always)]
fn eight_at_a_time<S: Scalar, const N: usize>(
    channel: Channel,
    values: [S; N],
    words: &mut [u32; N],
) {
    if !N.is_multiple_of(8) {
        for (word, code) in words.iter_mut().zip(channel.encode_lanes(values)) {
            *word |= code;
        }
        return;
    }
    for eight in (0..N).step_by(8) {
        let mut part = [S::default(); 8];
        part.copy_from_slice(&values[eight..eight + 8]);
        for (word, code) in words[eight..].iter_mut().zip(channel.encode_lanes(part)) {
            *word |= code;
        }
    }
}

/// ORs sixteen codes, shifted left by `offset`, into `words`. (The shift and OR are written
/// here, in the registers, rather than left to the caller's loops, which the compiler
/// vectorises across channels instead of lanes.)
#[target_feature(enable = "avx512f")]
#[inline]
fn or_codes(codes: __m512i, offset: u32, words: &mut [u32; 16]) {
    // SAFETY: `words` is sixteen readable and writable u32; neither access needs alignment.
    unsafe {
        let placed = _mm512_sllv_epi32(codes, _mm512_set1_epi32(offset as i32));
        let old = _mm512_loadu_si512(words.as_ptr().cast());
        _mm512_storeu_si512(words.as_mut_ptr().cast(), _mm512_or_si512(old, placed));
    }
}

/// Sixteen lanes in a register.
#[target_feature(enable = "avx512f")]
#[inline]
fn load(lanes: [u32; 16]) -> __m512i {
    // SAFETY: `lanes` is sixteen readable u32; the load needs no alignment.
    unsafe { _mm512_loadu_si512(lanes.as_ptr().cast()) }
}

/// The `bits`-bit codes of sixteen u32s: each clamped to the largest, as
/// `integer::uint_saturate`.
#[target_feature(enable = "avx512f")]
#[inline]
fn uint_codes(lanes: [u32; 16], bits: u32) -> __m512i {
    _mm512_min_epu32(load(lanes), _mm512_set1_epi32(max_code(bits) as i32))
}

/// The `bits`-bit two's complement codes of sixteen i32s (as their bits): each clamped to the
/// range of `bits` bits, as `integer::sint_saturate`.
#[target_feature(enable = "avx512f")]
#[inline]
fn sint_codes(lanes: [u32; 16], bits: u32) -> __m512i {
    let highest = (max_code(bits) >> 1) as i32;
    let clamped = _mm512_min_epi32(
        _mm512_max_epi32(load(lanes), _mm512_set1_epi32(-highest - 1)),
        _mm512_set1_epi32(highest),
    );
    _mm512_and_si512(clamped, _mm512_set1_epi32(max_code(bits) as i32))
}

/// The binary16 codes of sixteen f32s (as their bits), as `half::half_from_f32`: AVX-512's
/// conversion, rounding to nearest even with denormals kept (Intel's SDM, `VCVTPS2PH`), of
/// the value clamped to +-65504 (the codec saturates where the conversion would give
/// infinity); NaN gives 0.
#[target_feature(enable = "avx512f")]
#[inline]
fn half_codes(lanes: [u32; 16]) -> __m512i {
    let x = _mm512_castsi512_ps(load(lanes));
    let ordered = _mm512_cmp_ps_mask::<_CMP_ORD_Q>(x, x);
    let clamped = _mm512_min_ps(
        _mm512_max_ps(x, _mm512_set1_ps(-65504.0)),
        _mm512_set1_ps(65504.0),
    );
    let halves = _mm512_cvtps_ph::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(clamped);
    _mm512_maskz_mov_epi32(ordered, _mm512_cvtepu16_epi32(halves))
}

/// The `bits`-bit unorm codes of sixteen values: `floor(clamp(x, 0, 1) * max + 0.5)`, NaN
/// giving 0, through one multiply-add rounded down (the module's comment says why it is
/// exact). `bits` from 1 to 23, as the codec allows.
#[target_feature(enable = "avx512f")]
#[inline]
fn unorm_codes(lanes: [u32; 16], bits: u32) -> __m512i {
    let max = max_code(bits) as f32;
    let x = _mm512_castsi512_ps(load(lanes));
    // `max` returns its second operand where either is NaN, and +0 for -0: NaN and negatives
    // become +0. Then above 1 (infinity too) becomes 1.
    let x = _mm512_min_ps(_mm512_max_ps(x, _mm512_setzero_ps()), _mm512_set1_ps(1.0));
    let sum = _mm512_fmadd_round_ps::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(
        x,
        _mm512_set1_ps(max),
        _mm512_set1_ps(0.5),
    );
    // From 0.5 to max + 0.5: truncation is the floor, and the code fits a signed lane.
    _mm512_cvttps_epi32(sum)
}

/// The values of sixteen `bits`-bit unorm codes: `code / max` correctly rounded, through
/// Markstein's correction of the product by the reciprocal (the module's comment says why).
#[target_feature(enable = "avx512f")]
#[inline]
fn f32_from_unorm(codes: [u32; 16], bits: u32) -> [f32; 16] {
    let max = ((1u32 << bits) - 1) as f32;
    let reciprocal = 1.0 / max;
    // SAFETY: `codes` is sixteen readable u32; the load needs no alignment.
    let codes = unsafe { _mm512_loadu_si512(codes.as_ptr().cast()) };
    // Below 2^23: exact as floats, and positive as signed lanes.
    let code = _mm512_cvtepi32_ps(codes);
    let (max, reciprocal) = (_mm512_set1_ps(max), _mm512_set1_ps(reciprocal));
    let estimate = _mm512_mul_ps(code, reciprocal);
    let remainder = _mm512_fnmadd_ps(estimate, max, code);
    let quotient = _mm512_fmadd_ps(remainder, reciprocal, estimate);
    let mut out = [0f32; 16];
    // SAFETY: `out` is sixteen writable f32; the store needs no alignment.
    unsafe { _mm512_storeu_ps(out.as_mut_ptr(), quotient) };
    out
}

/// The values of sixteen binary16 codes (in their low 16 bits), exactly, as
/// `half::f32_from_half`: AVX-512's conversion (Intel's SDM, `VCVTPH2PS`), which widens
/// exactly, denormals included; but for exponent 31, whose bits are placed directly, because
/// the conversion sets a signalling NaN's quiet bit and the mirror keeps the payload as it is.
#[target_feature(enable = "avx512f")]
#[inline]
fn f32_from_half(codes: [u32; 16]) -> [f32; 16] {
    let codes = load(codes);
    let converted = _mm512_cvtph_ps(_mm512_cvtepi32_epi16(codes));
    let exponent = _mm512_set1_epi32(0x7c00);
    let special = _mm512_cmpeq_epi32_mask(_mm512_and_si512(codes, exponent), exponent);
    // Sign to bit 31, exponent 255, the ten mantissa bits at the top of the f32's 23.
    let sign = _mm512_slli_epi32::<16>(_mm512_and_si512(codes, _mm512_set1_epi32(0x8000)));
    let mantissa = _mm512_slli_epi32::<13>(_mm512_and_si512(codes, _mm512_set1_epi32(0x3ff)));
    let placed = _mm512_or_si512(
        _mm512_or_si512(sign, mantissa),
        _mm512_set1_epi32(0x7f80_0000),
    );
    let values = _mm512_mask_blend_ps(special, converted, _mm512_castsi512_ps(placed));
    let mut out = [0f32; 16];
    // SAFETY: `out` is sixteen writable f32; the store needs no alignment.
    unsafe { _mm512_storeu_ps(out.as_mut_ptr(), values) };
    out
}

/// Columns `column..column + 4` of four rows, one row per 128-bit quarter; zeros past the
/// rows' last column. Inlined, with the rows just read from the texels, each quarter is a
/// load from a texel where its columns are adjacent there.
#[inline(always)]
fn quarters<const C: usize>(rows: &[[u32; C]; 4], column: usize) -> __m512 {
    if C == 4 {
        // Rows of four columns, one after another, are the register: one load where the
        // quarters below take four and three inserts (a 4-word layout's unpack: Listing 2.2's
        // took 1.75 ns a texel in cache instead of 2.2).
        // SAFETY: four rows of four `u32`, one after another: sixteen readable `u32`; the load
        // needs no alignment; the callers run with AVX-512F (`lanes`, compiled for it, inlines
        // this).
        return unsafe { _mm512_loadu_ps(rows.as_ptr().cast()) };
    }
    let quarter = |r: usize| {
        let mut lanes = [0u32; 4];
        for (k, lane) in lanes.iter_mut().enumerate() {
            if column + k < C {
                *lane = rows[r][column + k];
            }
        }
        // SAFETY: `lanes` is four readable u32; the load needs no alignment; SSE is in
        // every x86-64 CPU.
        unsafe { _mm_loadu_ps(lanes.as_ptr().cast()) }
    };
    // SAFETY: the callers run with AVX-512F (`lanes`, compiled for it, inlines this).
    unsafe {
        let mut value = _mm512_castps128_ps512(quarter(0));
        value = _mm512_insertf32x4::<1>(value, quarter(1));
        value = _mm512_insertf32x4::<2>(value, quarter(2));
        _mm512_insertf32x4::<3>(value, quarter(3))
    }
}

/// [`quarters`] backwards: the register's quarters to rows `row..row + 4`.
#[target_feature(enable = "avx512f")]
#[inline]
fn store_quarters<const R: usize, const C: usize>(
    rows: &mut [[u32; C]; R],
    row: usize,
    column: usize,
    value: __m512,
) {
    let quarters = [
        _mm512_castps512_ps128(value),
        _mm512_extractf32x4_ps::<1>(value),
        _mm512_extractf32x4_ps::<2>(value),
        _mm512_extractf32x4_ps::<3>(value),
    ];
    for (r, quarter) in quarters.into_iter().enumerate() {
        let lanes: &mut [u32; 4] = (&mut rows[row + r][column..column + 4])
            .try_into()
            .expect("four lanes");
        // SAFETY: `lanes` is four writable u32; the store needs no alignment.
        unsafe { _mm_storeu_ps(lanes.as_mut_ptr().cast(), quarter) };
    }
}

/// Within each 128-bit quarter, the 4x4 transpose of the four registers' quarters: quarter
/// `k` of result `c` holds element `c` of quarter `k` of each input, in the inputs' order.
#[target_feature(enable = "avx512f")]
#[inline]
fn transpose_quarters(x: [__m512; 4]) -> [__m512; 4] {
    let low01 = _mm512_castps_pd(_mm512_unpacklo_ps(x[0], x[1]));
    let high01 = _mm512_castps_pd(_mm512_unpackhi_ps(x[0], x[1]));
    let low23 = _mm512_castps_pd(_mm512_unpacklo_ps(x[2], x[3]));
    let high23 = _mm512_castps_pd(_mm512_unpackhi_ps(x[2], x[3]));
    [
        _mm512_castpd_ps(_mm512_unpacklo_pd(low01, low23)),
        _mm512_castpd_ps(_mm512_unpackhi_pd(low01, low23)),
        _mm512_castpd_ps(_mm512_unpacklo_pd(high01, high23)),
        _mm512_castpd_ps(_mm512_unpackhi_pd(high01, high23)),
    ]
}

/// The lane of row `row` of a block of sixteen: `4k + j` for row `4j + k` (its own inverse).
#[inline(always)]
fn lane_of(row: usize) -> usize {
    4 * (row % 4) + row / 4
}

/// [`Isa::lanes`] of [`Avx512`]: per block of sixteen texels, four rows at a time read from
/// the texels ([`Row::row`]) into one register per four columns, then each register's
/// quarters transposed.
///
/// Why the rows are read here, texel by texel, and not from an array of them built first:
/// the compiler copied such an array to the stack with 64-byte stores and read it back with
/// the transposes' 16- and 32-byte loads, some of them across two of those stores, which the
/// core cannot forward from a store and waits for instead. Measured with `perf annotate` on a
/// 2-core EPYC of Zen 4, a quarter of Listing 2.2's in-cache pack samples fell after those
/// loads; read directly, its pack went from 1.8 to 1.45 ns a texel in cache, and the
/// eight-format layout's from 6.1 to 4.4 ns a texel from memory (alternating builds, medians
/// of 21 rounds of 2^20 texels).
#[target_feature(enable = "avx512f")]
#[inline]
fn lanes<T, W: Row<T, C>, const R: usize, const C: usize>(texels: &[T; R]) -> [[u32; R]; C] {
    let mut out = [[0; R]; C];
    let mut block = 0;
    while block + 16 <= R {
        // `registers[q][j]`: columns 4q..4q + 4 of rows 4j..4j + 4 of the block (only the
        // first `C.div_ceil(4)` of the `C` are used: an array length cannot be computed from
        // `C` in stable Rust).
        let mut registers = [[_mm512_setzero_ps(); 4]; C];
        for j in 0..4 {
            let at = block + 4 * j;
            let rows = [
                W::row(&texels[at]),
                W::row(&texels[at + 1]),
                W::row(&texels[at + 2]),
                W::row(&texels[at + 3]),
            ];
            for (q, register) in registers.iter_mut().take(C.div_ceil(4)).enumerate() {
                register[j] = quarters(&rows, 4 * q);
            }
        }
        // Transposed, result c of register q holds column 4q + c, row 4j + k in lane 4k + j.
        for (q, register) in registers.into_iter().take(C.div_ceil(4)).enumerate() {
            for (c, value) in transpose_quarters(register).into_iter().enumerate() {
                if let Some(column) = out.get_mut(4 * q + c) {
                    let lanes: &mut [u32; 16] = (&mut column[block..block + 16])
                        .try_into()
                        .expect("sixteen lanes");
                    // SAFETY: `lanes` is sixteen writable u32; the store needs no alignment.
                    unsafe { _mm512_storeu_ps(lanes.as_mut_ptr().cast(), value) };
                }
            }
        }
        block += 16;
    }
    for row in block..R {
        for (c, value) in W::row(&texels[row]).into_iter().enumerate() {
            out[c][row] = value;
        }
    }
    out
}

/// [`Isa::rows`] of [`Avx512`]: [`lanes`] backwards (the same shuffles: the order is its own
/// inverse).
#[target_feature(enable = "avx512f")]
#[inline]
fn rows<const R: usize, const C: usize>(lanes: &[[u32; R]; C]) -> [[u32; C]; R] {
    let mut out = [[0; C]; R];
    let mut block = 0;
    while block + 16 <= R {
        let mut column = 0;
        while column + 4 <= C {
            let columns: [__m512; 4] = std::array::from_fn(|c| {
                let lanes: &[u32; 16] = lanes[column + c][block..block + 16]
                    .try_into()
                    .expect("sixteen lanes");
                // SAFETY: `lanes` is sixteen readable u32; the load needs no alignment.
                unsafe { _mm512_loadu_ps(lanes.as_ptr().cast()) }
            });
            // Result j: quarter k holds row 4j + k's four columns.
            for (j, value) in transpose_quarters(columns).into_iter().enumerate() {
                store_quarters(&mut out, block + 4 * j, column, value);
            }
            column += 4;
        }
        for c in column..C {
            for row in 0..16 {
                out[block + row][c] = lanes[c][block + lane_of(row)];
            }
        }
        block += 16;
    }
    for row in block..R {
        for c in 0..C {
            out[row][c] = lanes[c][row];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::Words;
    use super::*;
    use gbuffer_core::codecs::unorm;

    /// Whether this CPU can run the tests; where it cannot, they say so and pass, as the
    /// copy they test never runs there.
    fn runs_here(test: &str) -> bool {
        let here = available();
        if !here {
            eprintln!("{test}: this CPU has no AVX-512; the AVX-512 copy cannot run here");
        }
        here
    }

    #[test]
    fn the_lanes_go_back_to_their_rows() {
        if !runs_here("the_lanes_go_back_to_their_rows") {
            return;
        }
        fn check<const R: usize, const C: usize>() {
            let mut matrix = [[0u32; C]; R];
            for (r, row) in matrix.iter_mut().enumerate() {
                for (c, value) in row.iter_mut().enumerate() {
                    *value = (r * 1000 + c) as u32;
                }
            }
            // SAFETY: `runs_here` checked the CPU.
            let (lanes, back) = unsafe {
                let lanes = lanes::<_, Words, R, C>(&matrix);
                (lanes, rows(&lanes))
            };
            assert_eq!(back, matrix, "{R}x{C}");
            // Every column holds each row once, in the documented lane.
            for (c, column) in lanes.iter().enumerate() {
                for r in 0..R {
                    let lane = if r < R / 16 * 16 {
                        r / 16 * 16 + lane_of(r % 16)
                    } else {
                        r
                    };
                    assert_eq!(column[lane], (r * 1000 + c) as u32, "{R}x{C} row {r}");
                }
            }
        }
        check::<16, 1>();
        check::<16, 4>();
        check::<16, 7>();
        check::<16, 12>();
        check::<16, 24>();
        check::<32, 5>();
        check::<17, 4>();
        check::<3, 4>();
    }

    /// Every f32 whose code changes between two neighbours' is where a wrong rounding would
    /// show; all of [0, 1] at 8 and 10 bits is too many for a unit test, so: every code's two
    /// boundaries and the floats beside them, every width, against the mirror; and a million
    /// spread values. `slices_every_f32` runs every f32 through the derived slices.
    #[test]
    fn the_unorm_encode_is_the_mirrors_at_every_boundary() {
        if !runs_here("the_unorm_encode_is_the_mirrors_at_every_boundary") {
            return;
        }
        let specials = [
            0.0,
            -0.0,
            -1.0,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            1.0,
            2.0,
            f32::from_bits(1),
            f32::MIN_POSITIVE,
        ];
        for bits in 1..=23 {
            let max = (1u32 << bits) - 1;
            let mut values: Vec<f32> = specials.to_vec();
            for code in (0..=max).step_by((max as usize / 4096).max(1)) {
                let boundary = (f64::from(code) + 0.5) / f64::from(max);
                let near = boundary as f32;
                values.extend([near.next_down(), near, near.next_up()]);
            }
            values.extend((0..100_000u32).map(|i| f32::from_bits(0x3f80_0000 - i * 10_651)));
            for chunk in values.chunks(16) {
                let mut lanes = [0.5f32; 16];
                lanes[..chunk.len()].copy_from_slice(chunk);
                // SAFETY: `runs_here` checked the CPU.
                let codes = stored(unsafe { unorm_codes(lanes.map(f32::to_bits), bits) });
                for (value, code) in lanes.into_iter().zip(codes) {
                    assert_eq!(
                        code,
                        unorm::unorm_from_f32(value, bits),
                        "{value:e} ({:#x}) at {bits} bits",
                        value.to_bits()
                    );
                }
            }
        }
    }

    /// The codes of `lanes` as `codes` gives them, stored.
    fn stored(codes: __m512i) -> [u32; 16] {
        let mut out = [0u32; 16];
        // SAFETY: `out` is sixteen writable u32; the store needs no alignment.
        unsafe { _mm512_storeu_si512(out.as_mut_ptr().cast(), codes) };
        out
    }

    /// Floats where the half rounding turns: the specials, both sides of
    /// every power of two a half can hold and of the midpoints between a half's neighbours
    /// around them, and a spread of every magnitude. `slices_every_f32` runs every f32.
    fn float_cases() -> Vec<f32> {
        let mut values = vec![
            0.0,
            -0.0,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MIN_POSITIVE,
            f32::from_bits(1),
            65504.0,
            65519.0,
            65520.0,
            65024.0,
            64512.0,
            1e9,
            -1e9,
        ];
        for half in 0..0x7c00u32 {
            let value = gbuffer_core::codecs::half::f32_from_half(half);
            let next = gbuffer_core::codecs::half::f32_from_half(half + 1);
            let middle = ((f64::from(value) + f64::from(next)) / 2.0) as f32;
            for x in [value, middle, middle.next_down(), middle.next_up()] {
                values.extend([x, -x]);
            }
        }
        values.extend((0..200_000u32).map(|i| f32::from_bits(i.wrapping_mul(21_475))));
        values
    }

    /// Runs `fast` on `values` sixteen at a time and holds each code to `mirror`'s.
    fn check(
        values: &[u32],
        fast: impl Fn([u32; 16]) -> __m512i,
        mirror: impl Fn(u32) -> u32,
        what: &str,
    ) {
        for chunk in values.chunks(16) {
            let mut lanes = [0u32; 16];
            lanes[..chunk.len()].copy_from_slice(chunk);
            for (lane, code) in lanes.into_iter().zip(stored(fast(lanes))) {
                assert_eq!(code, mirror(lane), "{what}: lane {lane:#x}");
            }
        }
    }

    #[test]
    fn the_half_encode_is_the_mirrors() {
        if !runs_here("the_half_encode_is_the_mirrors") {
            return;
        }
        let values: Vec<u32> = float_cases().into_iter().map(f32::to_bits).collect();
        // SAFETY: `runs_here` checked the CPU.
        let fast = |lanes| unsafe { half_codes(lanes) };
        let mirror = |lane| gbuffer_core::codecs::half::half_from_f32(f32::from_bits(lane));
        check(&values, fast, mirror, "half");
    }

    #[test]
    fn the_integer_encodes_are_the_mirrors() {
        if !runs_here("the_integer_encodes_are_the_mirrors") {
            return;
        }
        use gbuffer_core::codecs::integer::{sint_saturate, uint_saturate};
        let mut values = vec![0u32, 1, u32::MAX, i32::MAX as u32, i32::MIN as u32];
        for bits in 1..=32u32 {
            let max = max_code(bits);
            for edge in [max, max >> 1, !(max >> 1)] {
                values.extend([edge.wrapping_sub(1), edge, edge.wrapping_add(1)]);
            }
        }
        values.extend((0..10_000u32).map(|i| i.wrapping_mul(429_497)));
        for bits in 1..=32 {
            // SAFETY: `runs_here` checked the CPU.
            let fast = |lanes| unsafe { uint_codes(lanes, bits) };
            check(
                &values,
                fast,
                |lane| uint_saturate(lane, bits),
                &format!("uint {bits}"),
            );
            // SAFETY: as above.
            let fast = |lanes| unsafe { sint_codes(lanes, bits) };
            let mirror = |lane| sint_saturate(lane as i32, bits);
            check(&values, fast, mirror, &format!("sint {bits}"));
        }
    }

    /// Every half and every small-float code of every width, against the mirror's decodes,
    /// bit for bit (NaNs' payloads included).
    #[test]
    fn the_half_and_small_float_decodes_are_the_mirrors_for_every_code() {
        if !runs_here("the_half_and_small_float_decodes_are_the_mirrors_for_every_code") {
            return;
        }
        use gbuffer_core::codecs::{half, small_float};
        let decode = |codes: &[u32], shift: u32, mirror: &dyn Fn(u32) -> f32, what: &str| {
            for chunk in codes.chunks(16) {
                let mut lanes = [0u32; 16];
                lanes[..chunk.len()].copy_from_slice(chunk);
                // SAFETY: `runs_here` checked the CPU.
                let values = unsafe { f32_from_half(lanes.map(|code| code << shift)) };
                for (code, value) in lanes.into_iter().zip(values) {
                    let expected = mirror(code).to_bits();
                    assert_eq!(value.to_bits(), expected, "{what}: code {code:#x}");
                }
            }
        };
        let codes: Vec<u32> = (0..1 << 16).collect();
        decode(&codes, 0, &half::f32_from_half, "half");
        for bits in 6..=15 {
            let codes: Vec<u32> = (0..1 << bits).collect();
            let mirror = |code| small_float::f32_from_small_float(code, bits - 5);
            decode(
                &codes,
                15 - bits,
                &mirror,
                &format!("{bits}-bit small float"),
            );
        }
    }

    /// Every code of every width, against the mirror's decode (itself tested against f32
    /// division, correctly rounded).
    #[test]
    fn the_unorm_decode_is_the_mirrors_for_every_code() {
        if !runs_here("the_unorm_decode_is_the_mirrors_for_every_code") {
            return;
        }
        for bits in 1..=23 {
            let max = (1u32 << bits) - 1;
            let codes: Vec<u32> = (0..=max).collect();
            for chunk in codes.chunks(16) {
                let mut lanes = [0u32; 16];
                lanes[..chunk.len()].copy_from_slice(chunk);
                // SAFETY: `runs_here` checked the CPU.
                let values = unsafe { f32_from_unorm(lanes, bits) };
                for (code, value) in lanes.into_iter().zip(values) {
                    assert_eq!(
                        value.to_bits(),
                        unorm::f32_from_unorm(code, bits).to_bits(),
                        "code {code} of {bits} bits"
                    );
                }
            }
        }
    }
}
