//! GJK on the Minkowski difference of two point sets, generic over [`Real`]:
//! the lecture's form runs it in the input's type with the textbook
//! tolerances, the robust form in `f64` as its first stage (its answer is
//! then certified with exact predicates, see `robust`).
//!
//! The sub-distance is the case-by-case closest point on a simplex (Ericson,
//! *Real-Time Collision Detection*, §5.1.5–5.1.6, with the query point at
//! the origin), each degenerate simplex (zero length, area or volume)
//! answered by its lower faces, so no division by zero occurs.

use crate::real::{Real, Vec3};

/// A vertex of the simplex: the Minkowski point `w = a[ia] − b[ib]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Vertex<T: Real> {
    /// The Minkowski point.
    pub w: Vec3<T>,
    /// Index of the point of `a`.
    pub ia: usize,
    /// Index of the point of `b`.
    pub ib: usize,
}

/// The closest point of a simplex (1 to 4 vertices) to the origin.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Closest<T: Real> {
    /// The point.
    pub point: Vec3<T>,
    /// Its barycentric coordinates (zero beyond the simplex's size).
    pub lambda: [T; 4],
    /// The origin lies strictly inside a (non-degenerate) tetrahedron.
    pub inside: bool,
}

/// The closest point of the segment `a b` to the origin.
fn segment<T: Real>(a: &Vec3<T>, b: &Vec3<T>) -> (Vec3<T>, [T; 2]) {
    let e = b - a;
    let ee = e.dot(&e);
    let t = -a.dot(&e);
    if !(ee > T::zero()) || !(t > T::zero()) {
        return (*a, [T::one(), T::zero()]);
    }
    if t >= ee {
        return (*b, [T::zero(), T::one()]);
    }
    let t = t / ee;
    (a + e * t, [T::one() - t, t])
}

/// The closest point of the triangle `a b c` to the origin (Ericson's
/// `ClosestPtPointTriangle`); a degenerate triangle by its edges.
fn triangle<T: Real>(a: &Vec3<T>, b: &Vec3<T>, c: &Vec3<T>) -> (Vec3<T>, [T; 3]) {
    let (z, o) = (T::zero(), T::one());
    let ab = b - a;
    let ac = c - a;
    let d1 = -ab.dot(a);
    let d2 = -ac.dot(a);
    if d1 <= z && d2 <= z {
        return (*a, [o, z, z]);
    }
    let d3 = -ab.dot(b);
    let d4 = -ac.dot(b);
    if d3 >= z && d4 <= d3 {
        return (*b, [z, o, z]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= z && d1 >= z && d3 <= z && d1 - d3 > z {
        let v = d1 / (d1 - d3);
        return (a + ab * v, [o - v, v, z]);
    }
    let d5 = -ab.dot(c);
    let d6 = -ac.dot(c);
    if d6 >= z && d5 <= d6 {
        return (*c, [z, z, o]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= z && d2 >= z && d6 <= z && d2 - d6 > z {
        let w = d2 / (d2 - d6);
        return (a + ac * w, [o - w, z, w]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= z && d4 - d3 >= z && d5 - d6 >= z && (d4 - d3) + (d5 - d6) > z {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, [z, o - w, w]);
    }
    let sum = va + vb + vc;
    if sum > z && va >= z && vb >= z && vc >= z && sum.finite() {
        let (v, w) = (vb / sum, vc / sum);
        return (a + ab * v + ac * w, [o - v - w, v, w]);
    }
    // Degenerate (zero area, or rounding put the origin in no region): the
    // nearest of the three edges.
    let mut best: (Vec3<T>, [T; 3]) = (*a, [o, z, z]);
    let mut bd = a.norm_squared();
    for (i, j) in [(0usize, 1usize), (1, 2), (0, 2)] {
        let p = [a, b, c];
        let (q, l) = segment(p[i], p[j]);
        let d = q.norm_squared();
        if d < bd {
            bd = d;
            let mut lam = [z; 3];
            lam[i] = l[0];
            lam[j] = l[1];
            best = (q, lam);
        }
    }
    best
}

/// The closest point of the simplex `p` (1 to 4 points) to the origin.
pub(crate) fn closest_on_simplex<T: Real>(p: &[Vec3<T>]) -> Closest<T> {
    let z = T::zero();
    let mut lambda = [z; 4];
    match p.len() {
        1 => {
            lambda[0] = T::one();
            Closest { point: p[0], lambda, inside: false }
        }
        2 => {
            let (q, l) = segment(&p[0], &p[1]);
            lambda[..2].copy_from_slice(&l);
            Closest { point: q, lambda, inside: false }
        }
        3 => {
            let (q, l) = triangle(&p[0], &p[1], &p[2]);
            lambda[..3].copy_from_slice(&l);
            Closest { point: q, lambda, inside: false }
        }
        _ => tetrahedron(p),
    }
}

const FACES: [[usize; 4]; 4] = [[0, 1, 2, 3], [0, 1, 3, 2], [0, 2, 3, 1], [1, 2, 3, 0]];

/// A tetrahedron whose volume is below this many ulps of the product of its
/// edge lengths from one vertex is flat within rounding: its "inside" would
/// be decided by rounding, so its faces answer.
const FLAT_ULPS: f64 = 64.0;

fn tetrahedron<T: Real>(p: &[Vec3<T>]) -> Closest<T> {
    let z = T::zero();
    let vol = |a: &Vec3<T>, b: &Vec3<T>, c: &Vec3<T>, d: &Vec3<T>| (b - a).cross(&(c - a)).dot(&(d - a));
    let total = vol(&p[0], &p[1], &p[2], &p[3]);
    let size = (p[1] - p[0]).norm() * (p[2] - p[0]).norm() * (p[3] - p[0]).norm();
    let flat = !(total.abs() > T::of(FLAT_ULPS) * T::EPSILON * size);
    let mut best: Option<(T, Closest<T>)> = None;
    let mut any_outside = false;
    for [i, j, k, l] in FACES {
        let n = (p[j] - p[i]).cross(&(p[k] - p[i]));
        let side_origin = -n.dot(&p[i]);
        let side_other = n.dot(&(p[l] - p[i]));
        // The origin is outside this face when it lies on the side away from
        // the fourth vertex (every face, for a flat tetrahedron).
        let outside = flat || side_origin * side_other < z;
        if !outside {
            continue;
        }
        any_outside = true;
        let (q, lt) = triangle(&p[i], &p[j], &p[k]);
        let d = q.norm_squared();
        if best.as_ref().is_none_or(|(bd, _)| d < *bd) {
            let mut lambda = [z; 4];
            lambda[i] = lt[0];
            lambda[j] = lt[1];
            lambda[k] = lt[2];
            best = Some((d, Closest { point: q, lambda, inside: false }));
        }
    }
    if let (true, Some((_, c))) = (any_outside, best) {
        return c;
    }
    // Inside: barycentric coordinates by signed volumes.
    let o = Vec3::zeros();
    let lambda = [
        vol(&o, &p[1], &p[2], &p[3]) / total,
        vol(&p[0], &o, &p[2], &p[3]) / total,
        vol(&p[0], &p[1], &o, &p[3]) / total,
        vol(&p[0], &p[1], &p[2], &o) / total,
    ];
    let lambda = if lambda.iter().all(|x| x.finite() && *x >= z) { lambda } else { [T::one(), z, z, z] };
    Closest { point: o, lambda, inside: true }
}

/// Tolerances and caps of a GJK run.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Params<T: Real> {
    /// Stop when `‖v‖² − v·w ≤ rel² ‖v‖²` (van den Bergen's relative test).
    pub rel: T,
    /// Count the origin as contained when `‖v‖² ≤ abs · max ‖w‖²` over the
    /// simplex (van den Bergen's test against a vanishing `v`); 0 for "only
    /// an exact zero".
    pub abs: T,
    /// Iteration cap.
    pub max_iter: usize,
}

/// The end of a GJK run.
#[derive(Clone, Debug)]
pub(crate) struct Gjk<T: Real> {
    /// The final simplex (only vertices with positive weight, unless
    /// `contains`, when it is the simplex holding the origin).
    pub simplex: Vec<Vertex<T>>,
    /// The barycentric weights of `v` over `simplex`.
    pub lambda: Vec<T>,
    /// The closest point found, `Σ λ_k w_k`.
    pub v: Vec3<T>,
    /// The origin lies in the simplex (the cores meet, or touch within the
    /// tolerance `abs`).
    pub contains: bool,
}

impl<T: Real> Gjk<T> {
    /// The witness points `Σ λ a[ia]`, `Σ λ b[ib]` on the original sets.
    pub fn witnesses(&self, a: &[Vec3<T>], b: &[Vec3<T>]) -> (Vec3<T>, Vec3<T>) {
        let (mut pa, mut pb) = (Vec3::zeros(), Vec3::zeros());
        for (s, l) in self.simplex.iter().zip(&self.lambda) {
            pa += a[s.ia] * *l;
            pb += b[s.ib] * *l;
        }
        (pa, pb)
    }
}

/// The index of the point of `p` with the least (`sign = 1`) or greatest
/// (`sign = −1`) `sign · d · x`.
pub(crate) fn extreme<T: Real>(p: &[Vec3<T>], d: &Vec3<T>, least: bool) -> usize {
    let mut best = 0;
    let mut bv = d.dot(&p[0]);
    for (i, x) in p.iter().enumerate().skip(1) {
        let v = d.dot(x);
        if (least && v < bv) || (!least && v > bv) {
            best = i;
            bv = v;
        }
    }
    best
}

/// GJK between the hulls of `a` and `b` (both non-empty), support points
/// found on `a` and `b` as given and Minkowski points formed by `diff(i, j)`
/// (`a[i] − b[j]`, possibly computed from more accurate coordinates).
pub(crate) fn gjk<T: Real>(
    a: &[Vec3<T>],
    b: &[Vec3<T>],
    diff: &impl Fn(usize, usize) -> Vec3<T>,
    params: &Params<T>,
) -> Gjk<T> {
    gjk_from(a, b, diff, params, vec![Vertex { w: diff(0, 0), ia: 0, ib: 0 }])
}

/// [`gjk`] from a given simplex (1 to 4 vertices).
pub(crate) fn gjk_from<T: Real>(
    a: &[Vec3<T>],
    b: &[Vec3<T>],
    diff: &impl Fn(usize, usize) -> Vec3<T>,
    params: &Params<T>,
    start: Vec<Vertex<T>>,
) -> Gjk<T> {
    let (mut simplex, mut lambda, mut v) = match reduce(start) {
        Ok(x) => x,
        Err((simplex, lambda)) => {
            return Gjk { simplex, lambda, v: Vec3::zeros(), contains: true };
        }
    };
    let mut contains = false;
    if v == Vec3::zeros() {
        return Gjk { simplex, lambda, v, contains: true };
    }
    for _ in 0..params.max_iter {
        let ia = extreme(a, &v, true);
        let ib = extreme(b, &v, false);
        let w = diff(ia, ib);
        let vv = v.norm_squared();
        if simplex.iter().any(|s| s.ia == ia && s.ib == ib) || vv - v.dot(&w) <= params.rel * params.rel * vv {
            break;
        }
        let mut trial = simplex.clone();
        trial.push(Vertex { w, ia, ib });
        let (s2, l2, nvv) = match reduce(trial) {
            Ok(x) => x,
            Err((s2, l2)) => {
                simplex = s2;
                lambda = l2;
                v = Vec3::zeros();
                contains = true;
                break;
            }
        };
        let nv = nvv.norm_squared();
        if !(nv < vv) {
            // No progress: rounding has the last word.
            break;
        }
        simplex = s2;
        lambda = l2;
        v = nvv;
        let wmax = simplex.iter().fold(T::zero(), |m, s| m.max(s.w.norm_squared()));
        if nv == T::zero() || nv <= params.abs * wmax {
            contains = true;
            break;
        }
    }
    Gjk { simplex, lambda, v, contains }
}

/// The closest point of a simplex and the simplex reduced to the vertices
/// with positive weight; `Err` (the whole simplex and its weights) when the
/// origin is inside a tetrahedron.
#[allow(clippy::type_complexity, reason = "a private helper's pair of outcomes")]
fn reduce<T: Real>(trial: Vec<Vertex<T>>) -> Result<(Vec<Vertex<T>>, Vec<T>, Vec3<T>), (Vec<Vertex<T>>, Vec<T>)> {
    let pts: Vec<Vec3<T>> = trial.iter().map(|s| s.w).collect();
    let c = closest_on_simplex(&pts);
    if c.inside {
        let l = c.lambda[..trial.len()].to_vec();
        return Err((trial, l));
    }
    let mut keep: Vec<usize> = (0..trial.len()).filter(|&k| c.lambda[k] > T::zero()).collect();
    if keep.is_empty() {
        keep.push(trial.len() - 1);
    }
    let simplex = keep.iter().map(|&k| trial[k]).collect();
    let lambda = keep.iter().map(|&k| c.lambda[k]).collect();
    Ok((simplex, lambda, c.point))
}
