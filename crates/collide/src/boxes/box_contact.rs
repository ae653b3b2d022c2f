//! Box–box and box–triangle contact (the least push over the separating
//! axes), and the pieces the capsule–polytope contacts share with them: the
//! exact choice of the least push (`least_push`), the polynomials it is made
//! of (`sat_polys!`), and the touching set's point (`touching_point`).
//!
//! **The robust forms' axes.** Every candidate axis `L` of a problem is one
//! polynomial of its inputs picked by a *candidate*: ten units
//! `[s (3), t (3), f (3), dir]`, one-hot selectors `s`, `t` of the features'
//! directions, type flags `f` (which of the problem's kinds of axis: a face
//! normal, a cross product, …) and the way `dir = ±1`. Exactly one type flag
//! is set, so the selected polynomial is homogeneous in the lengths even
//! where different kinds of axis have different degrees (a box axis, degree 0;
//! a triangle's edge, degree 1; its normal, degree 2), which is what
//! `crate::boxes::poly`'s filter needs. A problem supplies `frame(l, g, c)`:
//! the axis `L` and its push `o`, the push along `dir·L` times a positive
//! factor common to all candidates (`‖q_a‖²‖q_b‖²` for two boxes, …), so that
//! the push is `o / (factor · ‖L‖)`. Then, all exactly:
//!
//! - an axis is no axis when `‖L‖² = 0`;
//! - contact when no push is negative (the sign of `o`);
//! - push 1 is less than push 2 when `o_1² ‖L_2‖² < o_2² ‖L_1‖²` (both pushes
//!   are non-negative then);
//! - two least pushes are along the same direction when `L_1 × L_2 = 0` and
//!   `dir_1 dir_2 L_1 · L_2 > 0`: anything else is a tie (`degenerate`).

use super::poly::{self, Fast, Filt, Ring, cross3, dot3, over_norm2, quaternion_axes, refs, scaled_f64, select, sub3};
use super::{all_finite, fallback_normal, finish, lecture_finite, quaternion_of, scene_scale, stage, up, wide3};
use crate::contact::Contact;
use crate::exact::{BigFloat, Estimate, Sign};
use crate::real::{Real, Vec3};
use crate::shapes::{OrientedBox, Triangle};

use super::OBB_EPSILON;
use super::capsule_capsule::closest_pt_segment_segment_lecture;

/// The touching set's tolerance, relative to the features' size (and the
/// depth): a feature's vertex within this of the other feature counts as
/// touching it. The features' plane comes from the normal, accurate to
/// `2^−40`, so a feature of size `s` is tilted by up to `2^−40 s` against
/// it: `2^−36` (about `1.5e-11`) of `s` is far above that and far below any
/// accuracy a judge asks of a point. (Beside it, [`TOUCH_TOL_ABS`] of the
/// scene's largest coordinate, for the rounding of the features' corners.)
pub const TOUCH_TOL: f64 = 1.0 / (1u64 << 36) as f64;

/// The touching set's tolerance relative to the scene's largest coordinate:
/// the features' corners are formed in `f64` from the centres, the rounded
/// rotation and the depth (a few ulps of that coordinate each); `2^−46`
/// (64 ulps) covers them.
pub const TOUCH_TOL_ABS: f64 = 1.0 / (1u64 << 46) as f64;

/// A candidate axis: `[s (3), t (3), f (3), dir]` (see the module doc).
pub(crate) type Cand = [f64; 10];

/// What the least push over a problem's axes is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Least {
    /// Some push is negative: no contact.
    Apart,
    /// Every axis is zero.
    NoAxis,
    /// The least push, its candidate, and whether another direction ties it.
    Touch { best: Cand, tie: bool },
}

/// Signs of a problem's least-push predicates known before the exact code
/// runs (a floating-point stage's certified ones, `crate::boxes::stage`):
/// `None` leaves the sign to the exact code.
pub(crate) trait Hints {
    /// Whether the candidate's axis is not the zero vector.
    fn nonzero(&self, _: &Cand) -> Option<bool> {
        None
    }
    /// The sign of the candidate's push.
    fn push(&self, _: &Cand) -> Option<Sign> {
        None
    }
    /// The sign of push 1 − push 2 (of non-negative pushes).
    fn cmp(&self, _: &Cand, _: &Cand) -> Option<Sign> {
        None
    }
    /// Whether the two candidates push along one direction.
    fn same(&self, _: &Cand, _: &Cand) -> Option<bool> {
        None
    }
}

/// No hints: the exact code decides everything.
pub(crate) struct NoHints;

impl Hints for NoHints {}

/// The least push over `axes` (each with `dir = +1`; `+L` is tried before
/// `−L`, in the order given), decided exactly by the problem's predicates:
/// `nonzero` (the axis is not the zero vector), `push` (the sign of the
/// push), `cmp` (the sign of push 1 − push 2, for non-negative pushes) and
/// `same` (the two candidates push along one direction).
pub(crate) fn least_push(
    axes: &[Cand],
    nonzero: impl Fn(&Cand) -> bool,
    push: impl Fn(&Cand) -> Sign,
    cmp: impl Fn(&Cand, &Cand) -> Sign,
    same: impl Fn(&Cand, &Cand) -> bool,
) -> Least {
    let mut cands: Vec<Cand> = Vec::with_capacity(2 * axes.len());
    for axis in axes.iter().filter(|a| nonzero(a)) {
        for dir in [1.0, -1.0] {
            let mut c = *axis;
            c[9] = dir;
            if push(&c) == Sign::Negative {
                return Least::Apart;
            }
            cands.push(c);
        }
    }
    if cands.is_empty() {
        return Least::NoAxis;
    }
    let mut b = 0;
    for i in 1..cands.len() {
        if cmp(&cands[i], &cands[b]) == Sign::Negative {
            b = i;
        }
    }
    let best = cands[b];
    let tie = cands.iter().enumerate().any(|(i, c)| i != b && cmp(c, &best) == Sign::Zero && !same(c, &best));
    Least::Touch { best, tie }
}

/// `parts` laid end to end (their lengths must add up to `N`).
pub(crate) fn cat<const N: usize>(parts: &[&[f64]]) -> [f64; N] {
    let mut out = [0.0; N];
    let mut i = 0;
    for p in parts {
        out[i..i + p.len()].copy_from_slice(p);
        i += p.len();
    }
    debug_assert_eq!(i, N, "units laid out wrong");
    out
}

/// References to `x[i..i + 3]`.
#[inline(always)]
pub(crate) fn at3<N>(x: &[N], i: usize) -> [&N; 3] {
    [&x[i], &x[i + 1], &x[i + 2]]
}

/// `x + y + |x − y|`, twice the larger of the two.
#[inline(always)]
pub(crate) fn max2x2<N: Ring>(x: &N, y: &N) -> N {
    x.add(y).add(&x.sub(y).abs())
}

/// Four times the largest of three.
#[inline(always)]
pub(crate) fn max3x4<N: Ring>(x: &N, y: &N, z: &N) -> N {
    let m = max2x2(x, y);
    let zz = z.add(z);
    max2x2(&m, &zz)
}

/// `Σ_i w_i v_i` of three vectors.
pub(crate) fn comb3<N: Ring>(w: &[N], v: [&[N; 3]; 3]) -> [N; 3] {
    std::array::from_fn(|k| w[0].mul(&v[0][k]).add(&w[1].mul(&v[1][k])).add(&w[2].mul(&v[2][k])))
}

/// `x · s` of a vector by a scalar.
#[inline(always)]
pub(crate) fn scale3<N: Ring>(x: &[N; 3], s: &N) -> [N; 3] {
    [x[0].mul(s), x[1].mul(s), x[2].mul(s)]
}

/// `x + y`.
#[inline(always)]
pub(crate) fn add3<N: Ring>(x: &[N; 3], y: &[N; 3]) -> [N; 3] {
    [x[0].add(&y[0]), x[1].add(&y[1]), x[2].add(&y[2])]
}

/// The separating-axis polynomials and their exact decisions for one problem,
/// given `frame(l, g, c) -> (L, o)` over lengths `[_; $k]` and global units
/// `[_; $g]` (see the module doc). Defines, in the module it is expanded in:
/// `least(l, g, axes)`, `normal(l, g, c, deg)` and `depth(l, g, c, deg)`
/// (the push's numerator `o` and `‖L‖²`, to `2^−40`; `deg` the degree of `L`
/// in the lengths).
macro_rules! sat_polys {
    ($frame:ident, $k:literal, $g:literal) => {
        fn push_p<N: Ring>(l: &[N; $k], u: &[N; $g + 10]) -> N {
            $frame(l, &u[..$g], &u[$g..]).1
        }
        fn norm_p<N: Ring>(l: &[N; $k], u: &[N; $g + 10]) -> N {
            let (x, _) = $frame(l, &u[..$g], &u[$g..]);
            dot3(refs(&x), refs(&x))
        }
        fn comp_p<N: Ring>(l: &[N; $k], u: &[N; $g + 13]) -> N {
            let (x, _) = $frame(l, &u[..$g], &u[$g..$g + 10]);
            u[$g + 9].mul(&dot3(refs(&x), $crate::boxes::box_contact::at3(u, $g + 10)))
        }
        fn cmp_p<N: Ring>(l: &[N; $k], u: &[N; $g + 20]) -> N {
            let (x1, o1) = $frame(l, &u[..$g], &u[$g..$g + 10]);
            let (x2, o2) = $frame(l, &u[..$g], &u[$g + 10..]);
            let (n1, n2) = (dot3(refs(&x1), refs(&x1)), dot3(refs(&x2), refs(&x2)));
            o1.mul(&o1).mul(&n2).sub(&o2.mul(&o2).mul(&n1))
        }
        fn cross_p<N: Ring>(l: &[N; $k], u: &[N; $g + 23]) -> N {
            let (x1, _) = $frame(l, &u[..$g], &u[$g..$g + 10]);
            let (x2, _) = $frame(l, &u[..$g], &u[$g + 10..$g + 20]);
            dot3(refs(&cross3(refs(&x1), refs(&x2))), $crate::boxes::box_contact::at3(u, $g + 20))
        }
        fn dot_p<N: Ring>(l: &[N; $k], u: &[N; $g + 20]) -> N {
            let (x1, _) = $frame(l, &u[..$g], &u[$g..$g + 10]);
            let (x2, _) = $frame(l, &u[..$g], &u[$g + 10..]);
            u[$g + 9].mul(&u[$g + 19]).mul(&dot3(refs(&x1), refs(&x2)))
        }

        /// The least push over `axes`, exactly.
        pub(super) fn least(
            l: [f64; $k],
            g: [f64; $g],
            axes: &[$crate::boxes::box_contact::Cand],
        ) -> $crate::boxes::box_contact::Least {
            least_by(l, g, axes, &$crate::boxes::box_contact::NoHints)
        }

        /// The least push over `axes`, exactly, taking the signs `hints`
        /// certifies as given.
        pub(super) fn least_by(
            l: [f64; $k],
            g: [f64; $g],
            axes: &[$crate::boxes::box_contact::Cand],
            hints: &impl $crate::boxes::box_contact::Hints,
        ) -> $crate::boxes::box_contact::Least {
            use $crate::boxes::box_contact::cat;
            use $crate::boxes::poly::sign_fast;
            use $crate::exact::Sign;
            let one = |c: &[f64; 10]| -> [f64; $g + 10] { cat(&[&g, c]) };
            let two = |c: &[f64; 10], d: &[f64; 10]| -> [f64; $g + 20] { cat(&[&g, c, d]) };
            $crate::boxes::box_contact::least_push(
                axes,
                |c| {
                    hints.nonzero(c).unwrap_or_else(|| {
                        sign_fast(l, one(c), norm_p::<Fast>, norm_p::<Filt>, norm_p::<BigFloat>) != Sign::Zero
                    })
                },
                |c| {
                    hints
                        .push(c)
                        .unwrap_or_else(|| sign_fast(l, one(c), push_p::<Fast>, push_p::<Filt>, push_p::<BigFloat>))
                },
                |c, d| {
                    hints
                        .cmp(c, d)
                        .unwrap_or_else(|| sign_fast(l, two(c, d), cmp_p::<Fast>, cmp_p::<Filt>, cmp_p::<BigFloat>))
                },
                |c, d| {
                    if let Some(same) = hints.same(c, d) {
                        return same;
                    }
                    let e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
                    e.iter().all(|e| {
                        let u: [f64; $g + 23] = cat(&[&g, c, d, e]);
                        sign_fast(l, u, cross_p::<Fast>, cross_p::<Filt>, cross_p::<BigFloat>) == Sign::Zero
                    }) && sign_fast(l, two(c, d), dot_p::<Fast>, dot_p::<Filt>, dot_p::<BigFloat>) == Sign::Positive
                },
            )
        }

        /// The unit vector along `dir · L` of candidate `c` (`L` of degree
        /// `deg` in the lengths), to `2^−40`.
        pub(super) fn normal(l: [f64; $k], g: [f64; $g], c: &[f64; 10], deg: i64) -> Option<$crate::real::Vec3<f64>> {
            use $crate::boxes::box_contact::cat;
            let e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            let comps = e.map(|e| {
                let u: [f64; $g + 13] = cat(&[&g, c, &e]);
                $crate::boxes::poly::value_fast(l, u, deg, comp_p::<Fast>, comp_p::<Filt>, comp_p::<BigFloat>)
            });
            $crate::exact::Estimate::unit_vector(comps).map(|d| $crate::real::Vec3::new(d[0], d[1], d[2]))
        }

        /// The push's numerator `o` and `‖L‖²` of candidate `c`, to `2^−40`.
        pub(super) fn depth(
            l: [f64; $k],
            g: [f64; $g],
            c: &[f64; 10],
            deg: i64,
        ) -> ($crate::exact::Estimate, $crate::exact::Estimate) {
            use $crate::boxes::box_contact::cat;
            let u: [f64; $g + 10] = cat(&[&g, c]);
            let o = $crate::boxes::poly::value_fast(l, u, 1 + deg, push_p::<Fast>, push_p::<Filt>, push_p::<BigFloat>);
            let n = $crate::boxes::poly::value_fast(l, u, 2 * deg, norm_p::<Fast>, norm_p::<Filt>, norm_p::<BigFloat>);
            (o, n)
        }
    };
}
pub(crate) use sat_polys;

/// `o / √n` as an estimate (`o > 0`, `n > 0`), formed on the exponents.
pub(crate) fn over_sqrt(o: Estimate, n: Estimate) -> Estimate {
    if o.sign != Sign::Positive || n.sign != Sign::Positive {
        return Estimate::ZERO;
    }
    let (m, e) = if n.exp.rem_euclid(2) == 0 { (n.mant, n.exp) } else { (2.0 * n.mant, n.exp - 1) };
    Estimate { sign: Sign::Positive, mant: o.mant / m.sqrt(), exp: o.exp - e / 2, rel_err: o.rel_err + n.rel_err }
}

/// `x · 2^e`, exactly (on the exponent).
pub(crate) fn times2(x: Estimate, e: i64) -> Estimate {
    Estimate { exp: x.exp + e, ..x }
}

/// An orthonormal pair spanning the plane perpendicular to the unit `n`.
fn plane_basis(n: &Vec3<f64>) -> (Vec3<f64>, Vec3<f64>) {
    let i = (0..3).min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs())).unwrap_or(0);
    let mut e = Vec3::zeros();
    e[i] = 1.0;
    let u = n.cross(&e);
    let u = u / u.norm();
    (u, n.cross(&u))
}

type P2 = [f64; 2];

fn sub2(a: P2, b: P2) -> P2 {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross2(a: P2, b: P2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn len2(a: P2) -> f64 {
    a[0].hypot(a[1])
}

/// The point of segment `[a, b]` nearest `p`.
fn nearest_on_segment2(p: P2, a: P2, b: P2) -> P2 {
    let d = sub2(b, a);
    let dd = d[0] * d[0] + d[1] * d[1];
    if !(dd > 0.0) {
        return a;
    }
    let t = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / dd;
    let t = t.clamp(0.0, 1.0);
    [a[0] + t * d[0], a[1] + t * d[1]]
}

/// The edges of a convex polygon given in order: none for a point, one for a
/// segment, `n` (closed) otherwise.
fn edges(h: &[P2]) -> Vec<(P2, P2)> {
    match h.len() {
        0 | 1 => vec![],
        2 => vec![(h[0], h[1])],
        n => (0..n).map(|i| (h[i], h[(i + 1) % n])).collect(),
    }
}

/// The point of the convex polygon `h` (in order) nearest `p`, and whether
/// `p` is inside it. A polygon thinner than `tol` is taken as its edges.
fn nearest_in_hull(p: P2, h: &[P2], tol: f64) -> P2 {
    if h.len() >= 3 {
        let area: f64 = (0..h.len()).map(|i| cross2(h[i], h[(i + 1) % h.len()])).sum::<f64>() / 2.0;
        let perimeter: f64 = edges(h).iter().map(|(a, b)| len2(sub2(*b, *a))).sum();
        if area.abs() > tol * perimeter {
            let s = area.signum();
            let inside = edges(h).iter().all(|(a, b)| {
                let e = sub2(*b, *a);
                len2(e) == 0.0 || s * cross2(e, sub2(p, *a)) >= 0.0
            });
            if inside {
                return p;
            }
        }
    }
    let mut best = h[0];
    let mut dist = len2(sub2(p, best));
    for (a, b) in edges(h) {
        let q = nearest_on_segment2(p, a, b);
        let d = len2(sub2(p, q));
        if d < dist {
            (best, dist) = (q, d);
        }
    }
    best
}

/// A point of the touching set of two features lying (up to rounding) in one
/// plane perpendicular to the unit `n`: `pa` and `pb` are convex polygons of
/// up to four vertices given in order (a point, a segment, a triangle or a
/// parallelogram). The point is the average of the intersection's corners:
/// the vertices of each inside the other (within `tol`) and the crossings of
/// their edges — all corners of the intersection of two convex polygons, and
/// so a point of it; written in `pb`'s plane. If rounding leaves no corner
/// (the features only touch), the point of `pb` nearest `pa`'s centroid.
/// `extent` is the scene's largest coordinate: the tolerance is
/// [`TOUCH_TOL`] of the features' size plus [`TOUCH_TOL_ABS`] of it.
pub(crate) fn touching_point(pa: &[Vec3<f64>], pb: &[Vec3<f64>], n: &Vec3<f64>, extent: f64) -> Vec3<f64> {
    let (u, w) = plane_basis(n);
    let o = pb[0];
    let size = pa.iter().chain(pb).fold(0.0f64, |m, p| m.max((p - o).amax()));
    let tol = TOUCH_TOL * size + TOUCH_TOL_ABS * extent;
    let flat = |p: &Vec3<f64>| {
        let d = p - o;
        [d.dot(&u), d.dot(&w)]
    };
    let a2: Vec<P2> = pa.iter().map(flat).collect();
    let b2: Vec<P2> = pb.iter().map(flat).collect();
    let mut sum = [0.0, 0.0];
    let mut count = 0.0;
    let mut add = |p: P2| {
        sum = [sum[0] + p[0], sum[1] + p[1]];
        count += 1.0;
    };
    for p in &a2 {
        if len2(sub2(*p, nearest_in_hull(*p, &b2, tol))) <= tol {
            add(*p);
        }
    }
    for q in &b2 {
        if len2(sub2(*q, nearest_in_hull(*q, &a2, tol))) <= tol {
            add(*q);
        }
    }
    for (a0, a1) in edges(&a2) {
        for (b0, b1) in edges(&b2) {
            let (da, db) = (sub2(a1, a0), sub2(b1, b0));
            let (la, lb) = (len2(da), len2(db));
            let den = cross2(da, db);
            if !(la > 0.0 && lb > 0.0) || den.abs() <= 1e-12 * la * lb {
                continue;
            }
            let r = sub2(b0, a0);
            let (s, t) = (cross2(r, db) / den, cross2(r, da) / den);
            let (es, et) = (tol / la, tol / lb);
            if s >= -es && s <= 1.0 + es && t >= -et && t <= 1.0 + et {
                let t = t.clamp(0.0, 1.0);
                add([b0[0] + t * db[0], b0[1] + t * db[1]]);
            }
        }
    }
    let x = if count > 0.0 {
        [sum[0] / count, sum[1] / count]
    } else {
        let c = a2.iter().fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
        let c = [c[0] / a2.len() as f64, c[1] / a2.len() as f64];
        nearest_in_hull(c, &b2, tol)
    };
    o + u * x[0] + w * x[1]
}

/// The face, edge or vertex of a box (centre `c`, rotation `r`, half-extents
/// `h`) with coordinate `s_i h_i` along each axis whose `s_i = ±1`, and free
/// along each axis with `s_i = 0`: its vertices in order (1, 2 or 4).
pub(crate) fn box_feature(c: &Vec3<f64>, r: &nalgebra::Matrix3<f64>, h: &Vec3<f64>, s: [i8; 3]) -> Vec<Vec3<f64>> {
    let mut base = *c;
    let mut free = Vec::new();
    for i in 0..3 {
        if s[i] == 0 {
            free.push(r.column(i) * h[i]);
        } else {
            base += r.column(i) * (f64::from(s[i]) * h[i]);
        }
    }
    match free.len() {
        0 => vec![base],
        1 => vec![base + free[0], base - free[0]],
        2 => {
            let (x, y) = (free[0], free[1]);
            vec![base + x + y, base + x - y, base - x - y, base - x + y]
        }
        // Three free axes would need a zero normal: the whole box.
        _ => vec![base],
    }
}

/// The exact sign as a coordinate choice: `+1`, `−1` or `0` (free).
pub(crate) fn side(s: Sign) -> i8 {
    match s {
        Sign::Positive => 1,
        Sign::Negative => -1,
        Sign::Zero => 0,
    }
}

/// The largest absolute coordinate of a set of points (the scene's scale for
/// [`TOUCH_TOL_ABS`]).
pub(crate) fn extent(ps: &[Vec3<f64>]) -> f64 {
    ps.iter().fold(0.0f64, |m, p| m.max(p.amax()))
}

/// A box's rotation (the rounded matrix, for values) in `f64`.
pub(crate) fn rotation_f64(q: &[f64; 4]) -> nalgebra::Matrix3<f64> {
    OrientedBox::new(Vec3::zeros(), Vec3::zeros(), *q).rotation_matrix()
}

/// The one-hot selector of axis `i`.
pub(crate) fn e3(i: usize) -> [f64; 3] {
    let mut e = [0.0; 3];
    e[i] = 1.0;
    e
}

/// A candidate from its selectors and flags (`dir = +1`).
pub(crate) fn cand(s: [f64; 3], t: [f64; 3], f: [f64; 3]) -> Cand {
    [s[0], s[1], s[2], t[0], t[1], t[2], f[0], f[1], f[2], 1.0]
}

// ---------------------------------------------------------------------------
// Box–box
// ---------------------------------------------------------------------------

/// Contact between boxes `a` and `b`, **the lecture's form**: Ericson's
/// `TestOBBOBB` (*Real-Time Collision Detection*, §4.4.1) turned into a
/// contact, with `R` from [`OrientedBox::rotation_matrix_lecture`],
/// `R_ij = A_i · B_j`, `t` the centres' offset in `a`'s frame, and
/// [`OBB_EPSILON`] added to every `|R_ij|`. Along each of the 15 axes the
/// overlap `r_a + r_b − |t · L|` (negative: no contact), divided by `‖L‖`
/// (`√(R_{i1 j}² + R_{i2 j}²)` for `A_i × B_j`; a cross product shorter than
/// [`OBB_EPSILON`] is skipped as parallel edges). The least overlap is the
/// depth (first of the format's order on equal values), the normal `∓L/‖L‖`
/// away from `b` (`+L` when `t · L = 0`). The point, as textbooks make it:
/// on a face axis, `a`'s deepest vertex (against the normal; an axis level
/// with it left at the centre's coordinate) moved out by the depth onto
/// `b`'s support plane; edge against edge, the point of `b`'s edge closest
/// to `a`'s (Ericson's closest points of two segments).
///
/// Known wrong by design: the epsilon widens every projection (boxes apart by
/// less than about `1e-6` of their size along a face axis are in contact, and
/// every depth is that much too deep); ties are `==` on rounded values, so a
/// 3-4-5 box resting on another is degenerate or not as the rounding falls;
/// the point is one vertex moved out, on the touching set only where that
/// vertex lands on `b` (not where `a` overhangs `b`'s face).
/// `degenerate` is set for a tie as computed (`t · L = 0` on the best axis,
/// or an equal overlap along a direction that differs).
pub fn contact_box_box_lecture<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    lecture_finite(contact_box_box_lecture_raw(a, b))
}

#[derive(Clone, Copy, Debug)]
enum LectureAxis {
    FaceA,
    FaceB,
    Edge(usize, usize),
}

/// One of the lecture's candidate pushes.
struct Push<T: Real> {
    depth: T,
    normal: Vec3<T>,
    kind: LectureAxis,
    both_ways: bool,
}

/// The least of the lecture's pushes (first on equal values) and whether it
/// ties, as computed.
fn lecture_least<T: Real>(pushes: Vec<Push<T>>) -> Option<(Push<T>, bool)> {
    let mut best = 0;
    for (i, p) in pushes.iter().enumerate() {
        if p.depth < pushes[best].depth {
            best = i;
        }
    }
    let b = pushes.get(best)?;
    let near_one = T::one() - T::of(1e-9);
    let tie = b.both_ways
        || pushes
            .iter()
            .enumerate()
            .any(|(i, p)| i != best && p.depth == b.depth && p.normal.dot(&b.normal) < near_one);
    let mut pushes = pushes;
    Some((pushes.swap_remove(best), tie))
}

fn sign_or_zero<T: Real>(x: T) -> T {
    if x > T::zero() {
        T::one()
    } else if x < T::zero() {
        -T::one()
    } else {
        T::zero()
    }
}

/// The vertex of a box deepest along `d` (the most `d·x`; a coordinate whose
/// axis is perpendicular to `d` left at the centre's).
fn support_lecture<T: Real>(c: &Vec3<T>, r: &nalgebra::Matrix3<T>, h: &Vec3<T>, d: &Vec3<T>) -> Vec3<T> {
    let mut p = *c;
    for i in 0..3 {
        p += r.column(i) * (sign_or_zero(r.column(i).dot(d)) * h[i]);
    }
    p
}

fn contact_box_box_lecture_raw<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    let (ra, rb) = (a.rotation_matrix_lecture(), b.rotation_matrix_lecture());
    let (ea, eb) = (a.half_extents.map(|x| x.abs()), b.half_extents.map(|x| x.abs()));
    let r = ra.transpose() * rb;
    let d = b.center - a.center;
    let t = ra.transpose() * d;
    let abs = r.map(|x| x.abs() + T::of(OBB_EPSILON));
    let mut pushes = Vec::with_capacity(15);
    let away = |dist: T, axis: Vec3<T>| if dist > T::zero() { -axis } else { axis };
    for i in 0..3 {
        let overlap = ea[i] + (eb[0] * abs[(i, 0)] + eb[1] * abs[(i, 1)] + eb[2] * abs[(i, 2)]) - t[i].abs();
        if !(overlap >= T::zero()) {
            return None;
        }
        let normal = away(t[i], ra.column(i).into_owned());
        pushes.push(Push { depth: overlap, normal, kind: LectureAxis::FaceA, both_ways: t[i] == T::zero() });
    }
    for j in 0..3 {
        let sa = ea[0] * abs[(0, j)] + ea[1] * abs[(1, j)] + ea[2] * abs[(2, j)];
        let tj = t[0] * r[(0, j)] + t[1] * r[(1, j)] + t[2] * r[(2, j)];
        let overlap = sa + eb[j] - tj.abs();
        if !(overlap >= T::zero()) {
            return None;
        }
        let normal = away(tj, rb.column(j).into_owned());
        pushes.push(Push { depth: overlap, normal, kind: LectureAxis::FaceB, both_ways: tj == T::zero() });
    }
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            let sa = ea[i1] * abs[(i2, j)] + ea[i2] * abs[(i1, j)];
            let sb = eb[j1] * abs[(i, j2)] + eb[j2] * abs[(i, j1)];
            let dist = t[i2] * r[(i1, j)] - t[i1] * r[(i2, j)];
            let overlap = sa + sb - dist.abs();
            if !(overlap >= T::zero()) {
                return None;
            }
            let len = (r[(i1, j)] * r[(i1, j)] + r[(i2, j)] * r[(i2, j)]).sqrt();
            if !(len > T::of(OBB_EPSILON)) {
                continue;
            }
            // L = A_i × B_j in a's frame is e_i × R_j.
            let mut la = Vec3::zeros();
            la[i1] = -r[(i2, j)];
            la[i2] = r[(i1, j)];
            let normal = away(dist, ra * (la / len));
            let kind = LectureAxis::Edge(i, j);
            pushes.push(Push { depth: overlap / len, normal, kind, both_ways: dist == T::zero() });
        }
    }
    let (best, tie) = lecture_least(pushes)?;
    let n = best.normal;
    let point = match best.kind {
        LectureAxis::FaceA | LectureAxis::FaceB => support_lecture(&a.center, &ra, &ea, &(-n)) + n * best.depth,
        LectureAxis::Edge(i, j) => {
            let mut pa = support_lecture(&a.center, &ra, &ea, &(-n));
            pa -= ra.column(i) * (sign_or_zero(-ra.column(i).dot(&n)) * ea[i]);
            let mut pb = support_lecture(&b.center, &rb, &eb, &n);
            pb -= rb.column(j) * (sign_or_zero(rb.column(j).dot(&n)) * eb[j]);
            let (da, db) = (ra.column(i) * ea[i], rb.column(j) * eb[j]);
            closest_pt_segment_segment_lecture(&(pa - da), &(pa + da), &(pb - db), &(pb + db)).1
        }
    };
    Some(Contact { point, normal: n, depth: best.depth, degenerate: tie })
}

/// Contact between boxes `a` and `b`, **robust form**: the format's least
/// push (`docs/FORMAT.md`, "box–box") with every decision exact for the boxes
/// of the quaternions' own rotations `R(q)` (see [`crate::boxes`]). The 15
/// axes are taken as `M^a_i`, `M^b_j` and `M^a_i × M^b_j` (`M = ‖q‖² R(q)`,
/// quadratics in `q`); the push along `±L` is
/// `(‖q_b‖² Σ h^a_i |L·M^a_i| + ‖q_a‖² Σ h^b_j |L·M^b_j| ± ‖q_a‖²‖q_b‖² L·(c_b − c_a))
/// / (‖q_a‖²‖q_b‖² ‖L‖)`. Exactly decided: which axes are zero (parallel
/// edges), contact (no push negative; touching counts), the least push
/// (comparing `o_1² ‖L_2‖²` with `o_2² ‖L_1‖²`), and ties along different
/// directions (`degenerate`; the first in the format's order is the answer).
/// Then, from the exactly chosen features: the normal `±L/‖L‖` and the depth
/// to `2^−40` (from the exact polynomials, so near-parallel edges lose
/// nothing), and the point: the average of the corners of the touching set
/// `(a + depth·n) ∩ b` — `a`'s support feature in `−n` (its face, edge or
/// vertex, each chosen by the exact sign of `L · A_i`) moved by `depth·n`,
/// clipped against `b`'s in `+n` — computed in `f64` with the rounded matrix
/// [`OrientedBox::rotation_matrix`], within [`TOUCH_TOL`] and [`TOUCH_TOL_ABS`]
/// of that set.
///
/// A floating-point stage settles the least push first where it is certain
/// (`crate::boxes::stage`), which is the exact decision.
///
/// Non-finite input: no contact. A zero quaternion is the identity.
pub fn contact_box_box<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    box_box(a, b, true)
}

/// [`contact_box_box`] without its floating-point stage: the exact decisions
/// alone, which the stage must agree with bit for bit.
#[cfg(test)]
pub(super) fn contact_box_box_unstaged<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    box_box(a, b, false)
}

fn box_box<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>, staged: bool) -> Option<Contact<T>> {
    let (qa, qb) = (quaternion_of(a)?, quaternion_of(b)?);
    let (ca, cb) = (wide3(&a.center), wide3(&b.center));
    let (ha, hb) = (wide3(&a.half_extents).map(f64::abs), wide3(&b.half_extents).map(f64::abs));
    let l: [f64; 12] = cat(&[&ca, &cb, &ha, &hb]);
    if !all_finite(&l) {
        return None;
    }
    let g: [f64; 8] = cat(&[&qa, &qb]);
    let axes = box_box_axes();
    // The floating-point stage settles the least push and the signs along
    // the axes where it is certain (`stage::box_box_contact`: the exact
    // decisions); the exact code decides the rest.
    let settled = if staged { stage::box_box_contact(&qa, &qb, &l) } else { None };
    let least = match &settled {
        None => bb::least(l, g, &axes),
        Some(s) if s.apart() => Least::Apart,
        Some(s) => s.least(&axes).unwrap_or_else(|| bb::least_by(l, g, &axes, s)),
    };
    let Least::Touch { best, tie } = least else { return None };
    let k = scene_scale(&l);
    let normal = bb::normal(l, g, &best, 0).unwrap_or_else(fallback_normal);
    let (o, n2) = bb::depth(l, g, &best, 0);
    let depth = scaled_f64(over_norm2(over_norm2(over_sqrt(o, n2), &qa), &qb), i64::from(k));
    // The features: a's in −n, b's in +n, by the exact signs of L · axis.
    let known = settled.map_or([None; 6], |s| s.along(&best));
    let along = |x: usize| {
        known[x].unwrap_or_else(|| {
            let w: [f64; 6] = std::array::from_fn(|y| if y == x { 1.0 } else { 0.0 });
            let u: [f64; 24] = cat(&[&g, &best, &w]);
            poly::sign_fast(l, u, bb::along::<Fast>, bb::along::<Filt>, bb::along::<BigFloat>)
        })
    };
    let sa = [0, 1, 2].map(|i| -side(along(i)));
    let sb = [0, 1, 2].map(|j| side(along(3 + j)));
    let (ras, rbs) = (rotation_f64(&qa), rotation_f64(&qb));
    let (cas, cbs, has, hbs) = (up(ca, k), up(cb, k), up(ha, k), up(hb, k));
    let fa: Vec<Vec3<f64>> = box_feature(&cas, &ras, &has, sa).into_iter().map(|p| p + normal * depth).collect();
    let fb = box_feature(&cbs, &rbs, &hbs, sb);
    let point = touching_point(&fa, &fb, &normal, extent(&[cas, cbs, has, hbs]));
    Some(finish(point, normal, depth, k, tie))
}

/// The 15 candidate axes of two boxes, in the format's order: `A_0..2`,
/// `B_0..2`, then `A_i × B_j` (`i` outer).
pub(super) fn box_box_axes() -> [Cand; 15] {
    let z = [0.0; 3];
    std::array::from_fn(|x| match x {
        0..3 => cand(e3(x), z, [1.0, 0.0, 0.0]),
        3..6 => cand(z, e3(x - 3), [0.0, 1.0, 0.0]),
        _ => cand(e3((x - 6) / 3), e3((x - 6) % 3), [0.0, 0.0, 1.0]),
    })
}

mod bb {
    use super::*;

    /// Lengths `[c_a, c_b, h_a, h_b]`, global units `[q_a, q_b]`, candidate
    /// `[s_a, s_b, (face a, face b, cross), dir]`: `L = M^a_s`, `M^b_s` or
    /// `M^a_s × M^b_s`, and `o = ‖q_a‖²‖q_b‖²` times the push along
    /// `dir · L`.
    pub(super) fn frame<N: Ring>(l: &[N; 12], g: &[N], c: &[N]) -> ([N; 3], N) {
        let (qa, qb) = ([&g[0], &g[1], &g[2], &g[3]], [&g[4], &g[5], &g[6], &g[7]]);
        let (ma, mb) = (quaternion_axes(qa), quaternion_axes(qb));
        let (na, nb) = (poly::norm2(qa), poly::norm2(qb));
        let (x, y) = (select(&c[0..3], &ma), select(&c[3..6], &mb));
        let axis = add3(&add3(&scale3(&x, &c[6]), &scale3(&y, &c[7])), &scale3(&cross3(refs(&x), refs(&y)), &c[8]));
        let lv = refs(&axis);
        let d = sub3(at3(l, 3), at3(l, 0));
        let mut o = na.mul(&nb).mul(&c[9]).mul(&dot3(lv, refs(&d)));
        for i in 0..3 {
            o = o.add(&nb.mul(&l[6 + i].mul(&dot3(lv, refs(&ma[i])).abs())));
            o = o.add(&na.mul(&l[9 + i].mul(&dot3(lv, refs(&mb[i])).abs())));
        }
        (axis, o)
    }
    sat_polys!(frame, 12, 8);

    /// `dir · L · (M^a_w + M^b_w)` for one-hot (or zero) selectors
    /// `w = [w_a, w_b]`: units `[q_a, q_b, candidate, w]`.
    pub(super) fn along<N: Ring>(l: &[N; 12], u: &[N; 24]) -> N {
        let (axis, _) = frame(l, &u[..8], &u[8..18]);
        let (qa, qb) = ([&u[0], &u[1], &u[2], &u[3]], [&u[4], &u[5], &u[6], &u[7]]);
        let w = add3(&select(&u[18..21], &quaternion_axes(qa)), &select(&u[21..24], &quaternion_axes(qb)));
        u[17].mul(&dot3(refs(&axis), refs(&w)))
    }
}

// ---------------------------------------------------------------------------
// Box–triangle
// ---------------------------------------------------------------------------

/// The triangle's edges `v1 − v0`, `v2 − v1`, `v0 − v2`.
pub(crate) fn tri_edges<T: Real>(t: &Triangle<T>) -> [Vec3<T>; 3] {
    let [v0, v1, v2] = t.vertices;
    [v1 - v0, v2 - v1, v0 - v2]
}

/// Contact between a box `a` and a triangle `b`, **the lecture's form**: the
/// separating axes of Ericson's box–triangle test (§5.2.9, with the box's
/// rotation from [`OrientedBox::rotation_matrix_lecture`]) — the box's three
/// axes, the triangle's normal `(v1 − v0) × (v2 − v0)`, and the nine
/// `A_i × E_k` — each projected plainly: the box to `c·L ± Σ h_i |A_i·L|`,
/// the triangle to `[min, max]` of its vertices. Along each, the shorter
/// push, `max_b − min_a` or `max_a − min_b` (negative: no contact), over
/// `‖L‖`; an axis shorter than [`OBB_EPSILON`] times its factors' lengths is
/// skipped as zero. The least (first in the format's order on equal values)
/// is the depth and its direction the normal. The point, as textbooks make it:
/// on a face axis (the box's or the triangle's normal), the box's deepest
/// vertex (an axis level with the normal left at the centre's coordinate)
/// moved out by the depth; edge against edge, the point of the triangle's
/// edge closest to the box's edge.
///
/// Known wrong: the skip threshold is absolute in the axes' lengths (a
/// near-parallel edge pair is skipped or not by it), the tie test is `==` on
/// rounded values, the point is one vertex.
pub fn contact_box_triangle_lecture<T: Real>(a: &OrientedBox<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    lecture_finite(contact_box_triangle_lecture_raw(a, b))
}

fn contact_box_triangle_lecture_raw<T: Real>(a: &OrientedBox<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    let ra = a.rotation_matrix_lecture();
    let h = a.half_extents.map(|x| x.abs());
    let v = b.vertices;
    let e = tri_edges(b);
    let normal_t = e[0].cross(&(v[2] - v[0]));
    let mut pushes = Vec::with_capacity(13);
    let mut axes: Vec<(Vec3<T>, T, LectureAxis)> = Vec::with_capacity(13);
    for i in 0..3 {
        axes.push((ra.column(i).into_owned(), T::zero(), LectureAxis::FaceA));
    }
    axes.push((normal_t, T::of(OBB_EPSILON) * e[0].norm() * e[2].norm(), LectureAxis::FaceB));
    for i in 0..3 {
        for (k, ek) in e.iter().enumerate() {
            axes.push((ra.column(i).cross(ek), T::of(OBB_EPSILON) * ek.norm(), LectureAxis::Edge(i, k)));
        }
    }
    for (l, skip, kind) in axes {
        let len = l.norm();
        if !(len > skip) || !(len > T::zero()) {
            continue;
        }
        let c = a.center.dot(&l);
        let rad = (0..3).fold(T::zero(), |s, i| s + h[i] * ra.column(i).dot(&l).abs());
        let p = v.map(|x| x.dot(&l));
        let (lo, hi) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
        let (plus, minus) = (hi - (c - rad), (c + rad) - lo);
        if !(plus >= T::zero() && minus >= T::zero()) {
            return None;
        }
        let (push, normal) = if plus <= minus { (plus, l / len) } else { (minus, -l / len) };
        pushes.push(Push { depth: push / len, normal, kind, both_ways: plus == minus });
    }
    let (best, tie) = lecture_least(pushes)?;
    let n = best.normal;
    let point = match best.kind {
        LectureAxis::FaceA | LectureAxis::FaceB => support_lecture(&a.center, &ra, &h, &(-n)) + n * best.depth,
        LectureAxis::Edge(i, k) => {
            let mut pa = support_lecture(&a.center, &ra, &h, &(-n));
            pa -= ra.column(i) * (sign_or_zero(-ra.column(i).dot(&n)) * h[i]);
            let da = ra.column(i) * h[i];
            let (s, t) = (v[k], v[(k + 1) % 3]);
            closest_pt_segment_segment_lecture(&(pa - da), &(pa + da), &s, &t).1
        }
    };
    Some(Contact { point, normal: n, depth: best.depth, degenerate: tie })
}

/// Contact between a box `a` and a triangle `b`, **robust form**: the
/// format's least push (`docs/FORMAT.md`, "box–triangle") over the box's axes
/// `M_i` (`‖q‖² R(q) e_i`), the triangle's normal
/// `N = (v1 − v0) × (v2 − v0)` and the nine `M_i × E_k` (edges `v1 − v0`,
/// `v2 − v1`, `v0 − v2`), the push along `±L` being
/// `(‖q‖² max_k (±L · (v_k − c)) + Σ h_i |L · M_i|) / (‖q‖² ‖L‖)` (the
/// maximum written with absolute values, `4 max(x, y, z)`). Exactly decided,
/// as in [`contact_box_box`]: zero axes (a zero-area triangle has no normal;
/// an edge parallel to a box axis no cross product), contact, the least push,
/// ties (`degenerate`, the first in the format's order answering), and the
/// features (the box's by the signs of `L · M_i`, the triangle's vertices of
/// greatest `L · v_k` by the signs of `L · (v_k − v_m)`). The normal and depth
/// to `2^−40`; the point the average of the corners of the touching set,
/// computed in `f64` (see [`contact_box_box`]).
///
/// Non-finite input: no contact. A zero quaternion is the identity.
pub fn contact_box_triangle<T: Real>(a: &OrientedBox<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    let q = quaternion_of(a)?;
    let (c, h) = (wide3(&a.center), wide3(&a.half_extents).map(f64::abs));
    let v = b.vertices.map(|x| wide3(&x));
    let l: [f64; 15] = cat(&[&c, &h, &v[0], &v[1], &v[2]]);
    if !all_finite(&l) {
        return None;
    }
    let z = [0.0; 3];
    let mut axes = Vec::with_capacity(13);
    axes.extend((0..3).map(|i| cand(e3(i), z, [1.0, 0.0, 0.0])));
    axes.push(cand(z, z, [0.0, 1.0, 0.0]));
    for i in 0..3 {
        axes.extend((0..3).map(|k| cand(e3(i), e3(k), [0.0, 0.0, 1.0])));
    }
    let Least::Touch { best, tie } = bt::least(l, q, &axes) else { return None };
    let deg = bt::degree(&best);
    let k = scene_scale(&l);
    let normal = bt::normal(l, q, &best, deg).unwrap_or_else(fallback_normal);
    let (o, n2) = bt::depth(l, q, &best, deg);
    let depth = scaled_f64(over_norm2(times2(over_sqrt(o, n2), -2), &q), i64::from(k));
    let along = |w: [f64; 6]| {
        let u: [f64; 20] = cat(&[&q, &best, &w]);
        poly::sign_fast(l, u, bt::along::<Fast>, bt::along::<Filt>, bt::along::<BigFloat>)
    };
    let s = [0, 1, 2].map(|i| -side(along(cat(&[&e3(i), &z]))));
    let top = triangle_top(|i, j| {
        let mut w = [0.0; 6];
        w[3 + i] = 1.0;
        w[3 + j] = -1.0;
        along(w)
    });
    let rot = rotation_f64(&q);
    let (cs, hs) = (up(c, k), up(h, k));
    let vs = v.map(|x| up(x, k));
    let fa: Vec<Vec3<f64>> = box_feature(&cs, &rot, &hs, s).into_iter().map(|p| p + normal * depth).collect();
    let fb: Vec<Vec3<f64>> = top.iter().map(|&i| vs[i]).collect();
    let point = touching_point(&fa, &fb, &normal, extent(&[cs, hs, vs[0], vs[1], vs[2]]));
    Some(finish(point, normal, depth, k, tie))
}

/// The vertices of a triangle with the greatest value along a direction, in
/// order, from the exact signs `order(i, j)` of `value_i − value_j`.
pub(crate) fn triangle_top(order: impl Fn(usize, usize) -> Sign) -> Vec<usize> {
    let mut best = 0;
    for j in 1..3 {
        if order(j, best) == Sign::Positive {
            best = j;
        }
    }
    (0..3).filter(|&j| j == best || order(j, best) == Sign::Zero).collect()
}

mod bt {
    use super::*;

    /// Lengths `[c, h, v0, v1, v2]`, global units `[q]`, candidate
    /// `[s (box axis), t (edge), (face, normal, cross), dir]`: `L = M_s`,
    /// `N` or `M_s × E_t`, and `o = 4‖q‖²` times the push along `dir · L`.
    pub(super) fn frame<N: Ring>(l: &[N; 15], g: &[N], c: &[N]) -> ([N; 3], N) {
        let q = [&g[0], &g[1], &g[2], &g[3]];
        let (m, n) = (quaternion_axes(q), poly::norm2(q));
        let v = [at3(l, 6), at3(l, 9), at3(l, 12)];
        let e = [sub3(v[1], v[0]), sub3(v[2], v[1]), sub3(v[0], v[2])];
        let x = select(&c[0..3], &m);
        let y = comb3(&c[3..6], [&e[0], &e[1], &e[2]]);
        let normal = cross3(refs(&e[0]), refs(&sub3(v[2], v[0])));
        let axis =
            add3(&add3(&scale3(&x, &c[6]), &scale3(&normal, &c[7])), &scale3(&cross3(refs(&x), refs(&y)), &c[8]));
        let lv = refs(&axis);
        let reach = v.map(|vk| c[9].mul(&dot3(lv, refs(&sub3(vk, at3(l, 0))))));
        let mut o = n.mul(&max3x4(&reach[0], &reach[1], &reach[2]));
        for i in 0..3 {
            let r = l[3 + i].mul(&dot3(lv, refs(&m[i])).abs());
            o = o.add(&r.add(&r).add(&r.add(&r)));
        }
        (axis, o)
    }
    sat_polys!(frame, 15, 4);

    /// The degree of a candidate's `L` in the lengths.
    pub(super) fn degree(c: &Cand) -> i64 {
        if c[6] != 0.0 {
            0
        } else if c[7] != 0.0 {
            2
        } else {
            1
        }
    }

    /// `dir · L · (M_w + Σ_k w'_k v_k)`: units `[q, candidate, w (3), w' (3)]`
    /// (a box axis, or a difference of vertices).
    pub(super) fn along<N: Ring>(l: &[N; 15], u: &[N; 20]) -> N {
        let (axis, _) = frame(l, &u[..4], &u[4..14]);
        let q = [&u[0], &u[1], &u[2], &u[3]];
        let w = select(&u[14..17], &quaternion_axes(q));
        let v: [[N; 3]; 3] = std::array::from_fn(|k| std::array::from_fn(|i| l[6 + 3 * k + i].clone()));
        let vv = comb3(&u[17..20], [&v[0], &v[1], &v[2]]);
        u[13].mul(&dot3(refs(&axis), refs(&add3(&w, &vv))))
    }
}

#[cfg(test)]
#[path = "contact_tests.rs"]
mod tests;
