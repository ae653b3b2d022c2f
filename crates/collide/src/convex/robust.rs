//! The robust signed distance between two cores (point sets in `f64`,
//! already scaled to the plain range): GJK in `f64`, its answer certified
//! with exact predicates, and the penetration depth by separating axes over
//! the hulls' exact faces and edges.

use super::gjk::{Gjk, Params, Vertex, gjk, gjk_from};
use super::hull::Hull;
use crate::boxes::poly::{Ring, at, cross3, dot3, refs, sub3};
use crate::exact::{P3, Sign, collinear, orient3d, triple_product};
use crate::real::Vec3;

/// GJK's iteration cap in the robust form: far above what any input needs
/// (the run stops when no support point improves `v`), a guard only.
const ROBUST_MAX_ITER: usize = 256;

/// How many times a failed certificate may add its most violating point to
/// the simplex and resume GJK before the separating axes take over.
const CERT_ROUNDS: usize = 8;

/// A certified distance may differ from GJK's `‖v‖` by this many ulps of the
/// scene's scale (the sub-distance's rounding on a simplex of that size);
/// beyond it the simplex was not the closest feature pair and the
/// certificate is refused.
const CERT_GAP_ULPS: f64 = 4096.0;

/// Points within this many ulps of the scene's scale of a supporting plane
/// belong to it (for witnesses and the degenerate flag of a penetration),
/// and pushes within it tie.
const SUPPORT_ULPS: f64 = 256.0;

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

fn v3(p: &P3) -> Vec3<f64> {
    Vec3::new(p[0], p[1], p[2])
}

fn sub(p: &P3, q: &P3) -> Vec3<f64> {
    Vec3::new(p[0] - q[0], p[1] - q[1], p[2] - q[2])
}

/// `N · (x − r)` with `N = a0 − b0` (one Minkowski point). Lengths
/// `[a0, b0, x, r]`.
fn cert1<N: Ring>(l: &[N; 12], _u: &[N; 0]) -> N {
    let n = sub3(at(l, 0), at(l, 3));
    dot3(refs(&n), refs(&sub3(at(l, 6), at(l, 9))))
}

/// `N · (x − r)` with `N = e × (w0 × e)`, `w_k = a_k − b_k`, `e = w1 − w0`:
/// the direction from the origin to its foot on the line `w0 w1`. Lengths
/// `[a0, a1, b0, b1, x, r]`.
fn cert2<N: Ring>(l: &[N; 18], _u: &[N; 0]) -> N {
    let w0 = sub3(at(l, 0), at(l, 6));
    let w1 = sub3(at(l, 3), at(l, 9));
    let e = sub3(refs(&w1), refs(&w0));
    let n = cross3(refs(&e), refs(&cross3(refs(&w0), refs(&e))));
    dot3(refs(&n), refs(&sub3(at(l, 12), at(l, 15))))
}

/// `N · (x − r)` with `N = (w1 − w0) × (w2 − w0)`, `w_k = a_k − b_k`.
/// Lengths `[a0, a1, a2, b0, b1, b2, x, r]`.
fn cert3<N: Ring>(l: &[N; 24], _u: &[N; 0]) -> N {
    let w = [0, 3, 6].map(|k| sub3(at(l, k), at(l, k + 9)));
    let e1 = sub3(refs(&w[1]), refs(&w[0]));
    let e2 = sub3(refs(&w[2]), refs(&w[0]));
    let n = cross3(refs(&e1), refs(&e2));
    dot3(refs(&n), refs(&sub3(at(l, 18), at(l, 21))))
}

/// The exact sign of `N · (x − r)`, `N` the simplex's normal (see `cert*`).
fn cert_sign(a: &[P3], b: &[P3], s: &[Vertex<f64>], x: P3, r: P3) -> Sign {
    let mut len = [0.0; 24];
    let k = s.len();
    for (m, v) in s.iter().enumerate() {
        len[3 * m..3 * m + 3].copy_from_slice(&a[v.ia]);
        len[3 * (k + m)..3 * (k + m) + 3].copy_from_slice(&b[v.ib]);
    }
    len[6 * k..6 * k + 3].copy_from_slice(&x);
    len[6 * k + 3..6 * k + 6].copy_from_slice(&r);
    match k {
        1 => {
            let l: [f64; 12] = len[..12].try_into().unwrap_or([0.0; 12]);
            crate::boxes::poly::sign_of!(cert1, l, [])
        }
        2 => {
            let l: [f64; 18] = len[..18].try_into().unwrap_or([0.0; 18]);
            crate::boxes::poly::sign_of!(cert2, l, [])
        }
        _ => crate::boxes::poly::sign_of!(cert3, len, []),
    }
}

/// The simplex's normal `N` in floating point (from differences of input
/// points, so that it is accurate in direction), and the vertex nearest the
/// origin.
fn float_normal(a: &[P3], b: &[P3], s: &[Vertex<f64>]) -> (Vec3<f64>, usize) {
    let w = |v: &Vertex<f64>| sub(&a[v.ia], &b[v.ib]);
    let e = |k: usize, base: usize| sub(&a[s[k].ia], &a[s[base].ia]) - sub(&b[s[k].ib], &b[s[base].ib]);
    let base = (0..s.len()).min_by(|&i, &j| w(&s[i]).norm_squared().total_cmp(&w(&s[j]).norm_squared())).unwrap_or(0);
    let n = match s.len() {
        1 => w(&s[0]),
        2 => {
            let e = e(1 - base, base);
            e.cross(&w(&s[base]).cross(&e))
        }
        _ => {
            // Cyclic order, so that the orientation is the exact N's.
            e((base + 1) % 3, base).cross(&e((base + 2) % 3, base))
        }
    };
    (n, base)
}

/// The exact affine dimension (0 to 2 is what supporting sets have) of the
/// points `idx` of `p`, and two distinct points when it is at least 1.
fn affine_dim(p: &[P3], idx: &[usize]) -> (usize, Option<(P3, P3)>) {
    let Some(&i0) = idx.first() else { return (0, None) };
    let Some(&i1) = idx.iter().find(|&&i| !crate::exact::points_equal(p[i], p[i0])) else { return (0, None) };
    let pair = Some((p[i0], p[i1]));
    if idx.iter().all(|&i| collinear(p[i0], p[i1], p[i])) {
        return (1, pair);
    }
    let i2 = idx.iter().copied().find(|&i| !collinear(p[i0], p[i1], p[i])).unwrap_or(i0);
    if idx.iter().all(|&i| orient3d(p[i0], p[i1], p[i2], p[i]) == Sign::Zero) { (2, pair) } else { (3, pair) }
}

/// Whether the directions `q1 − q0` and `r1 − r0` are exactly parallel.
fn parallel(q: (P3, P3), r: (P3, P3)) -> bool {
    let o = [0.0; 3];
    let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    axes.iter().all(|e| triple_product(q.0, q.1, r.0, r.1, o, *e) == Sign::Zero)
}

/// The degenerate flag from the supporting sets `fa` of `a` and `fb` of `b`
/// along the normal: witnesses not unique (both sets more than a point, and a
/// face against an edge or face, or parallel edges), or, when touching, a
/// normal not unique (the sets' difference spans less than a plane).
fn flag(a: &[P3], fa: &[usize], b: &[P3], fb: &[usize], touching: bool) -> bool {
    let (da, ea) = affine_dim(a, fa);
    let (db, eb) = affine_dim(b, fb);
    let par = match (ea, eb) {
        (Some(x), Some(y)) if da == 1 && db == 1 => parallel(x, y),
        _ => false,
    };
    let fiber = da >= 1 && db >= 1 && (da + db >= 3 || par);
    let span = if da >= 2 || db >= 2 {
        2
    } else if da == 1 && db == 1 {
        if par { 1 } else { 2 }
    } else {
        da + db
    };
    fiber || (touching && span < 2)
}

/// Certifies GJK's final simplex: with its exact normal `N`, every point of
/// `a` lies on or beyond `a`'s level and every point of `b` on or below
/// `b`'s, so the slab between is empty and its width is the distance. `Err`
/// with a vertex to add (the most violating support pair) or `None`.
fn certify(
    a: &[P3],
    b: &[P3],
    ar: &[Vec3<f64>],
    br: &[Vec3<f64>],
    g: &Gjk<f64>,
    scale: f64,
) -> Result<Core, Option<Vertex<f64>>> {
    let s = &g.simplex;
    let (nf, base) = float_normal(a, b, s);
    let Some(nhat) = crate::real::try_normalize_stable(&nf) else { return Err(None) };
    let (a0, b0) = (a[s[base].ia], b[s[base].ib]);
    let sep = cert_sign(a, b, s, a0, b0);
    let sa: Vec<Sign> = a.iter().map(|x| cert_sign(a, b, s, *x, a0)).collect();
    let sb: Vec<Sign> = b.iter().map(|y| cert_sign(a, b, s, *y, b0)).collect();
    let holds =
        |o: i8| sa.iter().all(|x| x.as_i8() * o >= 0) && sb.iter().all(|y| y.as_i8() * o <= 0) && sep.as_i8() * o >= 0;
    // The float normal's own orientation, when it is exact's (sep decides
    // it unless zero).
    let of = if sep != Sign::Zero {
        sep.as_i8()
    } else if nhat.dot(&g.v) >= 0.0 {
        1
    } else {
        -1
    };
    let o = if holds(of) {
        of
    } else if sep == Sign::Zero && holds(-of) {
        -of
    } else {
        // The most violating pair along the float normal, as a new vertex.
        let n = nhat * f64::from(of);
        let ia = super::gjk::extreme(ar, &n, true);
        let ib = super::gjk::extreme(br, &n, false);
        if s.iter().any(|v| v.ia == ia && v.ib == ib) {
            return Err(None);
        }
        return Err(Some(Vertex { w: sub(&a[ia], &b[ib]), ia, ib }));
    };
    let n = nhat * f64::from(o);
    let d = if sep == Sign::Zero { 0.0 } else { n.dot(&sub(&a0, &b0)).max(0.0) };
    let vn = g.v.norm();
    if (d - vn).abs() > CERT_GAP_ULPS * f64::EPSILON * scale.max(vn) {
        return Err(None);
    }
    let (pa, pb) = g.witnesses(&a.iter().map(v3).collect::<Vec<_>>(), &b.iter().map(v3).collect::<Vec<_>>());
    let m = (pa + pb) * 0.5;
    let fa: Vec<usize> = (0..a.len()).filter(|&i| sa[i] == Sign::Zero).collect();
    let fb: Vec<usize> = (0..b.len()).filter(|&j| sb[j] == Sign::Zero).collect();
    Ok(Core { d, pa: m + n * (0.5 * d), pb: m - n * (0.5 * d), n, degenerate: flag(a, &fa, b, &fb, sep == Sign::Zero) })
}

/// The signed distance of the hulls of `a` and `b` (finite, non-empty, in
/// the plain range).
pub(crate) fn core(a: &[P3], b: &[P3]) -> Core {
    let o = a[0];
    let ar: Vec<Vec3<f64>> = a.iter().map(|p| sub(p, &o)).collect();
    let br: Vec<Vec3<f64>> = b.iter().map(|p| sub(p, &o)).collect();
    let scale = ar.iter().chain(&br).fold(0.0f64, |m, x| m.max(x.amax()));
    if scale == 0.0 {
        // Every point is `o`: two single points, coincident.
        return Core { d: 0.0, pa: v3(&o), pb: v3(&o), n: Vec3::z(), degenerate: true };
    }
    let diff = |i: usize, j: usize| sub(&a[i], &b[j]);
    let params = Params { rel: 0.0, abs: 0.0, max_iter: ROBUST_MAX_ITER };
    let mut g = gjk(&ar, &br, &diff, &params);
    for _ in 0..=CERT_ROUNDS {
        if g.contains {
            break;
        }
        match certify(a, b, &ar, &br, &g, scale) {
            Ok(c) => return c,
            Err(Some(w)) => {
                let mut start = g.simplex.clone();
                start.push(w);
                g = gjk_from(&ar, &br, &diff, &params, start);
            }
            Err(None) => break,
        }
    }
    separating_axes(a, b, &ar, &br, &g, scale, o)
}

/// One candidate direction of the separating-axis search.
struct Push {
    push: f64,
    n: Vec3<f64>,
}

/// The penetration depth by separating axes (the cores meet, or GJK's answer
/// could not be certified): the least push over the hulls' face normals and
/// the cross products of their edges.
fn separating_axes(a: &[P3], b: &[P3], ar: &[Vec3<f64>], br: &[Vec3<f64>], g: &Gjk<f64>, scale: f64, o: P3) -> Core {
    let (ha, hb) = (Hull::new(a), Hull::new(b));
    let mut axes: Vec<Vec3<f64>> = Vec::new();
    axes.extend(ha.faces.iter().map(|f| f.n));
    axes.extend(hb.faces.iter().map(|f| f.n));
    for &(i, j) in &ha.edges {
        let ea = sub(&ha.pts[j], &ha.pts[i]);
        for &(k, l) in &hb.edges {
            let eb = sub(&hb.pts[l], &hb.pts[k]);
            if let Some(u) = crate::real::try_normalize_stable(&ea.cross(&eb)) {
                axes.push(u);
            }
        }
    }
    let tol = SUPPORT_ULPS * f64::EPSILON * scale;
    let (pa0, pb0) = g.witnesses(&a.iter().map(v3).collect::<Vec<_>>(), &b.iter().map(v3).collect::<Vec<_>>());
    if axes.is_empty() {
        // The Minkowski difference is a point or a segment (two points, a
        // point and a segment, two parallel segments): no axis separates it
        // from the origin in a plane's worth of directions.
        let n = perpendicular(&ha, &hb);
        if g.contains {
            return Core { d: 0.0, pa: pa0, pb: pb0, n, degenerate: true };
        }
        let v = pa0 - pb0;
        let d = v.norm();
        let n = crate::real::try_normalize_stable(&v).unwrap_or(n);
        return Core { d, pa: pa0, pb: pb0, n, degenerate: false };
    }
    let mut pushes: Vec<Push> = Vec::with_capacity(2 * axes.len());
    for u in &axes {
        let (amin, amax) = range(ar, u);
        let (bmin, bmax) = range(br, u);
        pushes.push(Push { push: bmax - amin, n: *u });
        pushes.push(Push { push: amax - bmin, n: -u });
    }
    let (best, best_n) =
        pushes.iter().min_by(|x, y| x.push.total_cmp(&y.push)).map_or((0.0, Vec3::z()), |p| (p.push, p.n));
    if best < -tol && !g.contains {
        // An axis separates the cores: GJK's answer stands, uncertified.
        let v = pa0 - pb0;
        let d = v.norm();
        let n = crate::real::try_normalize_stable(&v).unwrap_or(best_n);
        return Core { d, pa: pa0, pb: pb0, n, degenerate: false };
    }
    let ties = pushes.iter().any(|p| p.push <= best + tol && p.n.dot(&best_n) < 1.0 - 1e-12);
    let n = best_n;
    let (fa, fb, pa, pb) = support_witnesses(ar, br, &n, tol);
    let d = -best;
    let off = v3(&o);
    Core { d, pa: pa + off, pb: pb + off, n, degenerate: ties || flag(a, &fa, b, &fb, best.abs() <= tol) }
}

/// The least and greatest `u · x`.
fn range(p: &[Vec3<f64>], u: &Vec3<f64>) -> (f64, f64) {
    p.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        let t = u.dot(x);
        (lo.min(t), hi.max(t))
    })
}

/// A unit vector perpendicular to both hulls' edges (`+z` when they have
/// none, or `+z`'s component off the edge direction).
fn perpendicular(ha: &Hull, hb: &Hull) -> Vec3<f64> {
    let e = ha
        .edges
        .first()
        .map(|&(i, j)| sub(&ha.pts[j], &ha.pts[i]))
        .or_else(|| hb.edges.first().map(|&(i, j)| sub(&hb.pts[j], &hb.pts[i])));
    let Some(e) = e.and_then(|e| crate::real::try_normalize_stable(&e)) else { return Vec3::z() };
    let ax = if e.z.abs() < 0.9 { Vec3::z() } else { Vec3::x() };
    crate::real::try_normalize_stable(&(ax - e * e.dot(&ax))).unwrap_or(Vec3::z())
}

/// The supporting sets of `a` (least `n·x`) and `b` (greatest `n·y`) within
/// `tol`, and a witness pair on them: the closest points of their
/// projections onto the plane normal to `n`, lifted back to each set's
/// level (so `pa − pb` is along `n`).
fn support_witnesses(
    ar: &[Vec3<f64>],
    br: &[Vec3<f64>],
    n: &Vec3<f64>,
    tol: f64,
) -> (Vec<usize>, Vec<usize>, Vec3<f64>, Vec3<f64>) {
    let (la, _) = range(ar, n);
    let (_, hb) = range(br, n);
    let fa: Vec<usize> = (0..ar.len()).filter(|&i| n.dot(&ar[i]) <= la + tol).collect();
    let fb: Vec<usize> = (0..br.len()).filter(|&j| n.dot(&br[j]) >= hb - tol).collect();
    let proj = |x: &Vec3<f64>| x - n * n.dot(x);
    let pa: Vec<Vec3<f64>> = fa.iter().map(|&i| proj(&ar[i])).collect();
    let pb: Vec<Vec3<f64>> = fb.iter().map(|&j| proj(&br[j])).collect();
    let diff = |i: usize, j: usize| pa[i] - pb[j];
    let params = Params { rel: 0.0, abs: 0.0, max_iter: ROBUST_MAX_ITER };
    let g = gjk(&pa, &pb, &diff, &params);
    let (qa, qb) = g.witnesses(&pa, &pb);
    let m = (qa + qb) * 0.5;
    (fa, fb, m + n * la, m + n * hb)
}
