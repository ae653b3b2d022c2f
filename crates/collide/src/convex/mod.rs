//! Signed distance between convex solids: the convex hull of a finite point
//! set grown by a radius (a sphere is one point and its radius, a capsule its
//! axis's two ends, a box its eight corners, a triangle its three vertices).
//!
//! For solids `a` and `b` with cores (hulls without radius) at signed
//! distance `s` (the separation when apart, minus the penetration depth when
//! they overlap), the solids' signed distance is `s − r_a − r_b`, with the
//! same normal; `point_a` is `a`'s core witness minus `r_a·normal`,
//! `point_b` is `b`'s plus `r_b·normal`, and always
//! `point_a = point_b + distance·normal`. The normal is unit length, from
//! `b` toward `a` (for an overlap: the direction in which `a` is pushed out
//! by the shortest translation).
//!
//! **The lecture's form** ([`distance_lecture`]) is GJK (Gilbert, Johnson
//! and Keerthi 1988; van den Bergen's termination tests, [`GJK_REL_TOL`],
//! [`GJK_ABS_TOL`], [`GJK_MAX_ITER`]) with the case-by-case closest point on
//! the simplex, and EPA ([`EPA_REL_TOL`], [`EPA_MAX_ITER`]) when the cores
//! overlap, in the input's type. It fails where the textbook does: a
//! touching pair within GJK's absolute tolerance goes to EPA, a flat
//! Minkowski difference gives EPA no tetrahedron (then the fallback below),
//! and `f32` answers carry `f32`'s rounding.
//!
//! **The robust form** ([`distance`]) computes in `f64` on the exactly
//! widened inputs, scaled by a power of two outside the plain range, and
//! rounds once at the end; every decision that shapes the answer is an exact
//! predicate on the inputs as given (`robust`, `predicates`: floating-point
//! filters first, a double-double stage, then exact arithmetic), so it holds
//! at every scale, far below the rounding of the scene's coordinates:
//! 1. GJK to termination (no support point improves `v`), then a
//!    *certificate*: with the exact normal `N` of the final simplex (a
//!    polynomial in the input coordinates), every core point of `a` has
//!    `N·x ≥ N·a₀` and every point of `b` has `N·y ≤ N·b₀`, and the two
//!    supporting sets (the points exactly on those levels), seen along `N`,
//!    meet. A point beyond the slab joins the simplex and GJK resumes; where
//!    floating point cannot find the nearest feature (a distance below the
//!    rounding of the coordinates), GJK runs again with each step decided
//!    exactly. The certified distance is `N̂·(a₀ − b₀)`, exactly 0 for a
//!    touching pair.
//! 2. When the cores meet, the penetration depth by separating axes: the
//!    least push `max_b L·y − min_a L·x` (or the reverse) over the hulls'
//!    face normals and the cross products of their edge directions (each a
//!    polynomial in the inputs; the hulls' faces, merged where coplanar, and
//!    edges found with exact orientation predicates), the pushes that may be
//!    the least kept by a bounded floating-point pass and then ordered
//!    exactly, so that two least pushes in different directions are found
//!    as such.
//!
//! Along the answer's normal the witnesses are where the two supporting sets
//! (a point, a segment or a polygon each), seen along it, overlap: unique,
//! and not `degenerate`, exactly when that overlap is one point; a touching
//! pair's normal is unique only when that point lies strictly inside a
//! face or is two edges crossing strictly inside both, and the cores do not
//! lie in one plane. Cores that meet with no direction at all (points and
//! segments on one line) take the format's fallback normal: `+z` for
//! points, else the unit vector of `u × z` (`u × x` for a line along `z`).
//!
//! A box given to [`distance_solids`] as a box ([`Solid::Box`]) is decided
//! about exactly as the format defines it: `center + R(q)·u`, `|u_i| ≤ h_i`,
//! with `R(q)` the rotation of `q/‖q‖`, rational in `q` (a zero quaternion is
//! the identity). Its corners are `(‖q‖² c + Σ_i s_i h_i M_i)/‖q‖²` with
//! `M_i = ‖q‖² R(q) e_i` quadratic in `q` (`crate::boxes::poly`): the
//! predicates' floating-point filters run on the corners rounded to `f64`
//! with a bound on that rounding as their inputs' error, and the exact stage
//! on the exact corners, every point of a predicate multiplied by the
//! product of the boxes' `‖q‖²` (the predicates are homogeneous: their
//! signs are unchanged). A box turned by a signed permutation (the
//! identity, half and quarter turns of small quaternions) has corners `f64`
//! holds exactly, and costs nothing more. So a face of the 3-4-5 box
//! (`q = (2, 0, 0, 1)`, whose `3/5` is not a binary number) exactly parallel
//! to another solid's, or a point exactly on it, is found so. A box given as
//! points ([`box_corners`], rounded to the type; and the lecture's form
//! always) is decided about as those points.
//!
//! **Degenerate input** (an empty point set, a non-finite coordinate) is
//! answered by the fallback: distance 0, both points at the origin, normal
//! `+z`, `degenerate` set; a negative or NaN radius is taken as 0 and
//! flagged. No answer is NaN.

mod epa;
mod gjk;
mod hull;
mod points;
mod predicates;
mod robust;
#[cfg(test)]
mod tests;

pub use epa::{EPA_MAX_ITER, EPA_REL_TOL};
use points::{Corner, ExactBox, Xp};

use crate::exact::{P3, Sign, dot_diff};
use crate::real::{Real, Vec3, finite3, scale2, scale2v, to_f64_3, unit_scale};
use crate::shapes::{OrientedBox, Plane};

/// GJK (lecture) stops when `‖v‖² − v·w ≤ GJK_REL_TOL² ‖v‖²`: the support
/// point improves the distance by less than this fraction (van den Bergen's
/// relative tolerance, *Collision Detection in Interactive 3D Environments*,
/// §4.3.4).
pub const GJK_REL_TOL: f64 = 1e-6;

/// GJK (lecture) counts the origin as inside when
/// `‖v‖² ≤ GJK_ABS_TOL · max ‖w‖²` over the simplex: `v` has vanished within
/// the rounding of the simplex's points (van den Bergen's `100 ε` test,
/// taken with the `f64` epsilon as in his SOLID library).
pub const GJK_ABS_TOL: f64 = 100.0 * f64::EPSILON;

/// GJK's (lecture) iteration cap: each iteration adds a support point, and
/// a run on shapes of a few dozen points converges in far fewer.
pub const GJK_MAX_ITER: usize = 64;

/// The lecture's degenerate flag counts a point within this fraction of the
/// scene's size of a supporting plane as on it (parallel faces or edges).
pub const LECTURE_SUPPORT_TOL: f64 = 1e-6;

/// A convex solid as GJK sees it: the hull of `points` grown by `radius`.
#[derive(Clone, Copy, Debug)]
pub struct Rounded<'a, T: Real> {
    /// The core's points (at least one; any order, duplicates and interior
    /// points allowed).
    pub points: &'a [Vec3<T>],
    /// The radius, ≥ 0.
    pub radius: T,
}

/// The signed distance between two solids and where it is reached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Distance<T: Real> {
    /// The separation (> 0), 0 for touching, or minus the penetration depth.
    pub distance: T,
    /// The witness on `a` (a closest point, or for an overlap a point of
    /// `a`'s boundary).
    pub point_a: Vec3<T>,
    /// The witness on `b`.
    pub point_b: Vec3<T>,
    /// Unit normal from `b` toward `a`: `point_a = point_b + distance·normal`.
    pub normal: Vec3<T>,
    /// The witnesses or the normal are not unique, or the input was
    /// degenerate and the fallback answered.
    pub degenerate: bool,
}

impl<T: Real> Distance<T> {
    /// The fallback answer for degenerate input.
    fn fallback() -> Self {
        Self {
            distance: T::zero(),
            point_a: Vec3::zeros(),
            point_b: Vec3::zeros(),
            normal: Vec3::z(),
            degenerate: true,
        }
    }

    fn finite(&self) -> bool {
        self.distance.finite() && finite3(&self.point_a) && finite3(&self.point_b) && finite3(&self.normal)
    }
}

/// The eight corners of a box, from [`OrientedBox::rotation_matrix`]:
/// corner `i` is `center + Σ_k s_k h_k R e_k` with `s_k = −1` when bit `k` of
/// `i` is clear and `+1` when it is set.
pub fn box_corners<T: Real>(b: &OrientedBox<T>) -> [Vec3<T>; 8] {
    let r = b.rotation_matrix();
    core::array::from_fn(|i| {
        let mut p = b.center;
        for k in 0..3 {
            let s = if i >> k & 1 == 1 { T::one() } else { -T::one() };
            p += r.column(k) * (s * b.half_extents[k]);
        }
        p
    })
}

/// A radius as used: negative or NaN is 0 (flagged).
fn radius<T: Real>(r: T) -> (T, bool) {
    if r >= T::zero() && r.finite() { (r, false) } else { (T::zero(), true) }
}

/// Adds the radii to a core answer `(s, pa, pb, n)`.
fn grown<T: Real>(s: T, pa: Vec3<T>, pb: Vec3<T>, n: Vec3<T>, ra: T, rb: T, degenerate: bool) -> Distance<T> {
    Distance { distance: s - ra - rb, point_a: pa - n * ra, point_b: pb + n * rb, normal: n, degenerate }
}

/// The lecture's degenerate flag: the points of `a` within `tol` of its
/// least `n·x` and those of `b` within `tol` of its greatest `n·y` both
/// span more than a point, and a face meets an edge or a face, or two edges
/// are parallel (within `tol`).
fn lecture_flag<T: Real>(a: &[Vec3<T>], b: &[Vec3<T>], n: &Vec3<T>, tol: T) -> bool {
    let lo = a.iter().fold(T::max_value().unwrap_or(T::zero()), |m, x| m.min(n.dot(x)));
    let hi = b.iter().fold(T::min_value().unwrap_or(T::zero()), |m, x| m.max(n.dot(x)));
    let fa: Vec<Vec3<T>> = a.iter().filter(|x| n.dot(x) <= lo + tol).copied().collect();
    let fb: Vec<Vec3<T>> = b.iter().filter(|x| n.dot(x) >= hi - tol).copied().collect();
    let (da, ea) = float_dim(&fa, tol);
    let (db, eb) = float_dim(&fb, tol);
    let par = da == 1 && db == 1 && ea.cross(&eb).norm() <= tol / (tol + T::one()) * T::of(1e3);
    da >= 1 && db >= 1 && (da + db >= 3 || par)
}

/// Affine dimension (0, 1, or 2 for "more") of `p` within `tol`, and the
/// unit direction of a 1-dimensional set.
fn float_dim<T: Real>(p: &[Vec3<T>], tol: T) -> (usize, Vec3<T>) {
    let Some(p0) = p.first() else { return (0, Vec3::z()) };
    let far = p.iter().fold(*p0, |f, x| if (x - p0).norm() > (f - p0).norm() { *x } else { f });
    let Some(e) = (far - p0).try_normalize(tol) else { return (0, Vec3::z()) };
    if p.iter().all(|x| (x - p0).cross(&e).norm() <= tol) { (1, e) } else { (2, e) }
}

/// Signed distance between the solids `a` and `b`, **the lecture's form**:
/// GJK with van den Bergen's tolerances ([`GJK_REL_TOL`], [`GJK_ABS_TOL`],
/// [`GJK_MAX_ITER`]) and the case-by-case closest point on the simplex; the
/// witnesses from the final simplex's barycentric coordinates. When the
/// origin is found in the simplex, EPA from it (blown up to a tetrahedron;
/// [`EPA_REL_TOL`], [`EPA_MAX_ITER`]). Computed in `T`.
///
/// `degenerate` is set when the points within [`LECTURE_SUPPORT_TOL`] of the
/// two supporting planes show parallel features, and when EPA cannot form a
/// polytope (a flat Minkowski difference): then the answer is the core
/// distance 0, GJK's witnesses and the normal `+z`. An answer that is not
/// finite (a scene beyond the type's plain range) is the fallback.
pub fn distance_lecture<T: Real>(a: &Rounded<T>, b: &Rounded<T>) -> Distance<T> {
    if a.points.is_empty() || b.points.is_empty() {
        return Distance::fallback();
    }
    let (ra, bad_a) = radius(a.radius);
    let (rb, bad_b) = radius(b.radius);
    let (pa, pb) = (a.points, b.points);
    let diff = |i: usize, j: usize| pa[i] - pb[j];
    let params = gjk::Params { rel: T::of(GJK_REL_TOL), abs: T::of(GJK_ABS_TOL), max_iter: GJK_MAX_ITER };
    let g = gjk::gjk(pa, pb, &diff, &params);
    let size = pa.iter().chain(pb).fold(T::zero(), |m, x| m.max((x - pa[0]).norm()));
    let tol = T::of(LECTURE_SUPPORT_TOL) * size;
    let out = if !g.contains {
        let (wa, wb) = g.witnesses(pa, pb);
        let d = g.v.norm();
        let n = g.v / d;
        grown(d, wa, wb, n, ra, rb, lecture_flag(pa, pb, &n, tol))
    } else if let Some(e) = epa::epa(pa, pb, g.simplex.clone()) {
        let n = -e.n;
        grown(-e.depth, e.pa, e.pb, n, ra, rb, lecture_flag(pa, pb, &n, tol))
    } else {
        let (wa, wb) = g.witnesses(pa, pb);
        grown(T::zero(), wa, wb, Vec3::z(), ra, rb, true)
    };
    let out = Distance { degenerate: out.degenerate || bad_a || bad_b, ..out };
    if out.finite() { out } else { Distance::fallback() }
}

/// Clamps to the finite range (NaN to 0).
fn saturate<T: Real>(x: T) -> T {
    let big = T::max_value().unwrap_or_else(|| T::of(f64::MAX));
    if x.is_nan() { T::zero() } else { x.max(-big).min(big) }
}

/// An `f64` answer on a scene scaled by `2^k`, scaled back and rounded to
/// `T` once; a value beyond the type's range is saturated and flagged.
fn finish<T: Real>(d: f64, pa: Vec3<f64>, pb: Vec3<f64>, n: Vec3<f64>, k: i32, degenerate: bool) -> Distance<T> {
    let back = |p: &Vec3<f64>| scale2v(p, -k).map(T::of);
    let out = Distance {
        // `+ 0.0` turns a −0 into 0.
        distance: T::of(scale2(d, -k)) + T::zero(),
        point_a: back(&pa),
        point_b: back(&pb),
        normal: n.map(T::of),
        degenerate,
    };
    if out.finite() {
        return out;
    }
    Distance {
        distance: saturate(out.distance),
        point_a: out.point_a.map(saturate),
        point_b: out.point_b.map(saturate),
        normal: if finite3(&out.normal) { out.normal } else { Vec3::z() },
        degenerate: true,
    }
}

/// A solid for the robust distance ([`distance_solids`]): a hull of points
/// grown by a radius, or a box exactly as the format defines it (its
/// quaternion's own rotation, never the rounded matrix).
#[derive(Clone, Copy, Debug)]
pub enum Solid<'a, T: Real> {
    /// The hull of the points grown by the radius.
    Hull(Rounded<'a, T>),
    /// The box `center + R(q)·u`, `|u_i| ≤ h_i` (radius 0; a zero quaternion
    /// is the identity).
    Box(&'a OrientedBox<T>),
}

/// A solid's exact box, when it is one (`Err` for a number that is not
/// finite).
fn exact_box<T: Real>(s: &Solid<T>) -> Result<Option<ExactBox>, ()> {
    match s {
        Solid::Hull(_) => Ok(None),
        Solid::Box(b) => ExactBox::new(to_f64_3(&b.center), to_f64_3(&b.half_extents), b.rotation.map(|q| q.wide()))
            .map(Some)
            .ok_or(()),
    }
}

/// A box's corners' data (`Ok(None)` for a hull; `Err` when a corner's value
/// is not finite): each [`Corner`] and its `f64` value and bound.
type CornerData<'a> = ([Corner<'a>; 8], [(P3, f64); 8]);

fn corner_data(b: Option<&ExactBox>) -> Result<Option<CornerData<'_>>, ()> {
    let Some(b) = b else { return Ok(None) };
    let c = b.corners().ok_or(())?;
    let corners = std::array::from_fn(|i| Corner { b, bits: i as u8, lo: c[i].lo, ed: c[i].ed });
    Ok(Some((corners, c.map(|x| (x.v, x.e)))))
}

/// A solid's points (a box's corners with their bounds, see
/// `points::ExactBox::corners`) and radius (negative or NaN: 0, flagged).
fn solid_points<'a, T: Real>(s: &Solid<T>, c: Option<&'a CornerData<'a>>) -> (Vec<Xp<'a>>, T, bool) {
    match (s, c) {
        (Solid::Box(_), Some((corners, values))) => {
            let pts = corners.iter().zip(values).map(|(x, (v, e))| Xp { v: *v, e: *e, x: Some(x) });
            (pts.collect(), T::zero(), false)
        }
        (Solid::Hull(r), _) => {
            let (rad, bad) = radius(r.radius);
            (r.points.iter().map(|p| Xp::plain(to_f64_3(p))).collect(), rad, bad)
        }
        // Not reached: a box's corner data is always given.
        (Solid::Box(_), None) => (Vec::new(), T::zero(), true),
    }
}

/// Signed distance between the solids `a` and `b`, **robust form** (see the
/// module's documentation): the distance to a few ulps of the scene's own
/// scale, the normal's direction accurate, the witnesses on the witness
/// sets within rounding, for every finite input (flat, needle and
/// single-point hulls, duplicated and nearly coplanar points, kissing and
/// deeply penetrating pairs, scenes far from the origin, the whole `f64`
/// range). An exact touching pair answers exactly 0.
///
/// `degenerate` exactly when the witnesses are not unique (the exact
/// supporting sets overlap in more than a point, seen along the normal),
/// when the normal is not unique (two least pushes in different directions,
/// or a touching pair whose contact spans less than a facet of the
/// Minkowski difference), and for the fallback on degenerate input.
pub fn distance<T: Real>(a: &Rounded<T>, b: &Rounded<T>) -> Distance<T> {
    distance_solids(&Solid::Hull(*a), &Solid::Hull(*b))
}

/// [`distance`] between solids that may be boxes, each box decided about
/// exactly as the format defines it: its corners `c + R(q)·Σ s_i h_i e_i`
/// with `R(q)` the rotation of `q/‖q‖`, rational in `q` (see the module's
/// documentation). A box whose faces are exactly parallel to another
/// solid's face, or whose exact corner lies exactly on one, is found so
/// (the 3-4-5 box's `3/5` is not a binary number: its `f64` corners
/// would not show it). Values as [`distance`]'s, from the corners rounded
/// to `f64`.
pub fn distance_solids<T: Real>(a: &Solid<T>, b: &Solid<T>) -> Distance<T> {
    let (Ok(ba), Ok(bb)) = (exact_box(a), exact_box(b)) else { return Distance::fallback() };
    let (Ok(ca), Ok(cb)) = (corner_data(ba.as_ref()), corner_data(bb.as_ref())) else {
        return Distance::fallback();
    };
    let ((xa, ra, bad_a), (xb, rb, bad_b)) = (solid_points(a, ca.as_ref()), solid_points(b, cb.as_ref()));
    if xa.is_empty() || xb.is_empty() {
        return Distance::fallback();
    }
    let (ra, rb) = (ra.wide(), rb.wide());
    let m = xa.iter().chain(&xb).flat_map(|p| p.v).chain([ra, rb]).fold(0.0f64, |m, x| m.max(x.abs()));
    if !m.is_finite() {
        return Distance::fallback();
    }
    // Scaled by `2^k` (`k` from the largest magnitude, 0 in the plain range).
    let k = unit_scale::<f64>(m).unwrap_or(0);
    let scaled = |x: &[Xp]| -> Vec<P3> { x.iter().map(|p| p.v.map(|c| scale2(c, k))).collect() };
    let (wa, wb) = (scaled(&xa), scaled(&xb));
    let e = xa.iter().chain(&xb).fold(0.0f64, |m, p| m.max(p.e));
    // A scaled bound that falls into the subnormals gains `2^−1074`.
    let err = if e > 0.0 { scale2(e, k) + f64::from_bits(1) } else { 0.0 };
    let (ra, rb) = (scale2(ra, k), scale2(rb, k));
    let c = robust::core(&robust::Sets { a: &xa, b: &xb, sa: &wa, sb: &wb, err });
    let n = c.n;
    finish(c.d - ra - rb, c.pa - n * ra, c.pb + n * rb, n, k, c.degenerate || bad_a || bad_b)
}

/// Signed distance between the solid `a` and the solid half-space
/// `n·x ≤ offset` of the plane `b`, **the lecture's form**: `n̂ = n/‖n‖`
/// with the plain norm, `s = n̂·x − offset/‖n‖` for each core point, the
/// least `s` minus the radius; `point_a` the lowest point minus `r n̂`,
/// `point_b` its projection onto the plane, normal `n̂`. `degenerate` when
/// another point's `s` is within [`LECTURE_SUPPORT_TOL`] of the scene's size
/// of the least. A zero or non-finite normal (or a norm that under- or
/// overflows), and an answer that is not finite, give the fallback.
pub fn distance_plane_lecture<T: Real>(a: &Rounded<T>, b: &Plane<T>) -> Distance<T> {
    let len = b.normal.norm();
    if a.points.is_empty() || !(len > T::zero()) || !len.finite() {
        return Distance::fallback();
    }
    let (r, bad) = radius(a.radius);
    let n = b.normal / len;
    let off = b.offset / len;
    let s: Vec<T> = a.points.iter().map(|x| n.dot(x) - off).collect();
    let (lo, &smin) = s.iter().enumerate().fold((0, &s[0]), |m, x| if x.1 < m.1 { x } else { m });
    let size = a.points.iter().fold(T::zero(), |m, x| m.max((x - a.points[0]).norm()));
    let tol = T::of(LECTURE_SUPPORT_TOL) * size;
    let ties = s.iter().filter(|&&x| x <= smin + tol).count() > 1;
    let x = a.points[lo];
    let out =
        Distance { distance: smin - r, point_a: x - n * r, point_b: x - n * smin, normal: n, degenerate: ties || bad };
    if out.finite() { out } else { Distance::fallback() }
}

/// Signed distance between the solid `a` and the solid half-space
/// `n·x ≤ offset` of the plane `b`, **robust form**: the lowest core point
/// chosen by exact comparisons of `n·x` (so a tie is exact: a face or edge
/// parallel to the plane, flagged `degenerate`, the first lowest point
/// answering), its signed distance `(n·x − offset)/‖n‖` formed with exact
/// arithmetic to a few ulps and divided by a norm that neither over- nor
/// underflows, minus the radius; points and normal as the lecture's.
/// Computed in `f64` and rounded once. A zero or non-finite normal or
/// input gives the fallback.
pub fn distance_plane<T: Real>(a: &Rounded<T>, b: &Plane<T>) -> Distance<T> {
    if a.points.is_empty() {
        return Distance::fallback();
    }
    let (r, bad) = radius(a.radius);
    let nw = to_f64_3(&b.normal);
    let Some((m, l, nhat)) = crate::contact::normal_parts(&Vec3::new(nw[0], nw[1], nw[2])) else {
        return Distance::fallback();
    };
    let pts: Vec<P3> = a.points.iter().map(to_f64_3).collect();
    let off = b.offset.wide();
    if !off.is_finite() || !pts.iter().flatten().all(|x| x.is_finite()) {
        return Distance::fallback();
    }
    let mut lo = 0;
    let mut ties = false;
    for i in 1..pts.len() {
        match dot_diff(nw, pts[lo], pts[i]) {
            Sign::Negative => {
                lo = i;
                ties = false;
            }
            Sign::Zero => ties |= !crate::exact::points_equal(pts[lo], pts[i]),
            Sign::Positive => {}
        }
    }
    let x = pts[lo];
    let est = crate::exact::plane_side_estimate(nw, off, x, f64::EPSILON);
    let s = crate::boxes::poly::over_norm(est, m, l, 0);
    let rw = r.wide();
    // Scale the point with the normal's components (exact for a power of
    // two) only when the plain products could leave the range.
    let xv = Vec3::new(x[0], x[1], x[2]);
    let big = xv.amax().max(s.abs()).max(rw);
    let k = unit_scale::<f64>(big).unwrap_or(0);
    let xs = scale2v(&xv, k);
    let (ss, rs) = (scale2(s, k), scale2(rw, k));
    finish(ss - rs, xs - nhat * rs, xs - nhat * ss, nhat, k, ties || bad)
}
