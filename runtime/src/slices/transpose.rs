//! Transposes of small `u32` matrices, rows to columns: the texels' rows of components to
//! lanes of eight, and the lanes of words back to each texel's words.
//!
//! The AVX2 form moves blocks of 8x8, 8x4 and 4x8 through registers with the classic
//! unpack/shuffle/permute network (Intel's optimisation manual, "8x8 matrix transpose";
//! three rounds of two-input shuffles, each round interleaving pairs of rows at twice the
//! previous grain); what no block covers is moved by the plain loop.

/// `[c][r] = matrix[r][c]`, element by element.
#[inline(always)]
pub fn portable<const R: usize, const C: usize>(matrix: &[[u32; C]; R]) -> [[u32; R]; C] {
    let mut out = [[0; R]; C];
    by_element(matrix, &mut out, 0..R, 0..C);
    out
}

/// `[c][r] = matrix[r][c]`, by blocks of AVX2 registers.
///
/// # Safety
///
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub unsafe fn avx2<const R: usize, const C: usize>(matrix: &[[u32; C]; R]) -> [[u32; R]; C] {
    let mut out = [[0; R]; C];
    let mut row = 0;
    while row + 8 <= R {
        let mut column = 0;
        while column + 8 <= C {
            block_8x8(matrix, &mut out, row, column);
            column += 8;
        }
        if column + 4 <= C {
            block_8x4(matrix, &mut out, row, column);
            column += 4;
        }
        by_element(matrix, &mut out, row..row + 8, column..C);
        row += 8;
    }
    if row + 4 <= R {
        let mut column = 0;
        while column + 8 <= C {
            block_4x8(matrix, &mut out, row, column);
            column += 8;
        }
        by_element(matrix, &mut out, row..row + 4, column..C);
        row += 4;
    }
    by_element(matrix, &mut out, row..R, 0..C);
    out
}

/// Rows `rows` and columns `columns` of the transpose, element by element: the whole of
/// [`portable`], and what no block of [`avx2`] covers.
#[inline(always)]
fn by_element<const R: usize, const C: usize>(
    matrix: &[[u32; C]; R],
    out: &mut [[u32; R]; C],
    rows: std::ops::Range<usize>,
    columns: std::ops::Range<usize>,
) {
    for r in rows {
        for c in columns.clone() {
            out[c][r] = matrix[r][c];
        }
    }
}

#[cfg(target_arch = "x86_64")]
mod blocks {
    use std::arch::x86_64::*;

    /// Eight `u32` from `row[at..at + 8]`, as floats for the float shuffles (bits unchanged).
    #[target_feature(enable = "avx2")]
    #[inline]
    fn load8<const N: usize>(row: &[u32; N], at: usize) -> __m256 {
        let lanes: &[u32; 8] = row[at..at + 8].try_into().expect("eight lanes");
        // SAFETY: `lanes` is eight readable u32; the load needs no alignment.
        unsafe { _mm256_loadu_ps(lanes.as_ptr().cast()) }
    }

    #[target_feature(enable = "avx2")]
    #[inline]
    fn load4<const N: usize>(row: &[u32; N], at: usize) -> __m128 {
        let lanes: &[u32; 4] = row[at..at + 4].try_into().expect("four lanes");
        // SAFETY: `lanes` is four readable u32; the load needs no alignment.
        unsafe { _mm_loadu_ps(lanes.as_ptr().cast()) }
    }

    #[target_feature(enable = "avx2")]
    #[inline]
    fn store8<const N: usize>(row: &mut [u32; N], at: usize, value: __m256) {
        let lanes: &mut [u32; 8] = (&mut row[at..at + 8]).try_into().expect("eight lanes");
        // SAFETY: `lanes` is eight writable u32; the store needs no alignment.
        unsafe { _mm256_storeu_ps(lanes.as_mut_ptr().cast(), value) }
    }

    #[target_feature(enable = "avx2")]
    #[inline]
    fn store4<const N: usize>(row: &mut [u32; N], at: usize, value: __m128) {
        let lanes: &mut [u32; 4] = (&mut row[at..at + 4]).try_into().expect("four lanes");
        // SAFETY: `lanes` is four writable u32; the store needs no alignment.
        unsafe { _mm_storeu_ps(lanes.as_mut_ptr().cast(), value) }
    }

    /// Rows `row..row + 4`, eight `u32` each from `column`.
    #[target_feature(enable = "avx2")]
    #[inline]
    fn load_rows<const R: usize, const C: usize>(
        matrix: &[[u32; C]; R],
        row: usize,
        column: usize,
    ) -> [__m256; 4] {
        let mut rows = [_mm256_setzero_ps(); 4];
        for (r, value) in rows.iter_mut().enumerate() {
            *value = load8(&matrix[row + r], column);
        }
        rows
    }

    /// Within each 128-bit half, the 4x4 transpose of the four registers' halves.
    #[target_feature(enable = "avx2")]
    #[inline]
    fn transpose_halves(rows: [__m256; 4]) -> [__m256; 4] {
        let low01 = _mm256_unpacklo_ps(rows[0], rows[1]);
        let high01 = _mm256_unpackhi_ps(rows[0], rows[1]);
        let low23 = _mm256_unpacklo_ps(rows[2], rows[3]);
        let high23 = _mm256_unpackhi_ps(rows[2], rows[3]);
        [
            _mm256_shuffle_ps::<0x44>(low01, low23),
            _mm256_shuffle_ps::<0xee>(low01, low23),
            _mm256_shuffle_ps::<0x44>(high01, high23),
            _mm256_shuffle_ps::<0xee>(high01, high23),
        ]
    }

    /// Rows `row..row + 8`, columns `column..column + 8`.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub fn block_8x8<const R: usize, const C: usize>(
        matrix: &[[u32; C]; R],
        out: &mut [[u32; R]; C],
        row: usize,
        column: usize,
    ) {
        let top = transpose_halves(load_rows(matrix, row, column));
        let bottom = transpose_halves(load_rows(matrix, row + 4, column));
        // top[j] holds column j's rows 0-3 in its low half and column j + 4's in its high.
        for j in 0..4 {
            let low = _mm256_permute2f128_ps::<0x20>(top[j], bottom[j]);
            let high = _mm256_permute2f128_ps::<0x31>(top[j], bottom[j]);
            store8(&mut out[column + j], row, low);
            store8(&mut out[column + j + 4], row, high);
        }
    }

    /// Rows `row..row + 8`, columns `column..column + 4`.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub fn block_8x4<const R: usize, const C: usize>(
        matrix: &[[u32; C]; R],
        out: &mut [[u32; R]; C],
        row: usize,
        column: usize,
    ) {
        // Row r in the low half and row r + 4 in the high: one 4x4 transpose per half.
        let mut pairs = [_mm256_setzero_ps(); 4];
        for (r, value) in pairs.iter_mut().enumerate() {
            let low = load4(&matrix[row + r], column);
            let high = load4(&matrix[row + r + 4], column);
            *value = _mm256_set_m128(high, low);
        }
        let columns = transpose_halves(pairs);
        for (j, value) in columns.into_iter().enumerate() {
            store8(&mut out[column + j], row, value);
        }
    }

    /// Rows `row..row + 4`, columns `column..column + 8`.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub fn block_4x8<const R: usize, const C: usize>(
        matrix: &[[u32; C]; R],
        out: &mut [[u32; R]; C],
        row: usize,
        column: usize,
    ) {
        let halves = transpose_halves(load_rows(matrix, row, column));
        // halves[j] holds column j's four rows in its low half and column j + 4's in its high.
        for (j, value) in halves.into_iter().enumerate() {
            store4(&mut out[column + j], row, _mm256_castps256_ps128(value));
            store4(
                &mut out[column + j + 4],
                row,
                _mm256_extractf128_ps::<1>(value),
            );
        }
    }
}

#[cfg(target_arch = "x86_64")]
use blocks::{block_4x8, block_8x4, block_8x8};

#[cfg(test)]
mod tests {
    use super::*;

    /// Every shape the derive can ask for, from one row or column to past two blocks, against
    /// the definition.
    fn check<const R: usize, const C: usize>() {
        let mut matrix = [[0u32; C]; R];
        for (r, row) in matrix.iter_mut().enumerate() {
            for (c, value) in row.iter_mut().enumerate() {
                *value = (r * 1000 + c) as u32;
            }
        }
        let plain = portable(&matrix);
        for (c, column) in plain.iter().enumerate() {
            for (r, &value) in column.iter().enumerate() {
                assert_eq!(value, (r * 1000 + c) as u32, "{R}x{C} [{c}][{r}]");
            }
        }
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: checked just above.
            assert_eq!(unsafe { avx2(&matrix) }, plain, "{R}x{C} through AVX2");
        }
    }

    #[test]
    fn every_shape_transposes_as_the_definition_says() {
        check::<8, 1>();
        check::<8, 3>();
        check::<8, 4>();
        check::<8, 7>();
        check::<8, 8>();
        check::<8, 12>();
        check::<8, 13>();
        check::<8, 21>();
        check::<1, 8>();
        check::<3, 8>();
        check::<4, 8>();
        check::<5, 8>();
        check::<12, 8>();
        check::<13, 8>();
        check::<16, 8>();
        check::<21, 8>();
    }
}
