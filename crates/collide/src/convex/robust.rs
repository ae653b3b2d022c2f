//! The robust signed distance between two cores (point sets): GJK in `f64`
//! on the scaled points finds the nearest feature pair, and every decision
//! that makes the answer — which points support the two solids along the
//! normal, whether the witnesses or the normal are unique, which of two
//! equal pushes is the least — is an exact predicate on the points as given
//! (`super::predicates`), so the answer and its `degenerate` flag are right
//! at every scale.
//!
//! **The answer along a direction.** For a normal `n` (from `b` toward
//! `a`), let `S_a` be the points of `a` with the least `n·x` and `S_b` those
//! of `b` with the greatest `n·y`. When the slab between the two levels holds
//! no point of either (or, for an overlap, `n` is a least push) and the two
//! supporting sets, seen along `n`, meet, the signed distance is
//! `min n·x − max n·y` and the witness pairs are the points where the two
//! supporting polygons (points, segments or polygons, seen along `n`)
//! overlap: unique exactly when that overlap is one point. A touching pair
//! (distance exactly 0) also has a unique normal only when the overlap is a
//! point strictly inside a face, or two edges crossing strictly inside both
//! (a contact that spans a facet of the Minkowski difference), and the cores
//! do not lie in one plane.
//!
//! **Apart.** GJK's final simplex gives the exact normal `N` of its nearest
//! feature (a polynomial in the input coordinates); the certificate checks
//! the slab and the overlap exactly. A point beyond the slab joins the
//! simplex and GJK resumes; a simplex whose foot misses is replaced by its
//! faces.
//!
//! **Meeting.** The penetration depth by separating axes: the least push
//! `max_b L·y − min_a L·x` (or the reverse) over the hulls' face normals and
//! the cross products of their edges, each axis `L` a polynomial in the
//! inputs. A floating-point pass with a rigorous bound keeps only the pushes
//! that may be the least; their supports and their order are then decided
//! exactly (`p₁/‖L₁‖` against `p₂/‖L₂‖` by `p₁²‖L₂‖²` against `p₂²‖L₁‖²`), so
//! two least pushes in different directions are found exactly (`degenerate`).
//! A least push of exactly 0 is a touching pair; a negative one means the
//! cores are apart after all, and the axis or a new GJK run answers.

use super::gjk::{Gjk, Params, Vertex, extreme, gjk, gjk_from};
use super::hull::Hull;
use super::points::{Xp, same};
use super::predicates::{self as pr, Dir, ExactPush, collinear};
use crate::exact::{P3, Sign};
use crate::real::Vec3;
use std::cmp::Ordering;

/// GJK's iteration cap in the robust form: far above what any input needs
/// (the run stops when no support point improves `v`), a guard only.
const ROBUST_MAX_ITER: usize = 256;

/// How many times a failed certificate may add its most violating point to
/// the simplex and resume GJK before the separating axes take over.
const CERT_ROUNDS: usize = 8;

/// Unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// An absolute floor added to the floating-point bounds of the separating
/// axes' pass: what underflow can lose in a cross product or a dot product of
/// the scaled scene (whose largest coordinate is at most `2^201`), and what
/// scaling lost of coordinates that fell into the subnormals (`2^−1075`
/// each), far below.
const TINY: f64 = 1.0e-290;

/// The core's signed distance and witnesses, in the scaled scene's
/// coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Core {
    /// Signed distance of the cores.
    pub d: f64,
    /// Witness on `a`'s core.
    pub pa: Vec3<f64>,
    /// Witness on `b`'s core.
    pub pb: Vec3<f64>,
    /// Unit normal, from `b` toward `a`.
    pub n: Vec3<f64>,
    /// Witnesses or normal not unique.
    pub degenerate: bool,
}

/// The two point sets: as given (the exact points, for the exact
/// predicates) and their `f64` values scaled by a power of two into the
/// plain range (for floating point), index for index; `err` bounds each
/// scaled value's distance from the exact point's, per coordinate (0 when
/// every point is exact in `f64`).
pub(crate) struct Sets<'a> {
    pub a: &'a [Xp<'a>],
    pub b: &'a [Xp<'a>],
    pub sa: &'a [P3],
    pub sb: &'a [P3],
    pub err: f64,
}

/// The scene as the stages see it: the sets, and the scaled points relative
/// to `o` (`sa[0]`).
struct Scene<'a> {
    a: &'a [Xp<'a>],
    b: &'a [Xp<'a>],
    sa: &'a [P3],
    sb: &'a [P3],
    o: Vec3<f64>,
    ar: Vec<Vec3<f64>>,
    br: Vec<Vec3<f64>>,
    /// The largest 1-norm of `ar` and `br`, and of the exact points
    /// relative to `o` (scaled), rounded up.
    m1: f64,
    /// [`Sets::err`].
    pe: f64,
}

fn v3(p: &P3) -> Vec3<f64> {
    Vec3::new(p[0], p[1], p[2])
}

fn sub(p: &P3, q: &P3) -> Vec3<f64> {
    Vec3::new(p[0] - q[0], p[1] - q[1], p[2] - q[2])
}

impl<'a> Scene<'a> {
    fn new(s: &Sets<'a>) -> Self {
        let o = s.sa[0];
        let ar: Vec<Vec3<f64>> = s.sa.iter().map(|p| sub(p, &o)).collect();
        let br: Vec<Vec3<f64>> = s.sb.iter().map(|p| sub(p, &o)).collect();
        let m1 = ar.iter().chain(&br).fold(0.0f64, |m, x| m.max(x.x.abs() + x.y.abs() + x.z.abs()));
        let m1 = (m1 + 6.0 * s.err) * (1.0 + 4.0 * U);
        Scene { a: s.a, b: s.b, sa: s.sa, sb: s.sb, o: v3(&o), ar, br, m1, pe: s.err }
    }

    fn diff(&self, i: usize, j: usize) -> Vec3<f64> {
        self.ar[i] - self.br[j]
    }

    fn vertex(&self, ia: usize, ib: usize) -> Vertex<f64> {
        Vertex { w: self.diff(ia, ib), ia, ib }
    }
}

/// The signed distance of the hulls of the two sets (finite, non-empty, of
/// one length each way).
pub(crate) fn core(sets: &Sets) -> Core {
    let s = Scene::new(sets);
    let a0 = s.a[0];
    if s.a.iter().chain(s.b).all(|p| same(p, &a0)) {
        // Every point is one point: two single points, coincident.
        return Core { d: 0.0, pa: s.o, pb: s.o, n: Vec3::z(), degenerate: true };
    }
    let diff = |i: usize, j: usize| s.diff(i, j);
    let params = Params { rel: 0.0, abs: 0.0, max_iter: ROBUST_MAX_ITER };
    let g = gjk(&s.ar, &s.br, &diff, &params);
    if !g.contains {
        if let Some(c) = certified(&s, g.clone()) {
            return c;
        }
        // Floating point could not find the nearest feature (a distance far
        // below the rounding of the scene's coordinates): exactly.
        if let Some(c) = exact_gjk(&s, g.simplex.clone()) {
            return c;
        }
    }
    match separating_axes(&s) {
        Sat::Answer(c) => c,
        // The cores are apart though GJK found them meeting (or could not
        // certify its simplex): exactly, from the separating axis's supports.
        Sat::Apart(start) => exact_gjk(&s, vec![start]).unwrap_or_else(|| uncertified(&s, &g)),
    }
}

/// How many simplices the exact GJK may visit: each is strictly nearer the
/// origin than the last, so the run ends; a guard only.
const EXACT_ROUNDS: usize = 256;

/// GJK decided exactly: the current simplex's nearest face by exact
/// predicates ([`nearest_face`]), certified against every point
/// ([`certify_vertices`]); a point beyond its slab (the exact support
/// along its normal) joins it. `None` when the origin lies in a simplex
/// (the cores meet) or no progress is made.
fn exact_gjk(s: &Scene, start: Vec<Vertex<f64>>) -> Option<Core> {
    let mut w: Vec<Vertex<f64>> = Vec::with_capacity(4);
    for v in start {
        if !w.iter().any(|x| x.ia == v.ia && x.ib == v.ib) {
            w.push(v);
        }
    }
    for _ in 0..EXACT_ROUNDS {
        let (t, dir, o, sep) = nearest_face(s, &w)?;
        match certify_vertices(s, &t) {
            Ok(c) => return Some(c),
            Err(Fail::Beyond(_)) if sep != Sign::Zero => {
                let ia = exact_extreme_of(&dir, s.a, -o);
                let ib = exact_extreme_of(&dir, s.b, o);
                if w.iter().any(|x| x.ia == ia && x.ib == ib) {
                    return None;
                }
                w = t;
                w.push(s.vertex(ia, ib));
            }
            Err(_) => return None,
        }
    }
    None
}

/// The index of the point with the exactly greatest `o·N·x` (the first).
fn exact_extreme_of(dir: &Dir, p: &[Xp], o: i8) -> usize {
    (1..p.len()).fold(0, |best, i| if pr::side(dir, p[i], p[best]).as_i8() * o > 0 { i } else { best })
}

/// The face of the Minkowski simplex `w` (one to four vertices) nearest the
/// origin, exactly: a face whose normal `N` is not zero, whose foot of the
/// origin lies in it, and whose level (along `o·N`, `o` the sign of the
/// origin's side) has every vertex of `w` on or beyond it. With `N`, `o` and
/// the sign of `N·w₀`. `None` when there is none: the origin lies in `w`'s
/// hull.
#[allow(clippy::type_complexity, reason = "a private helper's tuple")]
fn nearest_face<'a>(s: &Scene<'a>, w: &[Vertex<f64>]) -> Option<(Vec<Vertex<f64>>, Dir<'a>, i8, Sign)> {
    let k = w.len();
    for size in 1..=k.min(3) {
        for m in 1u32..(1 << k) {
            if m.count_ones() as usize != size {
                continue;
            }
            let t: Vec<Vertex<f64>> = (0..k).filter(|i| m >> i & 1 == 1).map(|i| w[i]).collect();
            let pa: Vec<Xp> = t.iter().map(|v| s.a[v.ia]).collect();
            let pb: Vec<Xp> = t.iter().map(|v| s.b[v.ib]).collect();
            let dir = Dir::simplex(&pa, &pb);
            if pr::is_zero(&dir) {
                continue;
            }
            let foot = match size {
                1 => true,
                2 => pr::foot_on_edge([pa[0], pa[1]], [pb[0], pb[1]]),
                _ => pr::foot_in_triangle([pa[0], pa[1], pa[2]], [pb[0], pb[1], pb[2]]),
            };
            if !foot {
                continue;
            }
            let sep = pr::side(&dir, pa[0], pb[0]);
            let others: Vec<i8> = (0..k)
                .filter(|i| m >> i & 1 == 0)
                .map(|i| pr::side_w(&dir, s.a[w[i].ia], s.b[w[i].ib], pa[0], pb[0]).as_i8())
                .collect();
            let o = match sep {
                Sign::Positive => 1,
                Sign::Negative => -1,
                Sign::Zero if others.iter().all(|&x| x >= 0) => 1,
                Sign::Zero => -1,
            };
            if others.iter().all(|&x| x * o >= 0) {
                return Some((t, dir, o, sep));
            }
        }
    }
    None
}

/// GJK's answer certified (resuming GJK with each violating point, up to
/// [`CERT_ROUNDS`] times), or `None` when the simplex holds the origin or
/// no certificate could be had.
fn certified(s: &Scene, mut g: Gjk<f64>) -> Option<Core> {
    let diff = |i: usize, j: usize| s.diff(i, j);
    let params = Params { rel: 0.0, abs: 0.0, max_iter: ROBUST_MAX_ITER };
    for _ in 0..=CERT_ROUNDS {
        if g.contains {
            return None;
        }
        match certify_simplex(s, &g) {
            Ok(c) => return Some(c),
            Err(Some(w)) => {
                let mut start = g.simplex.clone();
                start.push(w);
                g = gjk_from(&s.ar, &s.br, &diff, &params, start);
            }
            Err(None) => return None,
        }
    }
    None
}

/// The last resort, which no input is known to reach: GJK's answer as it
/// is, flagged only when GJK found no direction.
fn uncertified(s: &Scene, g: &Gjk<f64>) -> Core {
    let (pa, pb) = g.witnesses(&s.ar, &s.br);
    let v = pa - pb;
    match crate::real::try_normalize_stable(&v) {
        Some(n) if !g.contains => Core { d: v.norm(), pa: pa + s.o, pb: pb + s.o, n, degenerate: false },
        _ => Core { d: 0.0, pa: pa + s.o, pb: pb + s.o, n: Vec3::z(), degenerate: true },
    }
}

/// Why a direction was not certified.
enum Fail {
    /// A point lies beyond the slab: the most violating pair along the
    /// direction.
    Beyond(Option<Vertex<f64>>),
    /// The direction is zero, or the supporting sets do not meet seen along
    /// it (the foot of the origin misses the feature).
    Misses,
}

/// Certifies GJK's final simplex, then (when its foot misses or its normal
/// vanishes) each of its faces. `Err` with a vertex to add (a point beyond
/// the simplex's slab) or `None`.
fn certify_simplex(s: &Scene, g: &Gjk<f64>) -> Result<Core, Option<Vertex<f64>>> {
    let simplex = &g.simplex;
    match certify_vertices(s, simplex) {
        Ok(c) => return Ok(c),
        Err(Fail::Beyond(w)) => {
            return Err(w.filter(|w| !simplex.iter().any(|v| v.ia == w.ia && v.ib == w.ib)));
        }
        Err(Fail::Misses) => {}
    }
    let k = simplex.len();
    let mut subsets: Vec<Vec<Vertex<f64>>> =
        (1u32..(1 << k) - 1).map(|m| (0..k).filter(|i| m >> i & 1 == 1).map(|i| simplex[i]).collect()).collect();
    subsets.sort_by_key(|x| std::cmp::Reverse(x.len()));
    subsets.into_iter().find_map(|sub| certify_vertices(s, &sub).ok()).ok_or(None)
}

/// The supporting sets of `a` and `b` along `±N` through `a[ia]` and
/// `b[ib]`: the orientation `o` (`+1` when every point of `a` has
/// `N·x ≥ N·a[ia]` and every point of `b` `N·y ≤ N·b[ib]`, `−1` for the
/// reverse), the indices on the two levels, and whether both orientations
/// hold (every point on the levels). `None` when neither holds.
struct Support {
    o: i8,
    fa: Vec<usize>,
    fb: Vec<usize>,
    both: bool,
}

fn support(s: &Scene, dir: &Dir, vertices: &[Vertex<f64>], sep: Sign) -> Option<Support> {
    let (ia, ib) = (vertices[0].ia, vertices[0].ib);
    let (a0, b0) = (s.a[ia], s.b[ib]);
    // A simplex vertex `a_k − b_k` has `N·(a_k − b_k − a₀ + b₀) = 0` by
    // construction: with `b_k = b₀`, `a_k` is level with `a₀` (and the same
    // for `b`), a zero the filters could not see through its rounding.
    let level_a: Vec<usize> = vertices.iter().filter(|v| same(&s.b[v.ib], &b0)).map(|v| v.ia).collect();
    let level_b: Vec<usize> = vertices.iter().filter(|v| same(&s.a[v.ia], &a0)).map(|v| v.ib).collect();
    let mut fa = Vec::new();
    let mut fb = Vec::new();
    // Orientations still possible: +1 and −1 (only sep's when it is not 0).
    let (mut pos, mut neg) = (sep != Sign::Negative, sep != Sign::Positive);
    for (i, x) in s.a.iter().enumerate() {
        let side = if level_a.contains(&i) { Sign::Zero } else { pr::side(dir, *x, a0) };
        match side {
            Sign::Zero => fa.push(i),
            Sign::Positive => neg = false,
            Sign::Negative => pos = false,
        }
        if !pos && !neg {
            return None;
        }
    }
    for (j, y) in s.b.iter().enumerate() {
        let side = if level_b.contains(&j) { Sign::Zero } else { pr::side(dir, *y, b0) };
        match side {
            Sign::Zero => fb.push(j),
            Sign::Positive => pos = false,
            Sign::Negative => neg = false,
        }
        if !pos && !neg {
            return None;
        }
    }
    Some(Support { o: if pos { 1 } else { -1 }, fa, fb, both: pos && neg })
}

/// Certifies the Minkowski simplex `vertices` (one to three of them): its
/// exact normal `N`, the slab, and its foot.
fn certify_vertices(s: &Scene, vertices: &[Vertex<f64>]) -> Result<Core, Fail> {
    let pa: Vec<Xp> = vertices.iter().map(|v| s.a[v.ia]).collect();
    let pb: Vec<Xp> = vertices.iter().map(|v| s.b[v.ib]).collect();
    let dir = Dir::simplex(&pa, &pb);
    if pr::is_zero(&dir) {
        return Err(Fail::Misses);
    }
    let (ia, ib) = (vertices[0].ia, vertices[0].ib);
    let sep = pr::side(&dir, s.a[ia], s.b[ib]);
    let Some(sup) = support(s, &dir, vertices, sep) else {
        // The most violating pair along the float normal.
        let n = pr::unit(&dir).unwrap_or_else(Vec3::z);
        let n = if sep == Sign::Negative { -n } else { n };
        let (ja, jb) = (extreme(&s.ar, &n, true), extreme(&s.br, &n, false));
        return Err(Fail::Beyond(Some(s.vertex(ja, jb))));
    };
    // The foot of the origin in the simplex itself: the supporting sets
    // meet there.
    let foot = match vertices.len() {
        1 => true,
        2 => pr::foot_on_edge([pa[0], pa[1]], [pb[0], pb[1]]),
        _ => pr::foot_in_triangle([pa[0], pa[1], pa[2]], [pb[0], pb[1], pb[2]]),
    };
    let touching = sep == Sign::Zero;
    let single = |idx: &[usize], p: &[Xp]| idx.iter().all(|&i| same(&p[i], &p[idx[0]]));
    let m = if foot && !touching && (single(&sup.fa, s.a) || single(&sup.fb, s.b)) {
        Meet::Point { strict: false, at: None }
    } else {
        meet(&dir, &pts(s, &sup.fa, true), &pts(s, &sup.fb, false))
    };
    if m.is_empty() {
        return Err(Fail::Misses);
    }
    let Some(n) = pr::unit(&dir) else { return Err(Fail::Misses) };
    let n = n * f64::from(sup.o);
    let degenerate = if touching { sup.both || !m.is_strict() } else { m.is_many() };
    let d = if touching { 0.0 } else { n.dot(&sub(&s.sa[ia], &s.sb[ib])).max(0.0) };
    let (pa, pb) = witnesses(s, &n, &sup.fa, &sup.fb, d, m.at());
    Ok(Core { d, pa, pb, n, degenerate })
}

/// The separating-axis stage's outcome.
enum Sat {
    /// The answer (meeting, touching, or apart along a facet normal).
    Answer(Core),
    /// The cores are apart and no axis's certificate holds: a vertex to
    /// restart GJK from.
    Apart(Vertex<f64>),
}

/// A candidate axis: its exact direction `(p₁ − p₀) × (q₁ − q₀)` and the
/// float unit vectors of its two factors with their error bounds
/// ([`unit_diff`]).
struct Axis<'a> {
    dir: Dir<'a>,
    units: [Option<(Vec3<f64>, f64)>; 2],
}

/// One push of the floating-point pass: the axis, the sense, the float unit
/// axis, the bound of its direction's error and the bound of the pass's
/// error on any push or support value along it (see [`float_axis`]).
struct Candidate {
    axis: usize,
    sense: i8,
    u: Vec3<f64>,
    delta: f64,
    err: f64,
}

/// The candidate axes of the two hulls: `a`'s face normals, `b`'s, and the
/// cross products of their edges.
fn axes<'a>(ha: &Hull<'a>, hb: &Hull<'a>) -> Vec<Axis<'a>> {
    let mut out = Vec::new();
    for h in [ha, hb] {
        let faces = if h.dim == 3 { &h.faces[..] } else { &h.faces[..h.faces.len().min(1)] };
        for f in faces {
            let [i, j, k] = f.idx;
            let p = &h.pts;
            out.push(Axis {
                dir: Dir::cross(p[i], p[j], p[i], p[k]),
                units: [unit_diff(p[i], p[j]), unit_diff(p[i], p[k])],
            });
        }
    }
    let (da, db) = (directions(ha), directions(hb));
    for &((i, j), ua) in &da {
        for &((k, l), ub) in &db {
            out.push(Axis { dir: Dir::cross(ha.pts[i], ha.pts[j], hb.pts[k], hb.pts[l]), units: [ua, ub] });
        }
    }
    out
}

/// The hull's edges, one per direction (exactly parallel edges, either way,
/// give the same cross products): an edge whose float direction is far from
/// every kept one's is new without an exact test.
#[allow(clippy::type_complexity, reason = "a private helper's pairs")]
fn directions(h: &Hull) -> Vec<((usize, usize), Option<(Vec3<f64>, f64)>)> {
    let mut kept: Vec<((usize, usize), Option<(Vec3<f64>, f64)>)> = Vec::new();
    for e in &h.edges {
        let u = unit_diff(h.pts[e.0], h.pts[e.1]);
        let dup = kept.iter().any(|(k, v)| {
            let far = matches!((u, v), (Some((u, du)), Some((v, dv))) if u.cross(v).norm() > 2.0 * (du + dv) + 4.0 * U);
            !far && pr::parallel(h.pts[k.0], h.pts[k.1], h.pts[e.0], h.pts[e.1])
        });
        if !dup {
            kept.push((*e, u));
        }
    }
    kept
}

/// The float unit vector of `q − p` and a bound on its error: both points'
/// values scaled by the power of two that brings their largest coordinate
/// near 1 (exact, but for coordinates that fall into the subnormals:
/// `2^−1074` each), subtracted (`u` relative) and normalized (`3u`): the
/// direction is off by at most `2(√3·u‖d‖ + 4·2^−1074 + √3 ε)/‖d‖ + 4u`
/// (`ε` the scaled sum of the points' bounds), bounded here by
/// `10u + (2^−1068 + 4ε)/‖d̃‖`. `None` when the difference vanishes.
fn unit_diff(p: Xp, q: Xp) -> Option<(Vec3<f64>, f64)> {
    let (pv, qv) = (p.v, q.v);
    let m = pv.iter().chain(&qv).fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 {
        return None;
    }
    let k = -crate::exact::frexp(m).1;
    let sc = |x: f64| crate::exact::ldexp(x, k);
    let d = Vec3::new(sc(qv[0]) - sc(pv[0]), sc(qv[1]) - sc(pv[1]), sc(qv[2]) - sc(pv[2]));
    let len = d.norm();
    let u = crate::real::try_normalize_stable(&d)?;
    let eps = if p.e + q.e > 0.0 { 4.0 * (sc(p.e + q.e) + f64::from_bits(1)) } else { 0.0 };
    Some((u, 10.0 * U + (f64::from_bits(7 << 52) + eps) / len))
}

/// The floating-point pass over one axis: its float unit vector `û`, the
/// bound `δ` of its direction's error, and a bound `err` such that every
/// push `max_b σû·y − min_a σû·x` computed with it on the scaled points
/// relative to `o`, and every support value `û·x`, is within `err` of the
/// exact push along `σL/‖L‖` (and within `err/2` of the exact value).
/// `L̃ = ê₁ × ê₂` of the edges' float unit vectors ([`unit_diff`], errors
/// `δ₁`, `δ₂`) is within `E = δ₁ + δ₂ + 6u` of the exact `L/(‖e₁‖‖e₂‖)`, so
/// its direction is off by at most `δ = 2E/(‖L̃‖ − E) + 2u`; with `M` the
/// largest 1-norm of a point relative to `o`, that moves a push by at most
/// `2Mδ` (the push is `2M`-Lipschitz in the direction), and the dot
/// products and the float relative coordinates add `18uM`: the bound is
/// twice their sum. The points' own bounds (the scaled [`Sets::err`] per
/// coordinate, `2ε` in a support value along a unit vector) add `4ε` to a
/// push. An axis whose `‖L̃‖` is within `2E` of zero has an unknown
/// direction (`err` infinite).
fn float_axis(s: &Scene, ax: &Axis) -> (Vec3<f64>, f64, f64) {
    let unknown = (Vec3::zeros(), f64::INFINITY, f64::INFINITY);
    let [Some((e1, d1)), Some((e2, d2))] = ax.units else { return unknown };
    let l = e1.cross(&e2);
    let big_e = d1 + d2 + 6.0 * U;
    let ln = l.norm();
    if !(ln > 2.0 * big_e) || !ln.is_finite() {
        return unknown;
    }
    let delta = (2.0 * big_e / (ln - big_e) + 2.0 * U) * (1.0 + 8.0 * U);
    let err = 2.0 * (s.m1 * (18.0 * U + 2.0 * delta) + 4.0 * s.pe) * (1.0 + 8.0 * U) + TINY;
    (l / ln, delta, err)
}

/// The least and greatest `u · x`.
fn range(p: &[Vec3<f64>], u: &Vec3<f64>) -> (f64, f64) {
    p.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        let t = u.dot(x);
        (lo.min(t), hi.max(t))
    })
}

/// The index of the point with the exactly greatest `σ L · x` (the first
/// such among those within `err` of the float greatest).
fn exact_extreme(dir: &Dir, exact: &[Xp], rel: &[Vec3<f64>], u: &Vec3<f64>, sense: f64, err: f64) -> usize {
    let vals: Vec<f64> = rel.iter().map(|x| sense * u.dot(x)).collect();
    let top = vals.iter().fold(f64::NEG_INFINITY, |m, v| m.max(*v));
    let mut best: Option<usize> = None;
    for (i, v) in vals.iter().enumerate() {
        // NaN values (an unknown direction) keep every point.
        if *v >= top - err || !v.is_finite() || !top.is_finite() {
            best = Some(match best {
                None => i,
                Some(b) if pr::side(dir, exact[i], exact[b]).as_i8() as f64 * sense > 0.0 => i,
                Some(b) => b,
            });
        }
    }
    best.unwrap_or(0)
}

/// The indices of the points level with `exact[r]` along the axis (exactly),
/// among those within `err` of it in floating point.
fn level_set(dir: &Dir, exact: &[Xp], rel: &[Vec3<f64>], u: &Vec3<f64>, r: usize, err: f64) -> Vec<usize> {
    let t = u.dot(&rel[r]);
    (0..exact.len())
        .filter(|&i| {
            let v = u.dot(&rel[i]);
            (!(v - t).is_finite() || (v - t).abs() <= err) && pr::side(dir, exact[i], exact[r]) == Sign::Zero
        })
        .collect()
}

/// The penetration depth by separating axes (see the module's
/// documentation).
fn separating_axes(s: &Scene) -> Sat {
    let (ha, hb) = (Hull::new(s.a), Hull::new(s.b));
    let axes = axes(&ha, &hb);
    // The floating-point pass: pushes that may be the least.
    let mut cands: Vec<(Candidate, f64, f64)> = Vec::with_capacity(2 * axes.len());
    for (k, ax) in axes.iter().enumerate() {
        let (u, delta, err) = float_axis(s, ax);
        if err.is_infinite() {
            if pr::is_zero(&ax.dir) {
                continue;
            }
            for sense in [1, -1] {
                cands.push((Candidate { axis: k, sense, u, delta, err }, f64::NEG_INFINITY, f64::INFINITY));
            }
            continue;
        }
        let (amin, amax) = range(&s.ar, &u);
        let (bmin, bmax) = range(&s.br, &u);
        for (sense, push) in [(1, bmax - amin), (-1, amax - bmin)] {
            cands.push((Candidate { axis: k, sense, u, delta, err }, push - err, push + err));
        }
    }
    if cands.is_empty() {
        return line_case(s, &ha, &hb);
    }
    let least_upper = cands.iter().fold(f64::INFINITY, |m, c| m.min(c.2));
    let kept: Vec<&Candidate> = cands.iter().filter(|c| c.1 <= least_upper || c.1.is_nan()).map(|c| &c.0).collect();
    // The exact pass: supports, pushes and their order.
    let pushes: Vec<(ExactPush, usize, usize)> = kept
        .iter()
        .map(|c| {
            let dir = axes[c.axis].dir;
            let sg = f64::from(c.sense);
            let xa = exact_extreme(&dir, s.a, &s.ar, &c.u, -sg, c.err);
            let yb = exact_extreme(&dir, s.b, &s.br, &c.u, sg, c.err);
            let p = if c.sense > 0 { [s.b[yb], s.a[xa]] } else { [s.a[xa], s.b[yb]] };
            let sign = pr::side(&dir, p[0], p[1]);
            (ExactPush { axis: dir, sense: c.sense, p, sign }, xa, yb)
        })
        .collect();
    // Two pushes go one way only if their float directions agree within
    // their bounds; then exactly.
    let same = |i: usize, j: usize| {
        let (ci, cj) = (kept[i], kept[j]);
        if ci.axis == cj.axis {
            return ci.sense == cj.sense;
        }
        let apart = (ci.u * f64::from(ci.sense) - cj.u * f64::from(cj.sense)).norm();
        !(apart > ci.delta + cj.delta + 4.0 * U) && pr::same_direction(&pushes[i].0, &pushes[j].0)
    };
    let mut sizes: Vec<Option<Option<(f64, f64)>>> = vec![None; pushes.len()];
    let mut size = |i: usize| *sizes[i].get_or_insert_with(|| pushes[i].0.log_size());
    let mut best = 0;
    let mut equal: Vec<usize> = Vec::new();
    for i in 1..pushes.len() {
        if same(i, best) {
            continue;
        }
        let known = [size(i), size(best)];
        match pr::push_cmp(&pushes[i].0, &pushes[best].0, known) {
            Ordering::Less => {
                best = i;
                equal.clear();
            }
            Ordering::Equal => equal.push(i),
            Ordering::Greater => {}
        }
    }
    let (push, xa, yb) = pushes[best];
    let tie = equal.iter().any(|&i| !same(i, best));
    let c = kept[best];
    let sg = f64::from(c.sense);
    let dir = push.axis;
    let fa = level_set(&dir, s.a, &s.ar, &c.u, xa, c.err);
    let fb = level_set(&dir, s.b, &s.br, &c.u, yb, c.err);
    let m = meet(&dir, &pts(s, &fa, true), &pts(s, &fb, false));
    let start = s.vertex(xa, yb);
    let Some(unit) = pr::unit(&dir) else { return Sat::Apart(start) };
    let n = unit * sg;
    match push.sign {
        Sign::Negative => {
            if m.is_empty() {
                return Sat::Apart(start);
            }
            // Apart along this facet normal: the slab holds no point, and
            // the supporting sets meet.
            let d = n.dot(&sub(&s.sa[xa], &s.sb[yb])).max(0.0);
            let (pa, pb) = witnesses(s, &n, &fa, &fb, d, m.at());
            Sat::Answer(Core { d, pa, pb, n, degenerate: m.is_many() })
        }
        Sign::Zero => {
            if m.is_empty() {
                return Sat::Apart(start);
            }
            let flat = fa.len() == s.a.len() && fb.len() == s.b.len();
            let (pa, pb) = witnesses(s, &n, &fa, &fb, 0.0, m.at());
            let degenerate = tie || flat || !m.is_strict();
            Sat::Answer(Core { d: 0.0, pa, pb, n, degenerate })
        }
        Sign::Positive => {
            let depth = n.dot(&sub(&s.sb[yb], &s.sa[xa])).max(0.0);
            let (pa, pb) = witnesses(s, &n, &fa, &fb, -depth, m.at());
            // The least push's witnesses are unique when the sets meet in
            // one point (they always meet: the push is a facet normal's).
            let degenerate = tie || !matches!(m, Meet::Point { .. });
            Sat::Answer(Core { d: -depth, pa, pb, n, degenerate })
        }
    }
}

/// The Minkowski difference is a point or a segment (two points, a point
/// and a segment, two parallel segments): no axis. Meeting (exactly) is
/// penetration 0 in every direction across the line: the format's fallback
/// normal, `degenerate`. Apart, the nearest pair is among the ends.
fn line_case(s: &Scene, ha: &Hull, hb: &Hull) -> Sat {
    let ends = |h: &Hull| -> Vec<usize> {
        match h.edges.first() {
            Some(&(i, j)) if h.dim == 1 => vec![h.orig[i], h.orig[j]],
            _ => vec![h.orig[0]],
        }
    };
    let (ea, eb) = (ends(ha), ends(hb));
    if let Some(p) = common_point(s, &ea, &eb) {
        let n = fallback_normal(s);
        return Sat::Answer(Core { d: 0.0, pa: v3(&p), pb: v3(&p), n, degenerate: true });
    }
    let mut candidates: Vec<Vec<Vertex<f64>>> = Vec::new();
    for &i in &ea {
        for &j in &eb {
            candidates.push(vec![s.vertex(i, j)]);
        }
    }
    if ea.len() == 2 {
        for &j in &eb {
            candidates.push(vec![s.vertex(ea[0], j), s.vertex(ea[1], j)]);
        }
    }
    if eb.len() == 2 {
        for &i in &ea {
            candidates.push(vec![s.vertex(i, eb[0]), s.vertex(i, eb[1])]);
        }
    }
    match candidates.iter().find_map(|c| certify_vertices(s, c).ok()) {
        Some(c) => Sat::Answer(c),
        None => Sat::Apart(s.vertex(ea[0], eb[0])),
    }
}

/// A point common to the two collinear (or single-point) sets given by
/// their ends, decided exactly; its scaled coordinates.
fn common_point(s: &Scene, ea: &[usize], eb: &[usize]) -> Option<P3> {
    let on = |p: Xp, q0: Xp, q1: Xp| {
        collinear(q0, q1, p) && pr::along(p, q0, q0, q1) != Sign::Negative && pr::along(q1, p, q0, q1) != Sign::Negative
    };
    match (ea.len(), eb.len()) {
        (1, 1) => same(&s.a[ea[0]], &s.b[eb[0]]).then_some(s.sa[ea[0]]),
        (1, _) => on(s.a[ea[0]], s.b[eb[0]], s.b[eb[1]]).then_some(s.sa[ea[0]]),
        (_, 1) => on(s.b[eb[0]], s.a[ea[0]], s.a[ea[1]]).then_some(s.sb[eb[0]]),
        _ => {
            // Two segments on one line meet when an end of one lies in the
            // other.
            let (p0, p1) = (s.a[ea[0]], s.a[ea[1]]);
            let (q0, q1) = (s.b[eb[0]], s.b[eb[1]]);
            eb.iter()
                .find(|&&j| on(s.b[j], p0, p1))
                .map(|&j| s.sb[j])
                .or_else(|| ea.iter().find(|&&i| on(s.a[i], q0, q1)).map(|&i| s.sa[i]))
        }
    }
}

/// The format's normal for cores that meet with no direction: `(0, 0, 1)`
/// for points, else the unit vector of `u × z` (`u × x` for a line along
/// `z`), `u` the line's direction (`a`'s first two distinct points, else
/// `b`'s).
fn fallback_normal(s: &Scene) -> Vec3<f64> {
    let dir = |exact: &[Xp], scaled: &[P3]| -> Option<Vec3<f64>> {
        let j = (1..exact.len()).find(|&j| !same(&exact[j], &exact[0]))?;
        Some(sub(&scaled[j], &scaled[0]))
    };
    let Some(u) = dir(s.a, s.sa).or_else(|| dir(s.b, s.sb)) else { return Vec3::z() };
    let z = Vec3::new(u.y, -u.x, 0.0);
    let v = if z.x == 0.0 && z.y == 0.0 { Vec3::new(0.0, u.z, -u.y) } else { z };
    crate::real::try_normalize_stable(&v).unwrap_or_else(Vec3::z)
}

/// A point of a supporting set: as given (for the predicates) and scaled
/// (for the witnesses), and whether it is `a`'s.
#[derive(Clone, Copy, Debug)]
struct Pt<'a> {
    x: Xp<'a>,
    s: Vec3<f64>,
    on_a: bool,
}

/// The points `idx` of `a` (`on_a`) or `b` as [`Pt`]s.
fn pts<'a>(s: &Scene<'a>, idx: &[usize], on_a: bool) -> Vec<Pt<'a>> {
    let (x, sc) = if on_a { (s.a, s.sa) } else { (s.b, s.sb) };
    idx.iter().map(|&i| Pt { x: x[i], s: v3(&sc[i]), on_a }).collect()
}

/// Where two supporting sets meet in one point: at a point of one of them,
/// or where a segment of `a`'s crosses one of `b`'s (`[a₀, a₁, b₀, b₁]`).
#[derive(Clone, Debug)]
enum At<'a> {
    Vertex(Pt<'a>),
    Cross(Box<[Pt<'a>; 4]>),
}

/// How two supporting sets meet, seen along the normal.
#[derive(Clone, Debug)]
enum Meet<'a> {
    /// Not at all.
    Empty,
    /// In one point (where, when known); `strict` when it is a point
    /// strictly inside a polygon or the crossing of two segments strictly
    /// inside both.
    Point { strict: bool, at: Option<At<'a>> },
    /// In more than one point.
    Many,
}

impl<'a> Meet<'a> {
    fn is_empty(&self) -> bool {
        matches!(self, Meet::Empty)
    }
    fn is_many(&self) -> bool {
        matches!(self, Meet::Many)
    }
    fn is_strict(&self) -> bool {
        matches!(self, Meet::Point { strict: true, .. })
    }
    fn at(&self) -> Option<&At<'a>> {
        match self {
            Meet::Point { at, .. } => at.as_ref(),
            _ => None,
        }
    }
}

/// A supporting set seen along the normal: a point, a segment (its two
/// ends) or a convex polygon (its vertices, counter-clockwise seen from the
/// normal's tip, none collinear with its neighbours).
enum Flat<'a> {
    Point(Pt<'a>),
    Segment(Pt<'a>, Pt<'a>),
    Polygon(Vec<Pt<'a>>),
}

/// The supporting set `pts` (non-empty, on one plane normal to `dir`) as a
/// [`Flat`], exactly.
fn flat_of<'a>(dir: &Dir, pts: &[Pt<'a>]) -> Flat<'a> {
    let mut q: Vec<Pt<'a>> = Vec::with_capacity(pts.len());
    for p in pts {
        if !q.iter().any(|x| same(&x.x, &p.x)) {
            q.push(*p);
        }
    }
    if q.len() == 1 {
        return Flat::Point(q[0]);
    }
    let (p0, p1) = (q[0].x, q[1].x);
    let Some(i2) = q.iter().position(|x| !collinear(p0, p1, x.x)) else {
        let (mut lo, mut hi) = (q[0], q[0]);
        for x in &q {
            if pr::along(x.x, lo.x, p0, p1) == Sign::Negative {
                lo = *x;
            }
            if pr::along(x.x, hi.x, p0, p1) == Sign::Positive {
                hi = *x;
            }
        }
        return Flat::Segment(lo, hi);
    };
    let p2 = q[i2].x;
    // Gift wrapping from the least point in the order along p1 − p0, then
    // p2 − p0 (a vertex: the two directions span the plane).
    let less = |x: Xp, y: Xp| match pr::along(x, y, p0, p1) {
        Sign::Zero => pr::along(x, y, p0, p2) == Sign::Negative,
        s => s == Sign::Negative,
    };
    let start = (1..q.len()).fold(0, |m, i| if less(q[i].x, q[m].x) { i } else { m });
    let mut hull = Vec::new();
    let mut cur = start;
    loop {
        hull.push(q[cur]);
        let mut next = if cur == 0 { 1 } else { 0 };
        for r in 0..q.len() {
            if r == cur || r == next {
                continue;
            }
            let (c, n, x) = (q[cur].x, q[next].x, q[r].x);
            let t = pr::orient(dir, c, n, c, x);
            if t == Sign::Negative || (t == Sign::Zero && pr::along(x, n, c, n) == Sign::Positive) {
                next = r;
            }
        }
        cur = next;
        if cur == start || hull.len() > q.len() {
            break;
        }
    }
    Flat::Polygon(hull)
}

/// How the supporting sets `pa` of `a` and `pb` of `b` (each on one plane
/// normal to `dir`) meet seen along `dir` (see [`Meet`]).
fn meet<'a>(dir: &Dir, pa: &[Pt<'a>], pb: &[Pt<'a>]) -> Meet<'a> {
    if pa.is_empty() || pb.is_empty() {
        return Meet::Empty;
    }
    let (x, y) = (flat_of(dir, pa), flat_of(dir, pb));
    let one = |p: &Pt<'a>| Meet::Point { strict: false, at: Some(At::Vertex(*p)) };
    match (&x, &y) {
        (Flat::Point(p), Flat::Point(q)) => {
            if pr::same_along(dir, p.x, q.x) {
                one(p)
            } else {
                Meet::Empty
            }
        }
        (Flat::Point(p), Flat::Segment(q0, q1)) | (Flat::Segment(q0, q1), Flat::Point(p)) => {
            let (q0, q1) = (q0.x, q1.x);
            if pr::orient(dir, q0, q1, q0, p.x) == Sign::Zero
                && pr::along(p.x, q0, q0, q1) != Sign::Negative
                && pr::along(q1, p.x, q0, q1) != Sign::Negative
            {
                one(p)
            } else {
                Meet::Empty
            }
        }
        (Flat::Point(p), Flat::Polygon(h)) | (Flat::Polygon(h), Flat::Point(p)) => {
            let mut strict = true;
            for k in 0..h.len() {
                match pr::orient(dir, h[k].x, h[(k + 1) % h.len()].x, h[k].x, p.x) {
                    Sign::Negative => return Meet::Empty,
                    Sign::Zero => strict = false,
                    Sign::Positive => {}
                }
            }
            Meet::Point { strict, at: Some(At::Vertex(*p)) }
        }
        (Flat::Segment(p0, p1), Flat::Segment(q0, q1)) => {
            let (a0, a1, b0, b1) = (p0.x, p1.x, q0.x, q1.x);
            if pr::orient(dir, a0, a1, b0, b1) != Sign::Zero {
                let s1 = pr::orient(dir, a0, a1, a0, b0) * pr::orient(dir, a0, a1, a0, b1);
                let s2 = pr::orient(dir, b0, b1, b0, a0) * pr::orient(dir, b0, b1, b0, a1);
                if s1 == Sign::Positive || s2 == Sign::Positive {
                    Meet::Empty
                } else {
                    let at = if p0.on_a { [*p0, *p1, *q0, *q1] } else { [*q0, *q1, *p0, *p1] };
                    Meet::Point {
                        strict: s1 == Sign::Negative && s2 == Sign::Negative,
                        at: Some(At::Cross(Box::new(at))),
                    }
                }
            } else if pr::orient(dir, a0, a1, a0, b0) != Sign::Zero {
                Meet::Empty
            } else {
                overlap(*p0, *p1, &[*q0, *q1])
            }
        }
        _ => general_meet(dir, &x, &y),
    }
}

/// The overlap of the segment `u v` and the points `ys` (all on its line
/// seen along the normal): how `[u, v]` meets their span.
fn overlap<'a>(u: Pt<'a>, v: Pt<'a>, ys: &[Pt<'a>]) -> Meet<'a> {
    let (mut ylo, mut yhi) = (ys[0], ys[0]);
    for y in ys {
        if pr::along(y.x, ylo.x, u.x, v.x) == Sign::Negative {
            ylo = *y;
        }
        if pr::along(y.x, yhi.x, u.x, v.x) == Sign::Positive {
            yhi = *y;
        }
    }
    let lo = if pr::along(ylo.x, u.x, u.x, v.x) == Sign::Positive { ylo } else { u };
    let hi = if pr::along(yhi.x, v.x, u.x, v.x) == Sign::Negative { yhi } else { v };
    match pr::along(hi.x, lo.x, u.x, v.x) {
        Sign::Positive => Meet::Many,
        Sign::Zero => Meet::Point { strict: false, at: Some(At::Vertex(lo)) },
        Sign::Negative => Meet::Empty,
    }
}

/// A polygon against a segment or a polygon: when a line through an edge
/// of one (or through the segment) has the other wholly on its far closed
/// side, the two meet only on that line; otherwise the segment crosses the
/// polygon's inside, or the polygons' insides overlap: more than a point.
fn general_meet<'a>(dir: &Dir, x: &Flat<'a>, y: &Flat<'a>) -> Meet<'a> {
    let verts = |f: &Flat<'a>| -> Vec<Pt<'a>> {
        match f {
            Flat::Point(p) => vec![*p],
            Flat::Segment(p, q) => vec![*p, *q],
            Flat::Polygon(h) => h.clone(),
        }
    };
    // Lines (u, v, σ): the set's side is σ·orient ≥ 0.
    let lines = |f: &Flat<'a>| -> Vec<(Pt<'a>, Pt<'a>, i8)> {
        match f {
            Flat::Point(_) => Vec::new(),
            Flat::Segment(p, q) => vec![(*p, *q, 1), (*p, *q, -1)],
            Flat::Polygon(h) => (0..h.len()).map(|k| (h[k], h[(k + 1) % h.len()], 1)).collect(),
        }
    };
    for (own, other) in [(x, y), (y, x)] {
        let others = verts(other);
        for (u, v, sg) in lines(own) {
            let signs: Vec<i8> = others.iter().map(|w| pr::orient(dir, u.x, v.x, u.x, w.x).as_i8() * sg).collect();
            if signs.iter().all(|&t| t <= 0) {
                let on: Vec<Pt<'a>> = others.iter().zip(&signs).filter(|(_, t)| **t == 0).map(|(w, _)| *w).collect();
                return if on.is_empty() { Meet::Empty } else { overlap(u, v, &on) };
            }
        }
    }
    Meet::Many
}

/// Where the segment `a₀a₁` crosses `b₀b₁` seen along `n` (scaled
/// coordinates): on `a₀a₁` at the parameter from its nearer end, so a point
/// near an end keeps that end's accuracy.
fn crossing(n: &Vec3<f64>, [a0, a1, b0, b1]: [Pt; 4]) -> Option<Vec3<f64>> {
    let m = (b1.s - b0.s).cross(n);
    let (d0, d1) = (m.dot(&(a1.s - a0.s)), m.dot(&(a0.s - a1.s)));
    let t0 = m.dot(&(b0.s - a0.s)) / d0;
    let t1 = m.dot(&(b0.s - a1.s)) / d1;
    let x = if t0 <= 0.5 { a0.s + (a1.s - a0.s) * t0.max(0.0) } else { a1.s + (a0.s - a1.s) * t1.max(0.0) };
    (t0.is_finite() && t1.is_finite() && x.iter().all(|c| c.is_finite())).then_some(x)
}

/// A witness pair on the supporting sets `fa` (of `a`) and `fb` (of `b`)
/// along the unit normal `n`, at signed distance `d`, in the scaled scene's
/// coordinates: where they meet when that is one known point, else a set's
/// single point and its foot on the other level, else the closest points of
/// the two sets' projections onto the plane normal to `n` (one point where
/// they overlap), lifted back to each set's level.
fn witnesses(s: &Scene, n: &Vec3<f64>, fa: &[usize], fb: &[usize], d: f64, at: Option<&At>) -> (Vec3<f64>, Vec3<f64>) {
    match at {
        Some(At::Vertex(p)) if p.on_a => return (p.s, p.s - n * d),
        Some(At::Vertex(p)) => return (p.s + n * d, p.s),
        Some(At::Cross(c)) => {
            if let Some(x) = crossing(n, **c) {
                return (x, x - n * d);
            }
        }
        None => {}
    }
    let fa: Vec<usize> = if fa.is_empty() { vec![0] } else { fa.to_vec() };
    let fb: Vec<usize> = if fb.is_empty() { vec![0] } else { fb.to_vec() };
    let single = |f: &[usize], p: &[Xp]| f.iter().all(|&i| same(&p[i], &p[f[0]]));
    if single(&fa, s.a) {
        let x = v3(&s.sa[fa[0]]);
        return (x, x - n * d);
    }
    if single(&fb, s.b) {
        let y = v3(&s.sb[fb[0]]);
        return (y + n * d, y);
    }
    let la = fa.iter().map(|&i| n.dot(&s.ar[i])).sum::<f64>() / fa.len() as f64;
    let hb = fb.iter().map(|&j| n.dot(&s.br[j])).sum::<f64>() / fb.len() as f64;
    let proj = |x: &Vec3<f64>| x - n * n.dot(x);
    let pa: Vec<Vec3<f64>> = fa.iter().map(|&i| proj(&s.ar[i])).collect();
    let pb: Vec<Vec3<f64>> = fb.iter().map(|&j| proj(&s.br[j])).collect();
    let diff = |i: usize, j: usize| pa[i] - pb[j];
    let params = Params { rel: 0.0, abs: 0.0, max_iter: ROBUST_MAX_ITER };
    let g = gjk(&pa, &pb, &diff, &params);
    let (qa, qb) = g.witnesses(&pa, &pb);
    let m = (qa + qb) * 0.5 + s.o;
    (m + n * la, m + n * hb)
}
