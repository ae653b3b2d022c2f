//! Spheres against spheres, pairwise, over arrays.

use crate::contact::{CONCENTRIC_FALLBACK_NORMAL, Contact, contact_sphere_sphere};
use crate::exact::norm::{clear_miss_factor, safe_squared_range};
use crate::real::{Real, Vec3};
use crate::shapes::Sphere;
use core::ops::Range;

use super::columns::Columns;

/// Spheres as a structure of arrays: sphere `i` is centred at
/// `(x[i], y[i], z[i])` with radius `radius[i]`, each an array of its own
/// ([`x`](Self::x) …), in one allocation with staggered starts (see
/// `columns.rs`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Spheres<T: Real> {
    /// `x, y, z, radius`.
    cols: Columns<T, 4>,
}

impl<T: Real> Spheres<T> {
    /// No spheres.
    pub fn new() -> Self {
        Self::default()
    }

    /// No spheres, room for `n`.
    pub fn with_capacity(n: usize) -> Self {
        Self { cols: Columns::with_capacity(n) }
    }

    /// Appends a sphere.
    pub fn push(&mut self, s: &Sphere<T>) {
        self.cols.push([s.center.x, s.center.y, s.center.z, s.radius]);
    }

    /// The number of spheres.
    pub fn len(&self) -> usize {
        self.cols.len()
    }

    /// Whether there are no spheres.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Sphere `i`, or `None` past the end.
    pub fn get(&self, i: usize) -> Option<Sphere<T>> {
        let [x, y, z, r] = self.cols.cols();
        Some(Sphere::new(Vec3::new(*x.get(i)?, *y.get(i)?, *z.get(i)?), *r.get(i)?))
    }

    /// Centres' `x`.
    pub fn x(&self) -> &[T] {
        self.cols.col(0)
    }

    /// Centres' `y`.
    pub fn y(&self) -> &[T] {
        self.cols.col(1)
    }

    /// Centres' `z`.
    pub fn z(&self) -> &[T] {
        self.cols.col(2)
    }

    /// Radii.
    pub fn radius(&self) -> &[T] {
        self.cols.col(3)
    }

    /// The four arrays cut to the first `n` spheres: `x, y, z, radius`.
    fn lanes(&self, n: usize) -> [&[T]; 4] {
        self.cols.cols().map(|c| &c[..n])
    }
}

impl<'a, T: Real> FromIterator<&'a Sphere<T>> for Spheres<T> {
    fn from_iter<I: IntoIterator<Item = &'a Sphere<T>>>(iter: I) -> Self {
        let iter = iter.into_iter();
        let mut s = Spheres::with_capacity(iter.size_hint().0);
        for x in iter {
            s.push(x);
        }
        s
    }
}

/// The answers of [`contact_spheres_spheres`], as a structure of arrays: pair
/// `i` is in contact when `hit()[i]`, and then its [`Contact`] is
/// `{point: (point_x()[i], point_y()[i], point_z()[i]), normal: (normal_x()[i],
/// …), depth: depth()[i], degenerate: degenerate()[i]}`; for a pair not in
/// contact every number is 0 and `degenerate` false. The seven number arrays
/// share one allocation with staggered starts (see `columns.rs`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SphereContacts<T: Real> {
    /// Whether pair `i` touches or overlaps.
    hit: Vec<bool>,
    /// `point_x, point_y, point_z, normal_x, normal_y, normal_z, depth`.
    cols: Columns<T, 7>,
    /// The normal is a fallback (see [`contact_sphere_sphere`]).
    degenerate: Vec<bool>,
}

impl<T: Real> SphereContacts<T> {
    /// No answers yet; [`contact_spheres_spheres`] sizes the arrays.
    pub fn new() -> Self {
        Self::default()
    }

    /// The number of pairs answered.
    pub fn len(&self) -> usize {
        self.hit.len()
    }

    /// Whether no pair was answered.
    pub fn is_empty(&self) -> bool {
        self.hit.is_empty()
    }

    /// Pair `i`'s answer as [`contact_sphere_sphere`] gives it (`None` for no
    /// contact or past the end).
    pub fn get(&self, i: usize) -> Option<Contact<T>> {
        if !*self.hit.get(i)? {
            return None;
        }
        let [px, py, pz, nx, ny, nz, depth] = self.cols.cols();
        Some(Contact {
            point: Vec3::new(px[i], py[i], pz[i]),
            normal: Vec3::new(nx[i], ny[i], nz[i]),
            depth: depth[i],
            degenerate: self.degenerate[i],
        })
    }

    /// Whether each pair touches or overlaps.
    pub fn hit(&self) -> &[bool] {
        &self.hit
    }

    /// Contact points' `x` (on sphere `b[i]`).
    pub fn point_x(&self) -> &[T] {
        self.cols.col(0)
    }

    /// Contact points' `y`.
    pub fn point_y(&self) -> &[T] {
        self.cols.col(1)
    }

    /// Contact points' `z`.
    pub fn point_z(&self) -> &[T] {
        self.cols.col(2)
    }

    /// Normals' `x` (unit, from `b[i]` toward `a[i]`).
    pub fn normal_x(&self) -> &[T] {
        self.cols.col(3)
    }

    /// Normals' `y`.
    pub fn normal_y(&self) -> &[T] {
        self.cols.col(4)
    }

    /// Normals' `z`.
    pub fn normal_z(&self) -> &[T] {
        self.cols.col(5)
    }

    /// Penetration depths.
    pub fn depth(&self) -> &[T] {
        self.cols.col(6)
    }

    /// Whether each pair's normal is a fallback (see [`contact_sphere_sphere`]).
    pub fn degenerate(&self) -> &[bool] {
        &self.degenerate
    }

    fn resize(&mut self, n: usize) {
        self.hit.resize(n, false);
        self.degenerate.resize(n, false);
        self.cols.resize(n);
    }

    fn set(&mut self, i: usize, k: Option<Contact<T>>) {
        let k = k.map_or((false, [T::zero(); 7], false), |k| {
            (true, [k.point.x, k.point.y, k.point.z, k.normal.x, k.normal.y, k.normal.z, k.depth], k.degenerate)
        });
        self.hit[i] = k.0;
        for (col, x) in self.cols.cols_mut().into_iter().zip(k.1) {
            col[i] = x;
        }
        self.degenerate[i] = k.2;
    }
}

/// `x` where `keep`, else 0 — a selection, not a branch.
#[inline(always)]
fn select<T: Real>(keep: bool, x: T) -> T {
    if keep { x } else { T::zero() }
}

/// Contact between spheres `a[i]` and `b[i]` for every `i` below the shorter
/// length `n`, written to `out` (resized to `n`; it allocates only when it
/// grows): the answers of [`contact_sphere_sphere`]`(a[i], b[i])`, bit for bit,
/// in the convention of [`Contact`] (normal from `b[i]` toward `a[i]`, point on
/// `b[i]`, touching counts).
///
/// **Formula** (the lecture's, as in [`contact_sphere_sphere`]): with
/// `Δ = M_a − M_b`, `reach = r_a + r_b`: apart when `‖Δ‖² > reach² (1 + 8u)`
/// (no root needed) or `√‖Δ‖² > reach`; otherwise `n = Δ · (1/‖Δ‖)`,
/// `p = M_b + r_b n`, `depth = reach − ‖Δ‖`.
///
/// **How it vectorizes.** The first pass computes every lane with the same
/// straight-line arithmetic (all of them take the root and the division — on
/// packed registers that costs less than a branch per pair), and keeps or
/// zeroes the answers by the contact mask. Exactly concentric centres get the
/// one-pair function's flagged fallback there too (common in `f32`, where
/// centres a hair apart round to one point). Other lanes whose `‖Δ‖²` lies
/// outside the range where the plain root is exact enough (`[2^−918, 2^920]`
/// in `f64`: distances that underflow or overflow) are answered in
/// a second pass by [`contact_sphere_sphere`] itself, which scales them. The
/// lanes go in blocks of `BLOCK` (64 lanes), and only a block holding such a lane is
/// looked at again.
///
/// **Degenerate input**: as [`contact_sphere_sphere`] (concentric: fallback
/// normal, flagged). Never NaN for finite input.
pub fn contact_spheres_spheres<T: Real>(a: &Spheres<T>, b: &Spheres<T>, out: &mut SphereContacts<T>) {
    let n = a.len().min(b.len());
    out.resize(n);
    let [ax, ay, az, ar] = a.lanes(n);
    let [bx, by, bz, br] = b.lanes(n);
    for r in blocks(n) {
        let [px, py, pz, nx, ny, nz, depth] = out.cols.cols_mut();
        let slow = contact_lanes(
            &ax[r.clone()],
            &ay[r.clone()],
            &az[r.clone()],
            &ar[r.clone()],
            &bx[r.clone()],
            &by[r.clone()],
            &bz[r.clone()],
            &br[r.clone()],
            &mut out.hit[r.clone()],
            &mut out.degenerate[r.clone()],
            &mut px[r.clone()],
            &mut py[r.clone()],
            &mut pz[r.clone()],
            &mut nx[r.clone()],
            &mut ny[r.clone()],
            &mut nz[r.clone()],
            &mut depth[r.clone()],
        );
        // Second pass, if needed: this block's lanes the first pass left
        // open (outside the fast range, not concentric), one at a time.
        if slow {
            for (i, x, y) in left_open([ax, ay, az, ar], [bx, by, bz, br], r, None) {
                out.set(i, contact_sphere_sphere(&x, &y));
            }
        }
    }
}

/// The first pass of [`contact_spheres_spheres`]: every lane computed alike;
/// returns whether any lane lies outside the fast range.
/// A function of its own so that each array is a separate reference
/// parameter: the compiler then knows that no output aliases another or an
/// input (references inside an array, a tuple or a struct carry no such
/// guarantee), and vectorizes the loop without run-time overlap checks.
#[inline(never)]
#[allow(clippy::too_many_arguments, reason = "one parameter per array: see above")]
fn contact_lanes<T: Real>(
    ax: &[T],
    ay: &[T],
    az: &[T],
    ar: &[T],
    bx: &[T],
    by: &[T],
    bz: &[T],
    br: &[T],
    hit: &mut [bool],
    degenerate: &mut [bool],
    px: &mut [T],
    py: &mut [T],
    pz: &mut [T],
    nx: &mut [T],
    ny: &mut [T],
    nz: &mut [T],
    depth: &mut [T],
) -> bool {
    let n = hit.len();
    // Every array cut to `n` here, one by one, so that the loop's indexing
    // needs no bounds checks (which would stop the vectorizer).
    let (ax, ay, az, ar) = (&ax[..n], &ay[..n], &az[..n], &ar[..n]);
    let (bx, by, bz, br) = (&bx[..n], &by[..n], &bz[..n], &br[..n]);
    let (degenerate, px, py, pz) = (&mut degenerate[..n], &mut px[..n], &mut py[..n], &mut pz[..n]);
    let (nx, ny, nz, depth) = (&mut nx[..n], &mut ny[..n], &mut nz[..n], &mut depth[..n]);
    let (lo, hi) = safe_squared_range::<T>();
    let factor = clear_miss_factor::<T>();
    // `|d| ≤ largest finite` is `d.is_finite()` written as a comparison, which
    // the vectorizer costs as one packed compare (the bit test it is otherwise
    // lowered to made it judge the loop not worth vectorizing).
    let largest = T::max_value().unwrap_or_else(|| T::of(f64::MAX));
    let [fx, fy, fz] = CONCENTRIC_FALLBACK_NORMAL.map(T::of);
    let mut slow = false;
    for i in 0..n {
        let (dx, dy, dz) = (ax[i] - bx[i], ay[i] - by[i], az[i] - bz[i]);
        let dd = T::zero() + ((dx * dx + dy * dy) + dz * dz);
        let reach = ar[i] + br[i];
        let dist = dd.sqrt();
        let inv = T::one() / dist;
        let fast = (dd >= lo) & (dd <= hi);
        let apart = (dd > reach * reach * factor) | (dist > reach);
        // Exactly concentric centres: the one-pair function's flagged
        // fallback (normal `CONCENTRIC_FALLBACK_NORMAL`, depth the reach),
        // whatever the radii.
        let concentric = concentric(dx, dy, dz);
        let keep = (fast & !apart) | concentric;
        let pick = |x: T, fallback: T| if concentric { fallback } else { x };
        let (ux, uy, uz) = (pick(dx * inv, fx), pick(dy * inv, fy), pick(dz * inv, fz));
        let d = pick(reach - dist, reach);
        hit[i] = keep;
        nx[i] = select(keep, ux);
        ny[i] = select(keep, uy);
        nz[i] = select(keep, uz);
        px[i] = select(keep, bx[i] + ux * br[i]);
        py[i] = select(keep, by[i] + uy * br[i]);
        pz[i] = select(keep, bz[i] + uz * br[i]);
        depth[i] = select(keep, d);
        let finite = d.abs() <= largest; // false for NaN and ±∞
        degenerate[i] = (keep & !finite) | concentric;
        slow |= !(fast | concentric);
    }
    slow
}

/// The first pass of [`test_spheres_spheres`]; returns whether any lane is
/// outside the fast range. Separate parameters, as [`contact_lanes`].
#[inline(never)]
#[allow(clippy::too_many_arguments, reason = "one parameter per array: see contact_lanes")]
fn test_lanes<T: Real>(
    ax: &[T],
    ay: &[T],
    az: &[T],
    ar: &[T],
    bx: &[T],
    by: &[T],
    bz: &[T],
    br: &[T],
    hit: &mut [bool],
) -> bool {
    let n = hit.len();
    let (ax, ay, az, ar) = (&ax[..n], &ay[..n], &az[..n], &ar[..n]);
    let (bx, by, bz, br) = (&bx[..n], &by[..n], &bz[..n], &br[..n]);
    let (lo, hi) = safe_squared_range::<T>();
    let factor = clear_miss_factor::<T>();
    let sure_reach = near_concentric_reach::<T>();
    let mut slow = false;
    for i in 0..n {
        let (dx, dy, dz) = (ax[i] - bx[i], ay[i] - by[i], az[i] - bz[i]);
        let dd = T::zero() + ((dx * dx + dy * dy) + dz * dz);
        let reach = ar[i] + br[i];
        let fast = (dd >= lo) & (dd <= hi);
        let apart = (dd > reach * reach * factor) | (dd.sqrt() > reach);
        // Below the fast range the centres are (nearly) concentric: exactly
        // concentric ones touch whatever the radii (the one-pair function's
        // flagged fallback), others with a reach of at least `sure_reach`
        // certainly touch, and the one-pair function's scaled path says so.
        let concentric = concentric(dx, dy, dz);
        let sure_touch = ((dd < lo) & (reach >= sure_reach)) | concentric;
        hit[i] = (fast & !apart) | sure_touch;
        slow |= !(fast | sure_touch);
    }
    slow
}

/// `2 √lo` (`lo` the bottom of the fast range, [`safe_squared_range`]; `2^−39`
/// in `f32`, `2^−458` in `f64`): a pair whose computed `‖Δ‖²` is below `lo`
/// and whose radii sum to at least this touches, for certain.
///
/// The computed `‖Δ‖²` is within a few roundings (of the differences, the
/// squares and the sums) of the exact one, plus 3 halves of the smallest
/// subnormal (squares that underflow), so the exact squared distance is below
/// `2 lo`, while the exact reach (one rounding from the computed one) has a
/// square above `2 lo`: the distance is below the reach.
/// [`contact_sphere_sphere`] then finds the contact on its scaled path (its distance accurate to a few ulps), or,
/// for exactly concentric centres, answers its flagged fallback contact:
/// either way `is_some()`. A negative, NaN or smaller reach is left to the
/// one-pair function (unless the centres are exactly concentric).
#[inline(always)]
fn near_concentric_reach<T: Real>() -> T {
    let (lo, _) = safe_squared_range::<T>();
    T::of(2.0) * lo.sqrt()
}

/// Whether spheres `a[i]` and `b[i]` touch or overlap, for every `i` below
/// the shorter length `n`, written to `out` (resized to `n`): exactly
/// [`contact_sphere_sphere`]`(a[i], b[i]).is_some()`, decided the same way
/// (see [`contact_spheres_spheres`]) without computing the contact. Lanes
/// outside the fast range are answered by [`contact_sphere_sphere`], block by
/// block (see `BLOCK`, 64 lanes), except exactly concentric pairs (which
/// touch whatever the radii) and nearly concentric pairs (`‖Δ‖²` below the
/// range) whose radii sum to at least `2 √lo`: they certainly touch, and the
/// first pass says so. In `f32` those are common — centres a
/// hair apart in `f64` round to the same `f32` point, or their difference's
/// squares underflow — and would otherwise send nearly every block to the
/// one-pair function.
pub fn test_spheres_spheres<T: Real>(a: &Spheres<T>, b: &Spheres<T>, out: &mut Vec<bool>) {
    let n = a.len().min(b.len());
    out.resize(n, false);
    let [ax, ay, az, ar] = a.lanes(n);
    let [bx, by, bz, br] = b.lanes(n);
    let hit = &mut out[..n];
    for r in blocks(n) {
        let slow = test_lanes(
            &ax[r.clone()],
            &ay[r.clone()],
            &az[r.clone()],
            &ar[r.clone()],
            &bx[r.clone()],
            &by[r.clone()],
            &bz[r.clone()],
            &br[r.clone()],
            &mut hit[r.clone()],
        );
        if slow {
            for (i, x, y) in left_open([ax, ay, az, ar], [bx, by, bz, br], r, Some(near_concentric_reach())) {
                hit[i] = contact_sphere_sphere(&x, &y).is_some();
            }
        }
    }
}

/// Whether the centres' difference is exactly zero: the lanes every first
/// pass answers with the one-pair function's concentric answer (branch-free,
/// for the lane loops).
#[inline(always)]
fn concentric<T: Real>(dx: T, dy: T, dz: T) -> bool {
    (dx == T::zero()) & (dy == T::zero()) & (dz == T::zero())
}

/// The lanes `0..n` in blocks of [`BLOCK`].
fn blocks(n: usize) -> impl Iterator<Item = Range<usize>> {
    (0..n).step_by(BLOCK).map(move |start| start..(start + BLOCK).min(n))
}

/// The lanes of `r` a first pass left to the one-pair function, with their
/// two spheres (`a` and `b` are the `x`, `y`, `z` and radius arrays): those
/// whose squared distance lies outside the fast range, except exactly
/// concentric centres and, below the range, pairs whose reach is at least
/// `sure_reach` — the lanes the first passes answer themselves
/// ([`near_concentric_reach`] for the overlap test; `None` for the contact
/// batch, which answers only the concentric ones). The same arithmetic as
/// the first passes, so the same lanes.
fn left_open<'s, T: Real>(
    a: [&'s [T]; 4],
    b: [&'s [T]; 4],
    r: Range<usize>,
    sure_reach: Option<T>,
) -> impl Iterator<Item = (usize, Sphere<T>, Sphere<T>)> + 's {
    let (lo, hi) = safe_squared_range::<T>();
    r.filter_map(move |i| {
        let (dx, dy, dz) = (a[0][i] - b[0][i], a[1][i] - b[1][i], a[2][i] - b[2][i]);
        let dd = T::zero() + ((dx * dx + dy * dy) + dz * dz);
        let concentric = concentric(dx, dy, dz);
        let sure = dd < lo && sure_reach.is_some_and(|s| a[3][i] + b[3][i] >= s);
        let one = |s: [&[T]; 4]| Sphere::new(Vec3::new(s[0][i], s[1][i], s[2][i]), s[3][i]);
        let answered = (dd >= lo && dd <= hi) || concentric || sure;
        (!answered).then(|| (i, one(a), one(b)))
    })
}

/// Lanes per block of [`contact_spheres_spheres`] and
/// [`test_spheres_spheres`]: each block is one vectorized
/// pass, and only a block holding a lane outside the fast range is gone over
/// again one lane at a time — so a rare such lane costs a second look at 64
/// lanes, not at the whole batch.
const BLOCK: usize = 64;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::c;
    use proptest::prelude::*;

    fn same<T: Real>(x: Option<Contact<T>>, y: Option<Contact<T>>) -> bool {
        // Bit for bit (NaN cannot occur for finite input).
        match (x, y) {
            (None, None) => true,
            (Some(x), Some(y)) => {
                x.degenerate == y.degenerate
                    && x.depth.wide().to_bits() == y.depth.wide().to_bits()
                    && (0..3).all(|k| {
                        x.point[k].wide().to_bits() == y.point[k].wide().to_bits()
                            && x.normal[k].wide().to_bits() == y.normal[k].wide().to_bits()
                    })
            }
            _ => false,
        }
    }

    fn check<T: Real>(pairs: &[(Sphere<T>, Sphere<T>)]) -> Result<(), TestCaseError> {
        let a: Spheres<T> = pairs.iter().map(|p| &p.0).collect();
        let b: Spheres<T> = pairs.iter().map(|p| &p.1).collect();
        let mut out = SphereContacts::new();
        contact_spheres_spheres(&a, &b, &mut out);
        let mut tests = Vec::new();
        test_spheres_spheres(&a, &b, &mut tests);
        prop_assert_eq!(out.len(), pairs.len());
        for (i, (x, y)) in pairs.iter().enumerate() {
            let one = contact_sphere_sphere(x, y);
            prop_assert!(same(out.get(i), one), "pair {i}: batch {:?}, one {:?}", out.get(i), one);
            prop_assert_eq!(tests[i], one.is_some(), "test of pair {}", i);
            if one.is_none() {
                prop_assert!(out.depth()[i].wide().to_bits() == 0 && out.normal_x()[i].wide().to_bits() == 0, "zeroed");
            }
        }
        Ok(())
    }

    /// Spheres near each other (about half touch), some far apart, some
    /// concentric, some at extreme scales: the batch must match the one-pair
    /// function on every lane, fast or not.
    fn pair() -> impl Strategy<Value = ([f64; 4], [f64; 4])> {
        let coord = prop_oneof![
            4 => -4.0..4.0f64,
            1 => (-1.0..1.0f64, -300i32..300).prop_map(|(m, e)| m * 2f64.powi(e)),
            1 => Just(1.0),
        ];
        let radius =
            prop_oneof![4 => 0.1..3.0f64, 1 => (0.1..1.0f64, -300i32..300).prop_map(|(m, e)| m * 2f64.powi(e))];
        let sphere = ([coord.clone(), coord.clone(), coord], radius).prop_map(|(c, r)| [c[0], c[1], c[2], r]);
        (sphere.clone(), sphere)
    }

    fn spheres<T: Real>(p: &[([f64; 4], [f64; 4])]) -> Vec<(Sphere<T>, Sphere<T>)> {
        let s = |v: [f64; 4]| Sphere::new(Vec3::new(c(v[0]), c(v[1]), c(v[2])), c(v[3]));
        p.iter().map(|(x, y)| (s(*x), s(*y))).collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn batch_matches_one_pair_at_a_time_f64(p in proptest::collection::vec(pair(), 0..40)) {
            check::<f64>(&spheres(&p))?;
        }

        #[test]
        fn batch_matches_one_pair_at_a_time_f32(p in proptest::collection::vec(pair(), 0..40)) {
            check::<f32>(&spheres(&p))?;
        }
    }

    /// Pairs whose distance is within a few dozen ulps of the sum of the
    /// radii, in a random direction: where the root's rounding decides, and
    /// the batch must decide as the one-pair function does.
    fn near_touching() -> impl Strategy<Value = ([f64; 4], [f64; 4])> {
        let dir = prop::array::uniform3(-1.0..1.0f64).prop_filter("direction", |d| d.iter().any(|x| x.abs() > 0.1));
        (dir, 0.01..10.0f64, 0.01..10.0f64, -40i32..40).prop_map(|(d, ra, rb, k)| {
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let dist = (ra + rb) * (1.0 + f64::from(k) * f64::EPSILON);
            let at = d.map(|x| x / len * dist);
            ([at[0], at[1], at[2], ra], [0.0, 0.0, 0.0, rb])
        })
    }

    /// Nearly concentric pairs: the second centre a tiny offset from the
    /// first (at the origin, so that offsets whose squares underflow survive;
    /// elsewhere, where `f32` often rounds them away), with radii around the
    /// batch's sure-touch threshold (`2^−39` in `f32`, `2^−458` in `f64`),
    /// zero and ordinary. The batch's first pass answers many of these
    /// itself; it must agree with the one-pair function on every lane.
    fn near_concentric() -> impl Strategy<Value = ([f64; 4], [f64; 4])> {
        let centre = prop_oneof![1 => prop::array::uniform3(-4.0..4.0f64), 1 => Just([0.0; 3])];
        let offset = prop::array::uniform3((-1.0..1.0f64, -620i32..-20).prop_map(|(m, e)| m * 2f64.powi(e)));
        let radius = prop_oneof![
            1 => 0.1..3.0f64,
            1 => (0.5..2.0f64, -45i32..-35).prop_map(|(m, e)| m * 2f64.powi(e)),
            1 => (0.5..2.0f64, -465i32..-450).prop_map(|(m, e)| m * 2f64.powi(e)),
            1 => Just(0.0),
        ];
        (centre, offset, radius.clone(), radius)
            .prop_map(|(c, o, ra, rb)| ([c[0] + o[0], c[1] + o[1], c[2] + o[2], ra], [c[0], c[1], c[2], rb]))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        #[test]
        fn batch_matches_one_pair_at_a_time_near_touching(p in proptest::collection::vec(near_touching(), 0..70)) {
            check::<f64>(&spheres(&p))?;
            check::<f32>(&spheres(&p))?;
        }

        #[test]
        fn batch_matches_one_pair_at_a_time_near_concentric(p in proptest::collection::vec(near_concentric(), 0..70)) {
            check::<f64>(&spheres(&p))?;
            check::<f32>(&spheres(&p))?;
        }
    }

    /// Centres `2^−70` apart in `f32`: the squares underflow to 0, below the
    /// fast range. With no radius they do not touch (the distance is not
    /// 0), with radii summing to the sure-touch threshold `2^−39` they do,
    /// and exactly concentric ones touch whatever the radii (the flagged
    /// fallback). Centres `2^−41` apart (`‖Δ‖² = 2^−82`, also below the
    /// range) with radii summing to `2^−45` do not touch: below the
    /// threshold, the one-pair function decides. The first pass answers the
    /// second and third; the first and fourth are left to the one-pair
    /// function.
    #[test]
    fn nearly_concentric_pairs_below_the_fast_range() {
        let tiny = 2f32.powi(-70);
        let s = |x: f32, r: f32| Sphere::new(Vec3::new(x, 0.0, 0.0), r);
        let pairs = [
            (s(tiny, 0.0), s(0.0, 0.0)),
            (s(tiny, 2f32.powi(-40)), s(0.0, 2f32.powi(-40))),
            (s(0.0, 0.0), s(0.0, 0.0)),
            (s(2f32.powi(-41), 2f32.powi(-46)), s(0.0, 2f32.powi(-46))),
        ];
        check(&pairs).expect("batch agrees");
        let a: Spheres<f32> = pairs.iter().map(|p| &p.0).collect();
        let b: Spheres<f32> = pairs.iter().map(|p| &p.1).collect();
        let mut tests = Vec::new();
        test_spheres_spheres(&a, &b, &mut tests);
        assert_eq!(tests, vec![false, true, true, false]);
    }

    #[test]
    fn touching_concentric_and_far_pairs() {
        let s = |x: f64, r: f64| Sphere::new(Vec3::new(x, 0.0, 0.0), r);
        let pairs = [
            (s(2.0, 1.0), s(0.0, 1.0)),              // touching: contact, depth 0
            (s(1.0, 1.0), s(1.0, 2.0)),              // concentric: fallback, flagged
            (s(1.5e308, 1.0), s(-1.5e308, 1.0)),     // Δ overflows: apart
            (s(2.0f64.next_up(), 1.0), s(0.0, 1.0)), // a hair apart
        ];
        check(&pairs).expect("batch agrees");
        let a: Spheres<f64> = pairs.iter().map(|p| &p.0).collect();
        let b: Spheres<f64> = pairs.iter().map(|p| &p.1).collect();
        let mut out = SphereContacts::new();
        contact_spheres_spheres(&a, &b, &mut out);
        assert_eq!(out.hit(), &[true, true, false, false]);
        assert!(out.degenerate()[1] && !out.degenerate()[0]);
    }
}
