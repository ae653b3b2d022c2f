//! Boxes against boxes, over arrays: the broad phase's overlap test.

use super::columns::Columns;
#[cfg(test)]
use crate::bounds::test_aabb_aabb;
use crate::real::{Real, Vec3};
use crate::shapes::Aabb;

/// Axis-aligned boxes as a structure of arrays: box `i` spans
/// `[min_x[i], max_x[i]] × [min_y[i], max_y[i]] × [min_z[i], max_z[i]]`, each
/// coordinate an array of its own ([`min_x`](Self::min_x) …). The six arrays
/// share one allocation, their starts staggered (see `columns.rs`) so that
/// the batch loop's twelve streams do not evict each other from the cache
/// whatever the number of boxes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Aabbs<T: Real> {
    /// `min_x, min_y, min_z, max_x, max_y, max_z`.
    cols: Columns<T, 6>,
}

impl<T: Real> Aabbs<T> {
    /// No boxes.
    pub fn new() -> Self {
        Self::default()
    }

    /// No boxes, room for `n`.
    pub fn with_capacity(n: usize) -> Self {
        Self { cols: Columns::with_capacity(n) }
    }

    /// Appends a box.
    pub fn push(&mut self, b: &Aabb<T>) {
        self.cols.push([b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z]);
    }

    /// The number of boxes.
    pub fn len(&self) -> usize {
        self.cols.len()
    }

    /// Whether there are no boxes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Box `i`, or `None` past the end.
    pub fn get(&self, i: usize) -> Option<Aabb<T>> {
        let [x0, y0, z0, x1, y1, z1] = self.cols.cols();
        let min = Vec3::new(*x0.get(i)?, *y0.get(i)?, *z0.get(i)?);
        let max = Vec3::new(*x1.get(i)?, *y1.get(i)?, *z1.get(i)?);
        Some(Aabb { min, max })
    }

    /// Lower corners' `x`.
    pub fn min_x(&self) -> &[T] {
        self.cols.col(0)
    }

    /// Lower corners' `y`.
    pub fn min_y(&self) -> &[T] {
        self.cols.col(1)
    }

    /// Lower corners' `z`.
    pub fn min_z(&self) -> &[T] {
        self.cols.col(2)
    }

    /// Upper corners' `x`.
    pub fn max_x(&self) -> &[T] {
        self.cols.col(3)
    }

    /// Upper corners' `y`.
    pub fn max_y(&self) -> &[T] {
        self.cols.col(4)
    }

    /// Upper corners' `z`.
    pub fn max_z(&self) -> &[T] {
        self.cols.col(5)
    }

    /// The six arrays cut to boxes `range`, in the order
    /// `min_x, min_y, min_z, max_x, max_y, max_z`.
    pub(crate) fn lanes(&self, range: core::ops::Range<usize>) -> [&[T]; 6] {
        self.cols.cols().map(|c| &c[range.clone()])
    }
}

impl<'a, T: Real> FromIterator<&'a Aabb<T>> for Aabbs<T> {
    fn from_iter<I: IntoIterator<Item = &'a Aabb<T>>>(iter: I) -> Self {
        let iter = iter.into_iter();
        let mut s = Aabbs::with_capacity(iter.size_hint().0);
        for b in iter {
            s.push(b);
        }
        s
    }
}

/// Whether boxes `a[i]` and `b[i]` overlap, for every `i` below the shorter
/// length `n`, written to `out` (resized to `n`; it allocates only when it
/// grows): exactly [`test_aabb_aabb`](crate::bounds::test_aabb_aabb)`(a[i], b[i])` — the same six
/// comparisons, touching counts.
///
/// **Formula** (the lecture's separating axes, as in [`test_aabb_aabb`](crate::bounds::test_aabb_aabb)):
/// overlap ⇔ for every axis `k`, `a.min_k ≤ b.max_k` and `b.min_k ≤ a.max_k`.
///
/// **How it vectorizes.** One lane per pair, the six comparisons combined
/// with `&` (no branch), each coordinate read from its own contiguous array:
/// the loop is straight-line comparisons on slices, which the compiler turns
/// into packed compares, several pairs per instruction, where one pair at a
/// time is bound by loading its twelve scattered numbers.
/// `cargo bench --bench queries` measures it against the one-at-a-time loop
/// and against parry's `Aabb::intersects`.
///
/// Exact: comparisons only. Degenerate input: as [`test_aabb_aabb`](crate::bounds::test_aabb_aabb).
pub fn test_aabbs_aabbs<T: Real>(a: &Aabbs<T>, b: &Aabbs<T>, out: &mut Vec<bool>) {
    let n = a.len().min(b.len());
    out.resize(n, false);
    let [ax0, ay0, az0, ax1, ay1, az1] = a.lanes(0..n);
    let [bx0, by0, bz0, bx1, by1, bz1] = b.lanes(0..n);
    for (i, o) in out[..n].iter_mut().enumerate() {
        *o = (ax0[i] <= bx1[i])
            & (bx0[i] <= ax1[i])
            & (ay0[i] <= by1[i])
            & (by0[i] <= ay1[i])
            & (az0[i] <= bz1[i])
            & (bz0[i] <= az1[i]);
    }
}

/// Whether box `one` overlaps `many[i]`, for every `i`, written to `out`
/// (resized to `many.len()`): exactly [`test_aabb_aabb`](crate::bounds::test_aabb_aabb)`(one, many[i])` —
/// the broad phase's "which of these boxes does this one touch", one box's
/// six numbers held in registers against the arrays. Vectorizes as
/// [`test_aabbs_aabbs`] does.
pub fn test_aabb_aabbs<T: Real>(one: &Aabb<T>, many: &Aabbs<T>, out: &mut Vec<bool>) {
    let n = many.len();
    out.resize(n, false);
    overlap_lanes(one, many.lanes(0..n), &mut out[..n]);
}

/// [`test_aabb_aabbs`]'s loop over lanes: `out[i]` is whether `one` overlaps
/// box `i` of the arrays `min_x, min_y, min_z, max_x, max_y, max_z` (each
/// cut to `out`'s length first: no bounds checks in the loop). Also the box
/// pass of the segments–mesh batch.
#[inline(always)]
pub(crate) fn overlap_lanes<T: Real>(one: &Aabb<T>, lanes: [&[T]; 6], out: &mut [bool]) {
    let n = out.len();
    let [x0, y0, z0, x1, y1, z1] = lanes.map(|c| &c[..n]);
    let (lo, hi) = (one.min, one.max);
    for (i, o) in out.iter_mut().enumerate() {
        *o = (lo.x <= x1[i]) & (x0[i] <= hi.x) & (lo.y <= y1[i]) & (y0[i] <= hi.y) & (lo.z <= z1[i]) & (z0[i] <= hi.z);
    }
}

/// The same answers one pair at a time, for the tests.
#[cfg(test)]
fn one_at_a_time<T: Real>(a: &Aabbs<T>, b: &Aabbs<T>) -> Vec<bool> {
    (0..a.len().min(b.len())).filter_map(|i| Some(test_aabb_aabb(&a.get(i)?, &b.get(i)?))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A box from a corner and non-negative extents (some zero: flat boxes
    /// and points), on a coarse grid so that touching faces are common.
    fn aabb() -> impl Strategy<Value = Spec> {
        (prop::array::uniform3(-6i32..6), prop::array::uniform3(0u8..4))
    }

    fn make<T: Real>((c, e): &Spec) -> Aabb<T> {
        let min = Vec3::new(T::of(f64::from(c[0])), T::of(f64::from(c[1])), T::of(f64::from(c[2])));
        let ext = Vec3::new(T::of(f64::from(e[0])), T::of(f64::from(e[1])), T::of(f64::from(e[2])));
        Aabb { min, max: min + ext }
    }

    /// A box as its corner and extents (see [`aabb`]).
    type Spec = ([i32; 3], [u8; 3]);

    fn check<T: Real>(pairs: &[(Spec, Spec)]) -> Result<(), TestCaseError> {
        let a: Vec<Aabb<T>> = pairs.iter().map(|p| make(&p.0)).collect();
        let b: Vec<Aabb<T>> = pairs.iter().map(|p| make(&p.1)).collect();
        let (sa, sb): (Aabbs<T>, Aabbs<T>) = (a.iter().collect(), b.iter().collect());
        let mut out = vec![true; 3];
        test_aabbs_aabbs(&sa, &sb, &mut out);
        prop_assert_eq!(&out, &one_at_a_time(&sa, &sb));
        if let Some(first) = a.first() {
            test_aabb_aabbs(first, &sb, &mut out);
            let want: Vec<bool> = b.iter().map(|x| test_aabb_aabb(first, x)).collect();
            prop_assert_eq!(out, want);
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn batch_matches_one_pair_at_a_time_f64(p in proptest::collection::vec((aabb(), aabb()), 0..40)) {
            check::<f64>(&p)?;
        }

        #[test]
        fn batch_matches_one_pair_at_a_time_f32(p in proptest::collection::vec((aabb(), aabb()), 0..40)) {
            check::<f32>(&p)?;
        }
    }

    #[test]
    fn touching_faces_count_and_a_gap_does_not() {
        // Unit boxes at x = 0, 1 (sharing the face x = 1) and 2.5 (a gap of 0.5).
        let at = |x: f64| Aabb { min: Vec3::new(x, 0.0, 0.0), max: Vec3::new(x + 1.0, 1.0, 1.0) };
        let a: Aabbs<f64> = [at(0.0), at(0.0)].iter().collect();
        let b: Aabbs<f64> = [at(1.0), at(2.5)].iter().collect();
        let mut out = Vec::new();
        test_aabbs_aabbs(&a, &b, &mut out);
        assert_eq!(out, vec![true, false]);
        test_aabb_aabbs(&at(0.0), &b, &mut out);
        assert_eq!(out, vec![true, false]);
    }

    #[test]
    fn batches_of_unequal_length_use_the_shorter() {
        let unit = Aabb { min: Vec3::new(0.0, 0.0, 0.0), max: Vec3::new(1.0, 1.0, 1.0) };
        let a: Aabbs<f64> = [unit, unit].iter().collect();
        assert_eq!(a.len(), 2);
        let b: Aabbs<f64> = [unit, unit, unit].iter().collect();
        let mut out = Vec::new();
        test_aabbs_aabbs(&a, &b, &mut out);
        assert_eq!(out, vec![true, true]);
        assert!(a.get(2).is_none());
    }
}
