//! The convex hull of a `convex` shape's points, exactly: the polytope the
//! referee's distance works on (`super::distance`).
//!
//! The points are the case's `f64` inputs. Every decision is an exact sign:
//! equality of coordinates, collinearity (a cross product's components),
//! coplanarity and the side of a face (`orient3d`, the determinant
//! `det[b − a, c − a, p − a]`). Each sign is first asked of the double-word
//! stage (`super::fast`, certified at any magnitude), and only a sign it
//! leaves open is computed in rationals. So the hull is the exact hull of the
//! inputs, whatever their scale or their degeneracy:
//!
//! - one distinct point: a one-vertex polytope (no edge, no face);
//! - collinear points: the segment between the two extreme ones;
//! - coplanar points: the polygon (Andrew's monotone chain, exact, in the
//!   plane dropped onto two coordinates), its plane's normal the one face
//!   normal and its sides the edges — the same description a triangle has;
//! - otherwise: the incremental hull. Each point outside the current hull
//!   sees the faces it is strictly above (an outside point is strictly above
//!   some facet of a full-dimensional polytope, so a point that sees none is
//!   in the hull, on its boundary included, and adds nothing); those faces go,
//!   and the horizon's edges are joined to the point. Neighbouring triangles
//!   in one plane make one facet: the edge between them is not an edge of the
//!   polytope (it is left out, with its direction) and the facet's normal is
//!   kept once — fewer separating axes, the same answers.
//!
//! The cost is the incremental hull's, `O(n·f)` side tests for `n` points and
//! `f` faces, each a few dozen floating-point operations when certified.

use super::convex::{Convex, hull as hull_2d, kept};
use super::error::RefereeError;
use super::exact::{Q, V3, cross, dot, is_zero, sub, v3};
use super::fast;
use crate::geom::P3;
use std::collections::HashMap;

/// The side of `p` against the plane of `a`, `b`, `c`: the sign of
/// `det[b − a, c − a, p − a] = (p − a)·((b − a) × (c − a))`, positive when `p`
/// lies on the side the normal `(b − a) × (c − a)` points to.
fn side(a: &P3, b: &P3, c: &P3, p: &P3) -> i8 {
    let d = fast::dot(&fast::diff3(p, a), &fast::cross(&fast::diff3(b, a), &fast::diff3(c, a)));
    if let Some(s) = d.signum() {
        return s;
    }
    let q = exact_point;
    let (a, b, c, p) = (q(a), q(b), q(c), q(p));
    sign(&dot(&sub(&p, &a), &cross(&sub(&b, &a), &sub(&c, &a))))
}

/// A checked input's exact value (every finite `f64` is a dyadic rational).
fn exact_point(p: &P3) -> V3 {
    p.map(|x| Q::try_from(x).expect("a checked input is finite"))
}

fn sign(x: &Q) -> i8 {
    match x.cmp(&Q::ZERO) {
        std::cmp::Ordering::Less => -1,
        std::cmp::Ordering::Equal => 0,
        std::cmp::Ordering::Greater => 1,
    }
}

/// Whether `a`, `b`, `c` are collinear (`(b − a) × (c − a) = 0` exactly).
fn collinear(a: &P3, b: &P3, c: &P3) -> bool {
    let x = fast::cross(&fast::diff3(b, a), &fast::diff3(c, a));
    if x.iter().any(|d| d.signum().is_some_and(|s| s != 0)) {
        return false;
    }
    if x.iter().all(|d| d.signum() == Some(0)) {
        return true;
    }
    let q = exact_point;
    is_zero(&cross(&sub(&q(b), &q(a)), &sub(&q(c), &q(a))))
}

/// A `convex` shape's points, checked (at least one, each finite) and each
/// kept once, in their order (−0 and +0 are the same coordinate).
pub(crate) fn distinct_points(points: &[P3], field: &'static str) -> Result<Vec<P3>, RefereeError> {
    if points.is_empty() {
        return Err(RefereeError::NoPoints { field });
    }
    let mut distinct: Vec<P3> = Vec::with_capacity(points.len());
    let mut seen = std::collections::HashSet::with_capacity(points.len());
    for p in points {
        super::exact::check_v3(p, field)?;
        if seen.insert(p.map(|x| if x == 0.0 { 0u64 } else { x.to_bits() })) {
            distinct.push(*p);
        }
    }
    Ok(distinct)
}

thread_local! {
    /// The last two hulls built on this thread, by their points' bits: a
    /// case's two hulls are asked for by the referee and again by the
    /// judge's sizes ([`hull_outline`]).
    static RECENT: std::cell::RefCell<Vec<(Vec<u64>, Convex)>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// How many hulls [`RECENT`] keeps.
const RECENT_HULLS: usize = 2;

/// The exact hull of `points` (at least one, each finite), as the polytope
/// the separating axes and the contact regions work on.
pub(crate) fn convex_hull(points: &[P3], field: &'static str) -> Result<Convex, RefereeError> {
    let key: Vec<u64> = points.iter().flatten().map(|x| x.to_bits()).collect();
    if let Some(hit) = RECENT.with(|r| r.borrow().iter().find(|(k, _)| *k == key).map(|(_, h)| h.clone())) {
        return Ok(hit);
    }
    let hull = computed_hull(points, field)?;
    RECENT.with(|r| {
        let mut r = r.borrow_mut();
        if r.len() == RECENT_HULLS {
            r.remove(0);
        }
        r.push((key, hull.clone()));
    });
    Ok(hull)
}

fn computed_hull(points: &[P3], field: &'static str) -> Result<Convex, RefereeError> {
    let distinct = distinct_points(points, field)?;
    let p0 = distinct[0];
    let Some(i1) = (1..distinct.len()).next() else {
        return Ok(Convex { vertices: vec![v3(&p0, field)?], edges: vec![], directions: vec![], normals: vec![] });
    };
    let p1 = distinct[i1];
    let Some(i2) = (2..distinct.len()).find(|&i| !collinear(&p0, &p1, &distinct[i])) else {
        return segment_hull(&distinct, field);
    };
    let p2 = distinct[i2];
    let Some(i3) = (3..distinct.len()).find(|&i| side(&p0, &p1, &distinct[i2], &distinct[i]) != 0) else {
        return flat_hull(&distinct, &p0, &p1, &p2, field);
    };
    solid_hull(&distinct, [0, i1, i2, i3], field)
}

/// Collinear points: the segment between the two extreme ones (extreme along
/// the coordinate in which the line moves most; every coordinate is monotone
/// along a line, so comparing inputs decides exactly).
fn segment_hull(points: &[P3], field: &'static str) -> Result<Convex, RefereeError> {
    let (p0, p1) = (points[0], points[1]);
    let k = (0..3).fold(0, |k, i| if (p1[i] - p0[i]).abs() > (p1[k] - p0[k]).abs() { i } else { k });
    // p1 − p0 may round, but not to a smaller coordinate's sign: the
    // coordinate of largest rounded difference is one in which they differ.
    let lo = points.iter().min_by(|a, b| a[k].total_cmp(&b[k])).expect("points");
    let hi = points.iter().max_by(|a, b| a[k].total_cmp(&b[k])).expect("points");
    Ok(Convex::of_segment(&v3(lo, field)?, &v3(hi, field)?))
}

/// Coplanar points: their polygon, its plane's normal the face normal.
fn flat_hull(points: &[P3], p0: &P3, p1: &P3, p2: &P3, field: &'static str) -> Result<Convex, RefereeError> {
    let (a, b, c) = (v3(p0, field)?, v3(p1, field)?, v3(p2, field)?);
    let normal = cross(&sub(&b, &a), &sub(&c, &a));
    let exact: Vec<V3> = points.iter().map(|p| v3(p, field)).collect::<Result<_, _>>()?;
    let polygon = hull_2d(&exact, kept(&normal));
    let n = polygon.len();
    let edges: Vec<(usize, usize)> = (0..n).map(|k| (k, (k + 1) % n)).collect();
    let directions = edges.iter().map(|&(i, j)| sub(&polygon[j], &polygon[i])).collect();
    Ok(Convex { vertices: polygon, edges, directions, normals: vec![normal] })
}

/// A full-dimensional hull, incrementally from the tetrahedron `start`.
fn solid_hull(points: &[P3], start: [usize; 4], field: &'static str) -> Result<Convex, RefereeError> {
    // Faces (i, j, k) with outward normal (p_j − p_i) × (p_k − p_i).
    let [i0, i1, i2, i3] = start;
    let mut faces: Vec<[usize; 3]> = Vec::new();
    for (f, opposite) in [([i0, i1, i2], i3), ([i0, i1, i3], i2), ([i0, i2, i3], i1), ([i1, i2, i3], i0)] {
        let s = side(&points[f[0]], &points[f[1]], &points[f[2]], &points[opposite]);
        faces.push(if s > 0 { [f[0], f[2], f[1]] } else { f });
    }
    for (p, x) in points.iter().enumerate() {
        if start.contains(&p) {
            continue;
        }
        let visible: Vec<bool> =
            faces.iter().map(|f| side(&points[f[0]], &points[f[1]], &points[f[2]], x) > 0).collect();
        if !visible.iter().any(|&v| v) {
            continue;
        }
        // Directed edges of the kept faces: a visible face's edge whose
        // reverse belongs to a kept face is on the horizon.
        let mut kept_edges: HashMap<(usize, usize), ()> = HashMap::new();
        for (f, _) in faces.iter().zip(&visible).filter(|(_, v)| !**v) {
            for e in 0..3 {
                kept_edges.insert((f[e], f[(e + 1) % 3]), ());
            }
        }
        let mut next: Vec<[usize; 3]> = Vec::with_capacity(faces.len() + 4);
        for (f, v) in faces.iter().zip(&visible) {
            if !*v {
                next.push(*f);
                continue;
            }
            for e in 0..3 {
                let (u, w) = (f[e], f[(e + 1) % 3]);
                if kept_edges.contains_key(&(w, u)) {
                    next.push([u, w, p]);
                }
            }
        }
        faces = next;
    }
    let mut index: HashMap<usize, usize> = HashMap::new();
    let mut vertices = Vec::new();
    for f in &faces {
        for &i in f {
            if let std::collections::hash_map::Entry::Vacant(e) = index.entry(i) {
                e.insert(vertices.len());
                vertices.push(v3(&points[i], field)?);
            }
        }
    }
    // Each face's outward normal; neighbouring faces in one plane (a box's
    // face split in two triangles) form one facet: the edge between them is
    // no edge of the polytope and is left out, and the facet's normal is
    // kept once.
    let face_normals: Vec<V3> = faces
        .iter()
        .map(|f| {
            let (a, b, c) = (&vertices[index[&f[0]]], &vertices[index[&f[1]]], &vertices[index[&f[2]]]);
            cross(&sub(b, a), &sub(c, a))
        })
        .collect();
    let mut faces_of: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    let mut order: Vec<(usize, usize)> = Vec::new();
    for (k, f) in faces.iter().enumerate() {
        for e in 0..3 {
            let (u, w) = (index[&f[e]], index[&f[(e + 1) % 3]]);
            let key = (u.min(w), u.max(w));
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
    let mut edges: Vec<(usize, usize)> = Vec::new();
    for key in order {
        let shared = &faces_of[&key];
        // Outward normals of two faces of a full-dimensional hull sharing an
        // edge are parallel only when they point the same way: one plane.
        if let [f, g] = shared[..]
            && is_zero(&cross(&face_normals[f], &face_normals[g]))
        {
            let (rf, rg) = (root(&mut facet, f), root(&mut facet, g));
            facet[rf] = rg;
            continue;
        }
        edges.push(key);
    }
    let directions = edges.iter().map(|&(i, j)| sub(&vertices[j], &vertices[i])).collect();
    let normals = (0..faces.len()).filter(|&k| root(&mut facet, k) == k).map(|k| face_normals[k].clone()).collect();
    Ok(Convex { vertices, edges, directions, normals })
}

/// A hull's vertices, edges (vertex index pairs) and unit face normals.
pub type Outline = (Vec<P3>, Vec<(usize, usize)>, Vec<P3>);

/// The exact hull of `points`, rounded for the judge's sizes: its vertices,
/// its edges (vertex index pairs) and its faces' unit normals.
///
/// # Errors
/// As the referee's distance: no points, or a number that is not finite.
pub fn hull_outline(points: &[P3]) -> Result<Outline, RefereeError> {
    let h = convex_hull(points, "points")?;
    let round = |v: &V3| super::exact::round_v(v);
    // Sizes need no correct rounding: each normal is its rounding, normalized
    // in `f64` (a few ulps from the exact unit normal) where its length is
    // finite and far enough above the subnormals that what underflow loses of
    // a component is below an ulp of it; else correctly rounded.
    let unit = |n: &V3| {
        let r = super::exact::round_v(n);
        let len = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        if len.is_finite() && len > f64::MIN_POSITIVE / f64::EPSILON {
            r.map(|x| x / len)
        } else {
            super::exact::round_unit(n)
        }
    };
    let normals = h.normals.iter().filter(|n| !is_zero(n)).map(unit).collect();
    Ok((h.vertices.iter().map(round).collect(), h.edges.clone(), normals))
}
