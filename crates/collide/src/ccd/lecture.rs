//! The lecture's continuous collision detection (Provot 1997; Bridson,
//! Fedkiw & Anderson 2002): the coplanarity cubic in `f64`, its roots by
//! bracketing and Newton's method, and a static inside test with a tolerance
//! at each root.

use super::{Ccd, Inputs};

/// Tolerance of the lecture's inside tests, on barycentric coordinates and
/// segment parameters (dimensionless): a point exactly on an edge comes out
/// at `−1e-16` or so after the roundings of the root and of the 2 × 2 solve,
/// and simulators widen the test so as not to lose it (Bridson et al. widen
/// by the cloth's thickness instead; this is the dimensionless form). `1e-6`
/// is the order such code uses: it admits points up to a millionth of the
/// triangle's (segment's) size outside it — the false positives the
/// benchmark counts.
pub const LECTURE_INSIDE_TOL: f64 = 1e-6;

/// Relative threshold below which the lecture's edge–edge test calls two
/// edges parallel: `‖da × db‖² ≤ PARALLEL_TOL · ‖da‖² ‖db‖²` (the squared
/// sine of the angle between them), as Ericson's closest-point code guards
/// its division. `1e-12` is a sine of `1e-6`.
pub const LECTURE_PARALLEL_TOL: f64 = 1e-12;

/// Cap on the safeguarded Newton iterations per root: each iteration also
/// shrinks the bracket (a Newton step leaving it is replaced by bisection),
/// and 64 halvings narrow `[0, 1]` to `2^−64`, below the spacing of the
/// doubles above `2^−11`; the cap is a guard, the stopping rule is the
/// bracket's relative width.
const NEWTON_STEPS: u32 = 64;

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V, b: V) -> V {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn det(a: V, b: V, c: V) -> f64 {
    dot(cross(a, b), c)
}

/// `x + t v`.
fn at(x: V, v: V, t: f64) -> V {
    [x[0] + t * v[0], x[1] + t * v[1], x[2] + t * v[2]]
}

/// The coefficients `[c0, c1, c2, c3]` of `det[u + t du, v + t dv, w + t dw]`.
pub(crate) fn cubic(u: V, du: V, v: V, dv: V, w: V, dw: V) -> [f64; 4] {
    [
        det(u, v, w),
        det(du, v, w) + det(u, dv, w) + det(u, v, dw),
        det(du, dv, w) + det(du, v, dw) + det(u, dv, dw),
        det(du, dv, dw),
    ]
}

fn horner(c: &[f64; 4], t: f64) -> f64 {
    ((c[3] * t + c[2]) * t + c[1]) * t + c[0]
}

fn horner_d(c: &[f64; 4], t: f64) -> f64 {
    (3.0 * c[3] * t + 2.0 * c[2]) * t + c[1]
}

/// The real roots of the cubic `c` in `[0, t_max]`, increasing, in `f64`:
/// the interval is cut at the roots of the derivative (quadratic formula in
/// its cancellation-free form), and each piece whose ends have opposite signs
/// (or a zero end) gives one root, by Newton's method safeguarded by
/// bisection. A cubic that is identically zero has none here (the caller
/// handles it).
pub(crate) fn cubic_roots(c: &[f64; 4], t_max: f64) -> Vec<f64> {
    let mut cuts = vec![0.0];
    let (a, b, cc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut crit = Vec::new();
    if a != 0.0 {
        let disc = b * b - 4.0 * a * cc;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            crit.push(q / a);
            if q != 0.0 {
                crit.push(cc / q);
            }
        }
    } else if b != 0.0 {
        crit.push(-cc / b);
    }
    crit.sort_by(f64::total_cmp);
    cuts.extend(crit.into_iter().filter(|&t| t > 0.0 && t < t_max));
    cuts.push(t_max);
    let mut roots: Vec<f64> = Vec::new();
    let push = |t: f64, roots: &mut Vec<f64>| {
        if t.is_finite() && roots.last() != Some(&t) {
            roots.push(t);
        }
    };
    for w in cuts.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let (flo, fhi) = (horner(c, lo), horner(c, hi));
        if flo == 0.0 {
            push(lo, &mut roots);
        }
        if flo * fhi < 0.0 {
            push(newton_bisect(c, lo, hi, flo), &mut roots);
        }
    }
    if horner(c, t_max) == 0.0 {
        push(t_max, &mut roots);
    }
    roots
}

/// A root of `c` in `(lo, hi)`, where `c(lo)` (= `flo`) and `c(hi)` have
/// opposite signs: Newton from the midpoint, a step leaving the bracket
/// replaced by bisection; the bracket shrinks every step.
fn newton_bisect(c: &[f64; 4], mut lo: f64, mut hi: f64, flo: f64) -> f64 {
    let mut t = 0.5 * (lo + hi);
    for _ in 0..NEWTON_STEPS {
        let ft = horner(c, t);
        if ft == 0.0 {
            return t;
        }
        if (ft < 0.0) == (flo < 0.0) {
            lo = t;
        } else {
            hi = t;
        }
        let d = horner_d(c, t);
        let next = t - ft / d;
        let next = if next > lo && next < hi { next } else { 0.5 * (lo + hi) };
        #[expect(clippy::float_cmp, reason = "a fixed point of the iteration: identity is the stopping rule")]
        let stuck = next == t;
        if stuck || hi - lo <= f64::EPSILON * hi {
            return next;
        }
        t = next;
    }
    t
}

/// Barycentric coordinates of `p` in triangle `a b c` (Ericson's Cramer form),
/// `None` when the triangle's 2 × 2 system is singular or non-finite.
fn barycentric(p: V, a: V, b: V, c: V) -> Option<[f64; 3]> {
    let (u, v, w) = (sub(b, a), sub(c, a), sub(p, a));
    let (d00, d01, d11, d20, d21) = (dot(u, u), dot(u, v), dot(v, v), dot(w, u), dot(w, v));
    let denom = d00 * d11 - d01 * d01;
    if denom == 0.0 || !denom.is_finite() {
        return None;
    }
    let bv = (d11 * d20 - d01 * d21) / denom;
    let bw = (d00 * d21 - d01 * d20) / denom;
    let r = [1.0 - bv - bw, bv, bw];
    r.iter().all(|x| x.is_finite()).then_some(r)
}

/// Line parameters `(s, u)` of the closest points of `a0 + s (a1 − a0)` and
/// `b0 + u (b1 − b0)` (Ericson §5.1.9, unclamped), `None` when the edges are
/// parallel by [`LECTURE_PARALLEL_TOL`] or a value is non-finite.
fn edge_params(a0: V, a1: V, b0: V, b1: V) -> Option<(f64, f64)> {
    let (d1, d2, r) = (sub(a1, a0), sub(b1, b0), sub(a0, b0));
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    let (c, b) = (dot(d1, r), dot(d1, d2));
    let denom = a * e - b * b;
    if !(denom > LECTURE_PARALLEL_TOL * a * e) || !denom.is_finite() {
        return None;
    }
    let s = (b * f - c * e) / denom;
    let u = (a * f - b * c) / denom;
    (s.is_finite() && u.is_finite()).then_some((s, u))
}

fn inside01(x: f64) -> bool {
    (-LECTURE_INSIDE_TOL..=1.0 + LECTURE_INSIDE_TOL).contains(&x)
}

/// The lecture's method for either query: roots of the cubic, then the
/// static test at each (`inside` answers `Some(hit)` or `None` for a
/// degenerate static configuration, which is no hit there).
fn lecture(
    x0: &Inputs,
    x1: &Inputs,
    t_max: f64,
    vectors: [(usize, usize); 3],
    inside: impl Fn(&Inputs) -> Option<bool>,
) -> Ccd {
    let vel: Inputs = core::array::from_fn(|i| sub(x1[i], x0[i]));
    let rel = |(i, j): (usize, usize)| (sub(x0[i], x0[j]), sub(vel[i], vel[j]));
    let ((u, du), (v, dv), (w, dw)) = (rel(vectors[0]), rel(vectors[1]), rel(vectors[2]));
    let c = cubic(u, du, v, dv, w, dw);
    if c.iter().any(|x| !x.is_finite()) {
        return Ccd::DEGENERATE_MISS;
    }
    #[expect(clippy::float_cmp, reason = "the lecture's test: every computed coefficient exactly zero")]
    let coplanar = c == [0.0; 4];
    // Coplanar throughout: the cubic has no roots to offer; the lecture tests
    // the start of the step alone.
    let candidates = if coplanar { vec![0.0] } else { cubic_roots(&c, t_max) };
    let mut degenerate = coplanar;
    for t in candidates {
        let x: Inputs = core::array::from_fn(|i| at(x0[i], vel[i], t));
        match inside(&x) {
            Some(true) => return Ccd { t: Some(t), degenerate: coplanar },
            Some(false) => {}
            None => degenerate = true,
        }
    }
    Ccd { t: None, degenerate }
}

/// The lecture's vertex–face test: `[p, a, b, c]` at `t = 0` and `t = 1`.
pub(crate) fn vertex_face(x0: &Inputs, x1: &Inputs, t_max: f64) -> Ccd {
    // f = det[b − a, c − a, p − a]
    lecture(x0, x1, t_max, [(2, 1), (3, 1), (0, 1)], |x| {
        barycentric(x[0], x[1], x[2], x[3]).map(|b| b.iter().all(|&c| c >= -LECTURE_INSIDE_TOL))
    })
}

/// The lecture's edge–edge test: `[a0, a1, b0, b1]` at `t = 0` and `t = 1`.
pub(crate) fn edge_edge(x0: &Inputs, x1: &Inputs, t_max: f64) -> Ccd {
    // f = det[a1 − a0, b0 − a0, b1 − a0]
    lecture(x0, x1, t_max, [(1, 0), (2, 0), (3, 0)], |x| {
        edge_params(x[0], x[1], x[2], x[3]).map(|(s, u)| inside01(s) && inside01(u))
    })
}
