//! The faces and edges of a point set's convex hull, found with exact
//! orientation predicates (`crate::exact`), for the robust penetration depth's
//! separating axes. Duplicated, coplanar and collinear points are handled:
//! a flat hull's face is its plane (once) and its edges the polygon's
//! boundary; a segment's one edge is its two extreme points; a point has none.
//! A solid hull's neighbouring triangles in one plane make one facet.
//!
//! A solid hull is built incrementally (`O(n·f)` predicates for `n` points
//! and `f` faces); a flat one's edges by pairs (`O(n³)` on its plane).

use super::points::{Xp, same};
use super::predicates::{Dir, along, collinear, orient3d, unit};
use crate::exact::{P3, Sign, cross_estimate};
use crate::real::Vec3;

/// Relative accuracy asked of a face normal's components (2^−50).
const NORMAL_REL_ERR: f64 = 1.0 / (1u64 << 50) as f64;

/// A face: three of its points, indices into [`Hull::pts`], whose normal
/// `(p₁ − p₀) × (p₂ − p₀)` points out of the hull (for a flat hull, to one
/// side of its plane).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Face {
    /// The three points.
    pub idx: [usize; 3],
}

/// A convex hull's combinatorics.
#[derive(Clone, Debug)]
pub(crate) struct Hull<'a> {
    /// The distinct input points.
    pub pts: Vec<Xp<'a>>,
    /// For each of `pts`, the index of the input point it is.
    pub orig: Vec<usize>,
    /// Affine dimension, 0 to 3.
    pub dim: usize,
    /// Faces, one per facet (for a flat hull, its plane once).
    pub faces: Vec<Face>,
    /// Edges, as pairs of indices into `pts` (a boundary segment may appear
    /// also split at collinear points).
    pub edges: Vec<(usize, usize)>,
}

/// The unit normal of the `f64` values (to orient a flat hull's lines: its
/// use is checked exactly).
fn unit_normal(a: P3, b: P3, c: P3) -> Option<Vec3<f64>> {
    let n = crate::exact::Estimate::unit_vector(cross_estimate(a, b, c, NORMAL_REL_ERR))?;
    Some(Vec3::new(n[0], n[1], n[2]))
}

/// Whether all signs are `≥ 0` or all `≤ 0`.
fn one_sided(signs: impl Iterator<Item = Sign>) -> bool {
    let (mut pos, mut neg) = (false, false);
    for s in signs {
        pos |= s == Sign::Positive;
        neg |= s == Sign::Negative;
    }
    !(pos && neg)
}

impl<'a> Hull<'a> {
    /// The hull of `points` (finite; at least one).
    pub(crate) fn new(points: &[Xp<'a>]) -> Self {
        let mut boxed = Hull {
            pts: points.to_vec(),
            orig: (0..points.len()).collect(),
            dim: 0,
            faces: Vec::new(),
            edges: Vec::new(),
        };
        if boxed.a_box() {
            return boxed;
        }
        let mut pts: Vec<Xp<'a>> = Vec::with_capacity(points.len());
        let mut orig = Vec::with_capacity(points.len());
        for (i, p) in points.iter().enumerate() {
            if !pts.iter().any(|q| same(p, q)) {
                pts.push(*p);
                orig.push(i);
            }
        }
        let mut hull = Hull { pts, orig, dim: 0, faces: Vec::new(), edges: Vec::new() };
        let p = &hull.pts;
        if p.len() == 1 {
            return hull;
        }
        let Some(i2) = (2..p.len()).find(|&i| !collinear(p[0], p[1], p[i])) else {
            hull.dim = 1;
            hull.edges.push(segment_ends(p));
            return hull;
        };
        if (3..p.len()).all(|i| orient3d(p[0], p[1], p[i2], p[i]) == Sign::Zero) {
            hull.dim = 2;
            hull.flat(i2);
            return hull;
        };
        hull.dim = 3;
        hull.solid();
        hull
    }

    /// The hull of a box's eight corners (in their order: corner `i` has
    /// `+h_k` where bit `k` of `i` is set) with positive half extents, known
    /// without a predicate: a face per axis and side, from the corners on
    /// that side (`(p₁ − p₀) × (p₂ − p₀)` along `±M_k`, outward: the axes of
    /// a rotation are right-handed), and the twelve pairs of corners that
    /// differ in one axis. `false` (nothing done) for any other point set.
    fn a_box(&mut self) -> bool {
        let p = &self.pts;
        let Some((b, _)) = p.first().and_then(Xp::corner) else { return false };
        let ok = p.len() == 8
            && b.solid()
            && p.iter()
                .enumerate()
                .all(|(i, x)| x.corner().is_some_and(|(y, s)| std::ptr::eq(b, y) && usize::from(s) == i));
        if !ok {
            return false;
        }
        self.dim = 3;
        for k in 0..3 {
            let (j, l) = ((k + 1) % 3, (k + 2) % 3);
            for side in [0, 1] {
                let base = side << k;
                let (p1, p2) = (base | 1 << j, base | 1 << l);
                self.faces.push(Face { idx: if side == 1 { [base, p1, p2] } else { [base, p2, p1] } });
            }
            for c in (0..8).filter(|c| c >> k & 1 == 0) {
                self.edges.push((c, c | 1 << k));
            }
        }
        true
    }

    /// A flat hull: the plane through `p0, p1, p[i2]`.
    fn flat(&mut self, i2: usize) {
        let p = &self.pts;
        let Some(n) = unit_normal(p[0].v, p[1].v, p[i2].v).or_else(|| unit(&Dir::cross(p[0], p[1], p[0], p[i2])))
        else {
            return;
        };
        // A point off the plane (checked exactly), to orient lines within it.
        let extent = p.iter().flat_map(|x| x.v).fold(0.0f64, |m, x| m.max((x - p[0].v[0]).abs()).max(x.abs()));
        let mut off = None;
        let mut scale = extent.max(f64::MIN_POSITIVE);
        for _ in 0..8 {
            let r = Xp::plain([p[0].v[0] + n.x * scale, p[0].v[1] + n.y * scale, p[0].v[2] + n.z * scale]);
            if orient3d(p[0], p[1], p[i2], r) != Sign::Zero {
                off = Some(r);
                break;
            }
            scale *= 4.0;
        }
        self.faces.push(Face { idx: [0, 1, i2] });
        if let Some(r) = off {
            let all: Vec<usize> = (0..self.pts.len()).collect();
            self.edges = boundary_edges(&self.pts, &all, r);
        }
    }

    /// A solid hull (its points span space), incrementally: from a
    /// tetrahedron of four points that span space, each point outside the
    /// current hull (strictly beyond some face: a point outside a
    /// full-dimensional polytope is strictly beyond one of its facets, so a
    /// point beyond none is inside or on it and adds nothing) removes the
    /// faces it sees and joins the horizon's edges to itself. `O(n·f)`
    /// predicates for `n` points and `f` faces. Neighbouring triangles in one
    /// plane are then one facet (one face; the edge between them is no
    /// edge).
    fn solid(&mut self) {
        let p = &self.pts;
        let n = p.len();
        // `new` found p0, p1, p[i2] not collinear and some point off their plane.
        let Some(i2) = (2..n).find(|&i| !collinear(p[0], p[1], p[i])) else { return };
        let Some(i3) = (3..n).find(|&i| orient3d(p[0], p[1], p[i2], p[i]) != Sign::Zero) else { return };
        // Faces (i, j, k) with outward normal (p_j − p_i) × (p_k − p_i): a point
        // beyond the face has orient3d < 0 (see `outward` below).
        let beyond = |f: &[usize; 3], x: Xp| orient3d(p[f[0]], p[f[1]], p[f[2]], x) == Sign::Negative;
        let start = [0, 1, i2, i3];
        let mut faces: Vec<[usize; 3]> = Vec::new();
        for (f, opposite) in [([0, 1, i2], i3), ([0, 1, i3], i2), ([0, i2, i3], 1), ([1, i2, i3], 0)] {
            faces.push(if beyond(&f, p[opposite]) { [f[0], f[2], f[1]] } else { f });
        }
        for (q, x) in p.iter().enumerate() {
            if start.contains(&q) {
                continue;
            }
            let visible: Vec<bool> = faces.iter().map(|f| beyond(f, *x)).collect();
            if !visible.contains(&true) {
                continue;
            }
            let mut kept_edges = std::collections::HashSet::new();
            for (f, _) in faces.iter().zip(&visible).filter(|(_, v)| !**v) {
                for e in 0..3 {
                    kept_edges.insert((f[e], f[(e + 1) % 3]));
                }
            }
            let mut next = Vec::with_capacity(faces.len() + 4);
            for (f, v) in faces.iter().zip(&visible) {
                if !*v {
                    next.push(*f);
                    continue;
                }
                for e in 0..3 {
                    let (u, w) = (f[e], f[(e + 1) % 3]);
                    if kept_edges.contains(&(w, u)) {
                        next.push([u, w, q]);
                    }
                }
            }
            faces = next;
        }
        // Neighbouring triangles in one plane (exactly) are one facet: the
        // edge between them is no edge of the hull, and the facet keeps one
        // of its triangles as its face.
        let mut faces_of: std::collections::HashMap<(usize, usize), Vec<usize>> = std::collections::HashMap::new();
        let mut order: Vec<(usize, usize)> = Vec::new();
        for (k, f) in faces.iter().enumerate() {
            for e in 0..3 {
                let key = (f[e].min(f[(e + 1) % 3]), f[e].max(f[(e + 1) % 3]));
                let entry = faces_of.entry(key).or_default();
                if entry.is_empty() {
                    order.push(key);
                }
                entry.push(k);
            }
        }
        let mut facet: Vec<usize> = (0..faces.len()).collect();
        fn root(facet: &mut [usize], mut k: usize) -> usize {
            while facet[k] != k {
                facet[k] = facet[facet[k]];
                k = facet[k];
            }
            k
        }
        for key in order {
            if let [f, g] = faces_of[&key][..] {
                let (ff, gg) = (faces[f], faces[g]);
                let opposite = gg.iter().copied().find(|&v| v != key.0 && v != key.1).unwrap_or(gg[0]);
                if orient3d(p[ff[0]], p[ff[1]], p[ff[2]], p[opposite]) == Sign::Zero {
                    let (rf, rg) = (root(&mut facet, f), root(&mut facet, g));
                    facet[rf] = rg;
                    continue;
                }
            }
            self.edges.push(key);
        }
        for (k, f) in faces.iter().enumerate() {
            if root(&mut facet, k) == k {
                self.faces.push(Face { idx: *f });
            }
        }
    }
}

/// The two extreme points of a collinear set (distinct, at least two),
/// ordered exactly along `p₁ − p₀`.
fn segment_ends(p: &[Xp]) -> (usize, usize) {
    if p.iter().all(|x| x.e == 0.0) {
        // Exact values: a coordinate that varies orders them.
        let d = [0, 1, 2].map(|k| (p[1].v[k] - p[0].v[k]).abs());
        let axis = if d[0] >= d[1] && d[0] >= d[2] {
            0
        } else if d[1] >= d[2] {
            1
        } else {
            2
        };
        let (mut lo, mut hi) = (0, 0);
        for (i, q) in p.iter().enumerate() {
            if q.v[axis] < p[lo].v[axis] {
                lo = i;
            }
            if q.v[axis] > p[hi].v[axis] {
                hi = i;
            }
        }
        return (lo.min(hi), lo.max(hi));
    }
    let (mut lo, mut hi) = (0, 0);
    for (i, q) in p.iter().enumerate() {
        if along(*q, p[lo], p[0], p[1]) == Sign::Negative {
            lo = i;
        }
        if along(*q, p[hi], p[0], p[1]) == Sign::Positive {
            hi = i;
        }
    }
    (lo.min(hi), lo.max(hi))
}

/// The boundary edges of the coplanar points `on` of `p` (a convex polygon
/// with possibly collinear and interior points): the pairs with every other
/// point on one side of their line. `r` is a point off their plane.
fn boundary_edges(p: &[Xp], on: &[usize], r: Xp) -> Vec<(usize, usize)> {
    let mut edges = Vec::new();
    for (x, &i) in on.iter().enumerate() {
        for &j in &on[x + 1..] {
            if one_sided(on.iter().map(|&m| orient3d(p[i], p[j], r, p[m]))) {
                edges.push((i, j));
            }
        }
    }
    edges
}
