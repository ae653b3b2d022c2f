//! The arrays of a batch type, in one allocation, their starts staggered so
//! that a loop reading all of them at once does not thrash the cache.
//!
//! A batch loop reads one element of every array per lane: twelve arrays for
//! box pairs, eight in and seven out for sphere contacts. Allocated one by
//! one, arrays of the same length usually start at the same offset modulo
//! 4 KiB (equal sizes laid end to end, or page-aligned blocks for large
//! ones), and a power-of-two count of boxes (1024 `f64` = 8 KiB) makes that
//! exact. Their elements at one index then fall into the same set of the L1
//! cache, which holds 8 lines per set: with twelve streams in one set, lines
//! are evicted before they are read out, and the box batch measured 2.2–3.0
//! ns per pair against 1.3 with the same data staggered (and 1.6 one pair at
//! a time). Here column `k` starts at `k · stride`, with `stride` at least
//! the capacity and chosen so that the columns' starts are at least [`GAP`]
//! bytes apart modulo [`PAGE`]: each column's stream has a set range of its
//! own.

use crate::real::Real;

/// The period of the L1 cache's set index, in bytes (64 sets of 64-byte
/// lines on x86-64 and most ARM cores; larger caches add ways, not sets).
const PAGE: usize = 4096;

/// Least distance between two columns' starts modulo [`PAGE`], in bytes: four
/// lines, so that each stream (and the next line a prefetcher brings in) has
/// sets of its own.
const GAP: usize = 256;

/// `K` columns of `T`, each `len` long, in one allocation: column `k` is
/// `data[k · stride .. k · stride + len]`.
#[derive(Clone)]
pub(crate) struct Columns<T: Real, const K: usize> {
    data: Vec<T>,
    len: usize,
    stride: usize,
}

impl<T: Real, const K: usize> Default for Columns<T, K> {
    fn default() -> Self {
        Self { data: Vec::new(), len: 0, stride: 0 }
    }
}

impl<T: Real, const K: usize> Columns<T, K> {
    /// Empty, with room for `n` rows.
    pub(crate) fn with_capacity(n: usize) -> Self {
        let mut c = Self::default();
        c.grow(n);
        c
    }

    /// The number of rows.
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Column `k` (empty past the last column).
    pub(crate) fn col(&self, k: usize) -> &[T] {
        let start = k * self.stride;
        self.data.get(start..start + self.len).unwrap_or(&[])
    }

    /// Every column.
    pub(crate) fn cols(&self) -> [&[T]; K] {
        core::array::from_fn(|k| self.col(k))
    }

    /// Every column, mutable (each its own slice, so a loop may write them
    /// all).
    pub(crate) fn cols_mut(&mut self) -> [&mut [T]; K] {
        let (len, stride) = (self.len, self.stride.max(1));
        let mut chunks = self.data.chunks_mut(stride);
        core::array::from_fn(|_| match chunks.next() {
            Some(c) => &mut c[..len],
            None => &mut [],
        })
    }

    /// Appends a row.
    pub(crate) fn push(&mut self, row: [T; K]) {
        if self.len == self.stride {
            self.grow((2 * self.stride).max(8));
        }
        let (len, stride) = (self.len, self.stride);
        for (k, x) in row.into_iter().enumerate() {
            self.data[k * stride + len] = x;
        }
        self.len += 1;
    }

    /// `n` rows: the first `min(n, len)` kept, the rest zero.
    pub(crate) fn resize(&mut self, n: usize) {
        if n > self.stride {
            self.grow(n);
        }
        let (len, stride) = (self.len, self.stride);
        if n > len {
            for k in 0..K {
                self.data[k * stride + len..k * stride + n].fill(T::zero());
            }
        }
        self.len = n;
    }

    /// Moves the columns to a new allocation with room for `n` rows.
    fn grow(&mut self, n: usize) {
        let stride = stride_for(n, size_of::<T>(), K);
        let mut data = vec![T::zero(); K * stride];
        for k in 0..K {
            data[k * stride..k * stride + self.len].copy_from_slice(self.col(k));
        }
        self.data = data;
        self.stride = stride;
    }
}

impl<T: Real, const K: usize> PartialEq for Columns<T, K> {
    fn eq(&self, other: &Self) -> bool {
        self.cols() == other.cols()
    }
}

impl<T: Real, const K: usize> core::fmt::Debug for Columns<T, K> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_list().entries(self.cols()).finish()
    }
}

/// The least stride (in elements of `size` bytes) of at least `n` whose
/// multiples `k · stride` for `k < columns` lie at least [`GAP`] bytes from
/// every multiple of [`PAGE`] (apart from `k = 0`): one stride of
/// `GAP / size` elements past a multiple of `PAGE` always qualifies (its
/// multiples up to `15 · GAP` stay clear), so the search ends within
/// `PAGE / size` steps and the padding is below one page per column.
fn stride_for(n: usize, size: usize, columns: usize) -> usize {
    let clear = |s: usize| {
        (1..columns).all(|k| {
            let d = (k * s * size) % PAGE;
            d.min(PAGE - d) >= GAP
        })
    };
    (n..).find(|&s| clear(s)).unwrap_or(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strides_keep_the_columns_apart_and_pad_little() {
        for size in [4, 8] {
            for columns in [4, 6, 7] {
                for n in [0, 1, 3, 64, 511, 512, 1024, 4096, 100_000] {
                    let s = stride_for(n, size, columns);
                    assert!(s >= n && (s - n) * size < PAGE, "n {n} size {size}: stride {s}");
                    for k in 1..columns {
                        let d = (k * s * size) % PAGE;
                        assert!(d.min(PAGE - d) >= GAP, "n {n} size {size} k {k}: {d}");
                    }
                }
            }
        }
    }

    #[test]
    fn push_resize_and_columns() {
        // Storage only: every value read back is one written, compared by
        // its bits.
        let bits = |xs: &[f64]| xs.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let rows: Vec<[f64; 3]> = (0..100).map(|i| [f64::from(i), f64::from(i) + 0.5, -f64::from(i)]).collect();
        let mut c: Columns<f64, 3> = Columns::default();
        for r in &rows {
            c.push(*r);
        }
        assert_eq!(c.len(), 100);
        for k in 0..3 {
            assert_eq!(bits(c.col(k)), bits(&rows.iter().map(|r| r[k]).collect::<Vec<_>>()), "column {k}");
        }
        assert!(c.col(3).is_empty());
        c.resize(10);
        c.resize(12);
        assert_eq!(bits(&c.col(2)[..10]), bits(&rows[..10].iter().map(|r| r[2]).collect::<Vec<_>>()));
        assert_eq!(bits(&c.col(2)[10..]), vec![0; 2], "rows past the old length are zero");
        let [a, _, d] = c.cols_mut();
        a[0] = 7.0;
        d[11] = 9.0;
        assert_eq!(c.cols()[0][0].to_bits(), 7.0f64.to_bits());
        assert_eq!(c.cols()[2][11].to_bits(), 9.0f64.to_bits());
        assert_eq!(c.clone(), c);
        let mut big = Columns::<f32, 6>::with_capacity(1024);
        big.resize(1024);
        assert!(big.cols().iter().all(|x| x.len() == 1024));
    }
}
