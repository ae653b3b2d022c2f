//! The verdict's first stage, the problem's own scale: for each field of an
//! answer, the sizes that decide it, from which its allowance is derived (see
//! [`super::tolerance`] for the rules' reasons and [`super::allowance`] for
//! their use).
//!
//! The model is backward error. An engine working in a precision with machine
//! epsilon `ε` is allowed what the exact answer changes by when each input
//! point `x` moves by `ε·‖x‖` (each radius, offset, speed and mass by `ε` of
//! itself), to first order. For each field that change is written as two
//! sizes, both lengths (or radians, or unitless, by the field):
//!
//! - `magnitude`: the sum of the magnitudes the field is built from — the
//!   answer's own value, the centre and radius of the sphere, the vertices of
//!   the triangle weighted by the barycentric coordinates of the answer's point
//!   (a small sphere beside a triangle with legs of 1e15 has a local scale of
//!   its own size, not of the legs). The fixed allowance (`rel`) multiplies it.
//! - `condition`: what ill-conditioning adds (a distance divided by a small
//!   one: a normal from two nearly coincident points, a near-parallel crossing,
//!   the tilt of a sliver's plane). The conditioning allowance (`K·ε`)
//!   multiplies it.
//!
//! Every size is computed with norms that scale before they square (no
//! overflow for coordinates near `f64::MAX`, no underflow for subnormal ones),
//! is never NaN, and is clamped into `[0, f64::MAX]`; an ill-conditioned size
//! that is infinite (a zero distance) is capped by the field's own range where
//! it has one (π for a normal, `t_max` for a time).

use crate::case::{Query, Shape};
use crate::engine::Answer;
use crate::load::LoadedCase;
use crashtest_core::vec3::{cross, dot, max_abs, sub};
use oracle::geom::P3;

/// How nearly a contact normal must be the triangle's face normal (the cosine
/// of the angle between them) for the closest point to count as in the face
/// region, where the plane's tilt moves it: within 1e-6 rad. An edge or vertex
/// contact whose normal is that close to the face's has its centre within 1e-6
/// of the distance over the plane of that feature, where the two regions'
/// allowances meet anyway.
const FACE_REGION_COSINE: f64 = 1.0 - 5e-13;

/// The two sizes of one field (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Size {
    /// Multiplied by the fixed relative allowance.
    pub magnitude: f64,
    /// Multiplied by the conditioning allowance `K·ε`.
    pub condition: f64,
}

impl Size {
    fn new(magnitude: f64, condition: f64) -> Self {
        Size { magnitude: clean(magnitude), condition: clean(condition) }
    }
}

/// The sizes of every field of one case's answer, from the case and the
/// referee's answer. A field that the answer does not have keeps its default
/// (zero sizes: only the floor is allowed).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Local {
    /// The contact, hit, impact or bounding sphere's point; an AABB's corners.
    pub point: Size,
    /// The contact's depth, the bounding sphere's radius.
    pub depth: Size,
    /// The normal, in radians (`magnitude` is 1: the fixed angle allowance).
    pub normal: Size,
    /// The segment parameter or the time of impact (`magnitude`: 1 for a
    /// segment parameter, `t_max` for a time).
    pub t: Size,
    /// Barycentric coordinates (`magnitude`: the coordinates' own size, at least 1).
    pub barycentric: Size,
    /// Response velocities.
    pub velocity: Size,
    /// The referee's margin from the nearest decision boundary (a length).
    pub margin: Size,
    /// The exact contact region on `b`'s surface where the contact point is
    /// not unique (a box face or edge down on a plane, a capsule along a plane,
    /// parallel capsules side by side): a point is judged by its distance to
    /// it, never to one chosen point of it.
    pub region: Option<Region>,
    /// A distance's witness set on `a` where the witnesses are not unique
    /// (`region` holds `b`'s).
    pub region_a: Option<Region>,
}

/// The most vertices a [`Region`] holds.
pub const REGION_VERTICES: usize = 16;

/// A contact region or a set of distance witnesses: a segment (2 vertices) or
/// a convex polygon (3 to [`REGION_VERTICES`], in order: two rectangles
/// clipped have up to eight corners, two hulls' faces more), each vertex the
/// referee's correctly rounded one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Region {
    /// The vertices; the first `len` are used.
    pub vertices: [P3; REGION_VERTICES],
    /// How many (2 to [`REGION_VERTICES`]).
    pub len: usize,
}

impl Default for Region {
    fn default() -> Self {
        Region { vertices: [[0.0; 3]; REGION_VERTICES], len: 0 }
    }
}

impl Region {
    /// The region of the referee's vertices, when it is more than a point. A
    /// polygon of more vertices than a region holds keeps every `k`-th of them
    /// in order: a convex polygon inside the set, so the judge is stricter
    /// there, never more lenient.
    pub(crate) fn of(vertices: &[P3]) -> Option<Region> {
        let n = vertices.len();
        if n < 2 {
            return None;
        }
        let len = n.min(REGION_VERTICES);
        let mut r = Region { vertices: [[0.0; 3]; REGION_VERTICES], len };
        for (k, v) in r.vertices[..len].iter_mut().enumerate() {
            *v = vertices[k * n / len];
        }
        Some(r)
    }

    /// The Euclidean distance from `p` to the region (0 inside it), by
    /// collide's closest points on a segment or on the polygon's triangles,
    /// on the scene scaled by the power of two that brings its largest
    /// coordinate near 1 (exact but where it pushes a coordinate into the
    /// subnormals): at `1e-226` the squares inside the closest-point
    /// computations would underflow to 0, at `1e300` overflow.
    pub fn distance(&self, p: &P3) -> f64 {
        let m = self.vertices[..self.len].iter().chain(std::iter::once(p)).fold(0.0f64, |m, q| m.max(max_abs(*q)));
        if m == 0.0 || !m.is_finite() {
            return self.distance_unscaled(p);
        }
        let e = m.log2().floor() as i32;
        let (d1, d2) = (2f64.powi(-e / 2), 2f64.powi(-e - (-e / 2)));
        let down = |q: &P3| q.map(|x| x * d1 * d2);
        let scaled = Region { vertices: self.vertices.map(|q| down(&q)), len: self.len };
        let (u1, u2) = (2f64.powi(e / 2), 2f64.powi(e - e / 2));
        clean(scaled.distance_unscaled(&down(p)) * u1 * u2)
    }

    fn distance_unscaled(&self, p: &P3) -> f64 {
        use collide::Vec3;
        use collide::contact::{closest_pt_point_segment, closest_pt_point_triangle};
        let v = |q: &P3| Vec3::new(q[0], q[1], q[2]);
        let (pv, vs) = (v(p), self.vertices.map(|q| v(&q)));
        let closest = match self.len {
            2 => vec![closest_pt_point_segment(&pv, &vs[0], &vs[1])],
            n => (1..n - 1)
                .map(|i| closest_pt_point_triangle(&pv, &collide::Triangle::new(vs[0], vs[i], vs[i + 1])))
                .collect(),
        };
        closest.iter().map(|c| distance(p, &[c.x, c.y, c.z])).fold(f64::INFINITY, f64::min)
    }
}

/// The largest ratio a tie's jump is weighed by: a feature that a
/// perturbation of `ε` of the sizes could swap for another (the lowest vertex of
/// a box nearly edge-down, a capsule's lower end when it nearly lies along the
/// plane, the face nearest a centre inside a box) moves the answer by up to the
/// jump; the conditioning allowance `16 ε` times `jump · size / gap` reaches the
/// whole jump at this cap for an `f64` engine, never more.
const TIE_RATIO_CAP: f64 = 1.0 / (16.0 * f64::EPSILON);

/// `jump · size / gap`, the conditioning of a feature that a gap of `gap`
/// separates from the next one, 0 when the gap is exactly 0 (the tie is
/// then in the referee's answer: its region or its flag).
fn tie(jump: f64, size: f64, gap: f64) -> f64 {
    if gap == 0.0 { 0.0 } else { clean(jump * ratio(size, gap).min(TIE_RATIO_CAP)) }
}

/// A box's size: its centre and the sum of its half-extents (the farthest a
/// corner is from the centre, along any axis, is at most that sum).
fn box_size(b: &crate::case::BoxSpec) -> f64 {
    clean(max_abs(b.center) + b.half_extents.iter().map(|h| h.abs()).sum::<f64>())
}

/// A capsule's size: its axis's ends and its radius.
fn capsule_size(c: &oracle::geom::Capsule) -> f64 {
    clean(max_abs(c.start).max(max_abs(c.end)) + c.radius)
}

/// The sphere's centre in the box's frame, `Rᵀ(M − c)`, in f64.
fn in_box_frame(b: &crate::case::BoxSpec, m: &P3) -> P3 {
    let r = b.to_geom().rotation_matrix();
    let (d, k) = diff(m, &b.center);
    [0, 1, 2].map(|j| clean_signed((r[0][j] * d[0] + r[1][j] * d[1] + r[2][j] * d[2]) * k))
}

/// A signed size without NaN, within `±f64::MAX`.
fn clean_signed(x: f64) -> f64 {
    if x.is_nan() { 0.0 } else { x.clamp(-f64::MAX, f64::MAX) }
}

/// The gap between the face nearest `u` (in the box's frame) and the next one:
/// what a centre inside the box must move for its nearest face to change.
fn nearest_face_gap(h: &P3, u: &P3) -> f64 {
    let mut d: Vec<f64> = (0..3).flat_map(|i| [h[i] - u[i], h[i] + u[i]]).collect();
    d.sort_by(f64::total_cmp);
    clean(d[1] - d[0])
}

/// A size as a finite, non-negative number: NaN (which no rule should give)
/// is treated as the largest size, so that it can never make a wrong answer
/// agree by a comparison with NaN.
fn clean(x: f64) -> f64 {
    if x.is_nan() { f64::MAX } else { x.clamp(0.0, f64::MAX) }
}

/// The Euclidean norm, scaled first by the largest coordinate, so that no
/// square under- or overflows. The norm itself can exceed `f64::MAX` (up to
/// `√3` times it) for coordinates near the top of the range: then it is `∞`,
/// which the callers clean to `f64::MAX`.
pub fn norm(v: &P3) -> f64 {
    let m = max_abs(*v);
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    let s = [v[0] / m, v[1] / m, v[2] / m];
    m * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt()
}

/// A difference whose coordinates do not overflow: `a − b` halved when a
/// coordinate of it would (the caller gets the factor back as `scale`).
pub(crate) fn diff(a: &P3, b: &P3) -> (P3, f64) {
    let d = sub(*a, *b);
    if d.iter().all(|x| x.is_finite()) {
        (d, 1.0)
    } else {
        ([a[0] / 2.0 - b[0] / 2.0, a[1] / 2.0 - b[1] / 2.0, a[2] / 2.0 - b[2] / 2.0], 2.0)
    }
}

/// `‖a − b‖` without overflow (finite up to `f64::MAX`, saturating above).
pub fn distance(a: &P3, b: &P3) -> f64 {
    let (d, k) = diff(a, b);
    clean(norm(&d) * k)
}

/// A unit vector along `v` (scaled first), or zero for a zero vector.
fn unit(v: &P3) -> P3 {
    let m = max_abs(*v);
    if m == 0.0 || !m.is_finite() {
        return [0.0; 3];
    }
    let s = [v[0] / m, v[1] / m, v[2] / m];
    let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    [s[0] / n, s[1] / n, s[2] / n]
}

/// The triangle's shape in sizes that do not overflow: the vertices scaled by
/// a power of two (exact) so that the largest coordinate is about 1, then the
/// edges, the twice-area and the three altitudes computed there and scaled back
/// (altitudes are lengths; their ratios to the vertices' sizes are unitless).
struct TriangleShape {
    verts: [P3; 3],
    /// The unit normal `(v1 − v0) × (v2 − v0)` (zero for a zero-area triangle).
    normal: P3,
    /// `alt[i]`: the distance of vertex `i` from the line of the other two
    /// (0 for a zero-area triangle).
    alt: [f64; 3],
}

impl TriangleShape {
    fn new(v: &[P3; 3]) -> Self {
        let m = max_abs(v[0]).max(max_abs(v[1])).max(max_abs(v[2]));
        // A power of two near the largest coordinate: dividing by it is exact
        // unless a coordinate far below it falls into the subnormals (its loss
        // is far below the ε of the sizes computed here).
        let k = if m > 0.0 && m.is_finite() { 2f64.powi(m.log2().floor() as i32) } else { 1.0 };
        let s = v.map(|p| [p[0] / k, p[1] / k, p[2] / k]);
        let n = cross(sub(s[1], s[0]), sub(s[2], s[0]));
        let twice_area = norm(&n);
        let edge = |i: usize, j: usize| norm(&sub(s[i], s[j]));
        let alt_of = |opposite: f64| if opposite > 0.0 { twice_area / opposite * k } else { 0.0 };
        TriangleShape { verts: *v, normal: unit(&n), alt: [alt_of(edge(1, 2)), alt_of(edge(2, 0)), alt_of(edge(0, 1))] }
    }

    /// The tilt of the triangle's plane per ε of vertex motion: `Σ ‖v_i‖/alt_i`
    /// radians (a vertex moved by `ε‖v_i‖` across the plane turns it by that over
    /// its altitude). 0 for a zero-area triangle, which has no plane to tilt:
    /// its answers are those of the segment or point it collapsed to.
    fn tilt(&self) -> f64 {
        #[allow(clippy::float_cmp, reason = "exactly zero marks a triangle without a plane")]
        if self.normal == [0.0; 3] {
            return 0.0;
        }
        clean((0..3).map(|i| if self.alt[i] > 0.0 { max_abs(self.verts[i]) / self.alt[i] } else { f64::MAX }).sum())
    }

    /// The smallest altitude.
    fn min_alt(&self) -> f64 {
        self.alt[0].min(self.alt[1]).min(self.alt[2])
    }

    /// Barycentric weights of the point `p` (taken in the plane), clamped to be
    /// non-negative and to sum to 1: each vertex's share in where `p` is. For a
    /// zero-area triangle, equal shares (the bound then rests on the tilt,
    /// which is infinite there).
    fn weights(&self, p: &P3) -> [f64; 3] {
        let [a, b, c] = self.verts;
        let m = max_abs(a).max(max_abs(b)).max(max_abs(c)).max(max_abs(*p));
        let k = if m > 0.0 && m.is_finite() { 2f64.powi(m.log2().floor() as i32) } else { 1.0 };
        let sc = |q: &P3| [q[0] / k, q[1] / k, q[2] / k];
        let (a, b, c, p) = (sc(&a), sc(&b), sc(&c), sc(p));
        let n = cross(sub(b, a), sub(c, a));
        let nn = dot(n, n);
        if !(nn > 0.0) {
            return [1.0 / 3.0; 3];
        }
        let area = |x: &P3, y: &P3, z: &P3| (dot(cross(sub(*y, *x), sub(*z, *x)), n) / nn).max(0.0);
        let w = [area(&p, &b, &c), area(&a, &p, &c), area(&a, &b, &p)];
        let sum = w[0] + w[1] + w[2];
        if sum > 0.0 { w.map(|x| x / sum) } else { [1.0 / 3.0; 3] }
    }

    /// `Σ w_i ‖v_i‖`: the vertices' sizes in the share the point `p` takes of
    /// each.
    fn weighted_size(&self, p: &P3) -> f64 {
        let w = self.weights(p);
        (0..3).map(|i| w[i] * max_abs(self.verts[i])).sum()
    }

    /// `Σ |λ_i| ‖v_i‖` for signed coordinates `λ` (a barycentric answer).
    fn coords_size(&self, l: &P3) -> f64 {
        (0..3).map(|i| l[i].abs() * max_abs(self.verts[i])).sum()
    }

    /// The distance of `p` from the triangle's plane.
    fn height(&self, p: &P3) -> f64 {
        let (d, k) = diff(p, &self.verts[0]);
        clean(dot(d, self.normal).abs() * k)
    }
}

/// A plane's offset in lengths, `|d|/‖n‖`, and its unit normal, without
/// overflow or underflow for normals of any finite length.
fn plane_offset(normal: &P3, offset: f64) -> (f64, P3) {
    let m = max_abs(*normal);
    if m == 0.0 {
        return (0.0, [0.0; 3]);
    }
    let s = [normal[0] / m, normal[1] / m, normal[2] / m];
    let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    // |d| / (m·n), dividing by the two factors in turn.
    (clean(offset.abs() / n / m), unit(normal))
}

/// A ratio of sizes, `num / den`, with `0/0 = 0` and `x/0 = ∞` (then cleaned
/// or capped by the caller).
fn ratio(num: f64, den: f64) -> f64 {
    if num == 0.0 {
        0.0
    } else if den > 0.0 {
        num / den
    } else {
        f64::INFINITY
    }
}

/// The face of the case's mesh nearest the sphere's centre (in f64, by
/// collide's certified per-face distances; the lowest index on a tie), as a
/// triangle. `None` for an empty mesh.
fn nearest_face(lc: &LoadedCase, s: &crate::case::SphereSpec) -> Option<Shape> {
    let m = lc.meshes[1].as_ref()?;
    let vertices = m.vertices.iter().map(|p| collide::Vec3::new(p[0], p[1], p[2])).collect();
    let mesh = collide::mesh::TriMesh::new(vertices, m.triangles.clone()).ok()?;
    let c = collide::Vec3::new(s.center[0], s.center[1], s.center[2]);
    // Every face within reach: the nearest one is the contact's face.
    let all = collide::Sphere::new(c, f64::MAX);
    let k = collide::mesh::contact_sphere_mesh_nearest_bvh(&all, &collide::mesh::MeshBvh::new(mesh))?;
    let [i, j, l] = *m.triangles.get(k.triangle)?;
    Some(Shape::Triangle(crate::case::TriangleSpec {
        vertices: [m.vertices[i], m.vertices[j], m.vertices[l]],
        velocity: None,
    }))
}

/// The sizes of the case's answer fields, from the case and the referee's
/// answer `truth`.
pub fn local(lc: &LoadedCase, truth: &Answer) -> Local {
    let case = &lc.case;
    match (case.query, &case.a, case.b.as_ref(), truth) {
        // A mesh: the sizes of its face nearest the centre (the face the
        // contact is with), never the whole mesh's.
        (Query::Contact, Shape::Sphere(sp), Some(Shape::Mesh(_)), Answer::Contact(w)) => match nearest_face(lc, sp) {
            Some(face) => contact(&case.a, &face, w.contact.as_ref()),
            None => Local::default(),
        },
        (Query::Contact, a, Some(b), Answer::Contact(w)) => {
            Local { region: contact_region(a, b), ..contact(a, b, w.contact.as_ref()) }
        }
        (Query::Intersect, Shape::Segment(s), Some(Shape::Box(b)), Answer::Intersect(w)) => {
            intersect_box(&s.start, &s.end, b, w.hit.as_ref())
        }
        (Query::Intersect, Shape::Segment(s), Some(Shape::Capsule(c)), Answer::Intersect(w)) => {
            intersect_capsule(&s.start, &s.end, c, w.hit.as_ref())
        }
        (Query::Intersect, Shape::Segment(s), Some(b), Answer::Intersect(w)) => {
            let tri = match b {
                Shape::Triangle(t) => Some(TriangleShape::new(&t.vertices)),
                Shape::Mesh(_) => w.hit.and_then(|h| h.triangle).and_then(|i| {
                    let m = lc.meshes[1].as_ref()?;
                    let f = m.triangles.get(i)?;
                    Some(TriangleShape::new(&[m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]]))
                }),
                _ => None,
            };
            let mesh_size = lc.meshes[1].as_ref().map(|m| m.vertices.iter().copied().map(max_abs).fold(0.0, f64::max));
            intersect(&s.start, &s.end, b, tri.as_ref(), mesh_size, w.hit.as_ref())
        }
        (Query::Barycentric, Shape::Point(p), Some(Shape::Triangle(t)), Answer::Barycentric(w)) => {
            barycentric(&p.at, &TriangleShape::new(&t.vertices), &w.coords)
        }
        (Query::Bounds, _, _, Answer::Bounds(w)) => {
            let pts = crate::load::bounded_points(lc);
            let points = pts.iter().copied().map(max_abs).fold(0.0, f64::max);
            let (center, radius) = w.sphere.map(|s| (max_abs(s.center), s.radius)).unwrap_or((0.0, 0.0));
            let corners = w.aabb.map(|b| max_abs(b.min).max(max_abs(b.max))).unwrap_or(0.0);
            Local {
                // The AABB's coordinates are judged each by its own size (see
                // `judge`); the sphere's centre by the points' sizes.
                point: Size::new(corners.max(center).max(points), 0.0),
                depth: Size::new(radius + center + points, 0.0),
                ..Local::default()
            }
        }
        (Query::Overlap, Shape::Aabb(a), Some(Shape::Aabb(b)), _) => {
            let m = max_abs(a.min).max(max_abs(a.max)).max(max_abs(b.min)).max(max_abs(b.max));
            Local { margin: Size::new(m, 0.0), ..Local::default() }
        }
        (Query::Overlap, Shape::Box(a), Some(b), _) => {
            let m = box_size(a)
                + match b {
                    Shape::Box(b) => box_size(b),
                    Shape::Aabb(b) => max_abs(b.min).max(max_abs(b.max)),
                    _ => 0.0,
                };
            Local { margin: Size::new(m, 0.0), ..Local::default() }
        }
        (Query::Toi, Shape::Sphere(a), Some(b), Answer::Toi(w)) => toi(lc, a, b, w),
        (Query::Response, Shape::Sphere(a), Some(b), Answer::Response(w)) => response(a, b, w),
        (Query::Ccd, a, Some(b), Answer::Ccd(w)) => ccd(a, b, w, lc.case.t_max()),
        (Query::Distance, a, Some(b), Answer::Distance(w)) => {
            let (region_a, region) = distance_regions(a, b).unzip();
            Local { region, region_a, ..distance_sizes(a, b, w) }
        }
        _ => Local::default(),
    }
}

fn contact(a: &Shape, b: &Shape, w: Option<&oracle::geom::Contact>) -> Local {
    let Some(w) = w else {
        // Apart: only the margin (the negative depth) is judged, by the
        // shapes' own sizes.
        let m = contact_margin_size(a, b);
        return Local { margin: m, ..Local::default() };
    };
    if let Some(local) = contact_convex(a, b, w) {
        return local;
    }
    let pm = max_abs(w.point);
    let dm = w.depth.abs();
    match (a, b) {
        (Shape::Sphere(sa), Shape::Sphere(sb)) => {
            let (ca, cb) = (max_abs(sa.center), max_abs(sb.center));
            // The centres' distance (scaled: no overflow near f64's limits).
            let d = distance(&sa.center, &sb.center);
            let spread = ca + cb;
            let turn = ratio(spread, d).min(std::f64::consts::PI / f64::EPSILON);
            let depth = Size::new(sa.radius + sb.radius + spread + dm, 0.0);
            Local {
                point: Size::new(cb + sb.radius + pm, sb.radius * turn),
                depth,
                normal: Size::new(1.0, turn),
                margin: depth,
                ..Local::default()
            }
        }
        (Shape::Sphere(s), Shape::Plane(p)) | (Shape::Plane(p), Shape::Sphere(s)) => {
            let c = max_abs(s.center);
            let (dn, _) = plane_offset(&p.normal, p.offset);
            let depth = Size::new(s.radius + 2.0 * c + 2.0 * dn + dm, 0.0);
            // The point is the centre's projection (on the plane) or the
            // sphere's deepest point: both within the centre, the radius and
            // the offset's sizes.
            let point = Size::new(depth.magnitude + pm + c, 0.0);
            Local { point, depth, normal: Size::new(1.0, 1.0), margin: depth, ..Local::default() }
        }
        (Shape::Sphere(s), Shape::Triangle(t)) | (Shape::Triangle(t), Shape::Sphere(s)) => {
            let tri = TriangleShape::new(&t.vertices);
            let c = max_abs(s.center);
            let h = (s.radius - w.depth).abs();
            let sphere_first = matches!(a, Shape::Sphere(_));
            // The triangle's closest point: the answer's point when the
            // triangle is `b`, else the sphere's centre moved by `h` toward it.
            let q = if sphere_first {
                w.point
            } else {
                [s.center[0] + h * w.normal[0], s.center[1] + h * w.normal[1], s.center[2] + h * w.normal[2]]
            };
            let wq = tri.weighted_size(&q);
            // The plane's tilt moves the closest point only in the face region,
            // where the normal is the face's: at an edge or a vertex the point
            // depends on that feature's own vertices alone (the weights), and a
            // zero-area triangle has no face.
            let across = dot(unit(&w.normal), tri.normal).abs();
            let in_face = across >= FACE_REGION_COSINE;
            let tilt = if in_face && h > 0.0 { h * tri.tilt() } else { 0.0 };
            let q_size = c + wq + max_abs(q);
            let turn = ratio(q_size + tilt, h).min(std::f64::consts::PI / f64::EPSILON);
            let depth = Size::new(s.radius + q_size + dm, tilt);
            let point =
                if sphere_first { Size::new(q_size + pm, tilt) } else { Size::new(c + s.radius + pm, s.radius * turn) };
            Local { point, depth, normal: Size::new(1.0, turn), margin: depth, ..Local::default() }
        }
        (Shape::Sphere(s), Shape::Box(b)) => {
            let size = max_abs(s.center) + s.radius + box_size(b) + pm + dm;
            let depth = Size::new(size, 0.0);
            if w.depth < s.radius {
                // Centre outside: the closest point of the box moves with the
                // inputs (a projection: 1-Lipschitz), the normal turns by the
                // sizes over the centre's distance.
                let turn = ratio(size, s.radius - w.depth).min(std::f64::consts::PI / f64::EPSILON);
                Local { point: depth, depth, normal: Size::new(1.0, turn), margin: depth, ..Local::default() }
            } else {
                // Centre inside: the nearest face decides; a perturbation
                // swaps it for the next within its gap (the point jumps across
                // the box, the normal by a right angle or more).
                let u = in_box_frame(b, &s.center);
                let gap = nearest_face_gap(&b.half_extents, &u);
                let across = 2.0 * b.half_extents.iter().map(|h| h.abs()).sum::<f64>();
                Local {
                    point: Size::new(size, tie(across, size, gap)),
                    depth,
                    normal: Size::new(1.0, tie(1.0, size, gap)),
                    margin: depth,
                    ..Local::default()
                }
            }
        }
        (Shape::Box(b), Shape::Plane(p)) => {
            let (dn, n) = plane_offset(&p.normal, p.offset);
            let size = box_size(b) + 2.0 * dn + pm + dm;
            let depth = Size::new(size, 0.0);
            // The lowest vertex: along each axis nearly parallel to the plane
            // the other end of that edge is within the gap 2hᵢ|n̂·Rᵢ|.
            let r = b.to_geom().rotation_matrix();
            let jumps: f64 = (0..3)
                .map(|i| {
                    let h = b.half_extents[i].abs();
                    let along = (n[0] * r[0][i] + n[1] * r[1][i] + n[2] * r[2][i]).abs();
                    tie(2.0 * h, size, 2.0 * h * along)
                })
                .sum();
            Local {
                point: Size::new(size, jumps),
                depth,
                normal: Size::new(1.0, 1.0),
                margin: depth,
                ..Local::default()
            }
        }
        (Shape::Sphere(s), Shape::Capsule(c)) => {
            let size = max_abs(s.center) + s.radius + capsule_size(c) + pm + dm;
            let turn = ratio(size, s.radius + c.radius - w.depth).min(std::f64::consts::PI / f64::EPSILON);
            let depth = Size::new(size, 0.0);
            Local {
                point: Size::new(size, c.radius * turn),
                depth,
                normal: Size::new(1.0, turn),
                margin: depth,
                ..Local::default()
            }
        }
        (Shape::Capsule(ca), Shape::Capsule(cb)) => {
            let size = capsule_size(ca) + capsule_size(cb) + pm + dm;
            let turn = ratio(size, ca.radius + cb.radius - w.depth).min(std::f64::consts::PI / f64::EPSILON);
            // Nearly parallel axes: the closest pair slides along them by
            // the sizes over the sine of their angle, within b's length.
            let (da, ka) = diff(&ca.end, &ca.start);
            let (db, kb) = diff(&cb.end, &cb.start);
            let (la, lb) = (clean(norm(&da) * ka), clean(norm(&db) * kb));
            let sine = norm(&cross(unit(&da), unit(&db)));
            let slide = if la > 0.0 && lb > 0.0 { tie(lb, size, sine * lb) } else { 0.0 };
            let depth = Size::new(size, 0.0);
            Local {
                point: Size::new(size, clean(cb.radius * turn + slide)),
                depth,
                normal: Size::new(1.0, turn),
                margin: depth,
                ..Local::default()
            }
        }
        (Shape::Capsule(c), Shape::Plane(p)) => {
            let (dn, n) = plane_offset(&p.normal, p.offset);
            let size = capsule_size(c) + 2.0 * dn + pm + dm;
            let (d, k) = diff(&c.end, &c.start);
            let len = clean(norm(&d) * k);
            let jump = tie(len, size, clean(dot(d, n).abs() * k));
            let depth = Size::new(size, 0.0);
            Local {
                point: Size::new(size, jump),
                depth,
                normal: Size::new(1.0, 1.0),
                margin: depth,
                ..Local::default()
            }
        }
        _ => Local::default(),
    }
}

/// The referee's contact region of a box or capsule on a plane, of two
/// capsules, and of a box or capsule on a box or triangle, when it is more
/// than a point (`None` otherwise, and for a case the referee refuses).
pub(crate) fn contact_region(a: &Shape, b: &Shape) -> Option<Region> {
    use oracle::referee;
    let vertices = match (a, b) {
        (Shape::Box(a), Shape::Plane(p)) => referee::contact_region_box_plane(&a.to_geom(), &p.to_geom()),
        (Shape::Capsule(a), Shape::Capsule(b)) => referee::contact_region_capsule_capsule(a, b),
        (Shape::Capsule(a), Shape::Plane(p)) => referee::contact_region_capsule_plane(a, &p.to_geom()),
        (Shape::Box(a), Shape::Box(b)) => referee::contact_region_box_box(&a.to_geom(), &b.to_geom()),
        (Shape::Box(a), Shape::Triangle(t)) => referee::contact_region_box_triangle(&a.to_geom(), &t.to_geom()),
        (Shape::Capsule(a), Shape::Box(b)) => referee::contact_region_capsule_box(a, &b.to_geom()),
        (Shape::Capsule(a), Shape::Triangle(t)) => referee::contact_region_capsule_triangle(a, &t.to_geom()),
        _ => return None,
    };
    Region::of(&vertices.ok()??)
}

/// The plane of the surface at a hit (its normal through its point), whose
/// segment–plane sizes stand for a curved or boxed surface's there; `z = 0`
/// when there is no hit.
fn tangent_plane(w: Option<&oracle::geom::SegmentHit>) -> crate::case::PlaneSpec {
    match w {
        Some(h) => {
            let n = unit(&h.normal);
            crate::case::PlaneSpec { normal: n, offset: dot(n, h.point), velocity: None }
        }
        None => crate::case::PlaneSpec { normal: [0.0, 0.0, 1.0], offset: 0.0, velocity: None },
    }
}

/// A segment's first hit on a box: the entering face's plane plays the
/// surface of [`intersect`], with the box's size at the hit; a hit near an edge
/// or corner (another slab entering within the gap) may enter through the
/// neighbouring face, whose normal is a right angle away.
fn intersect_box(s0: &P3, s1: &P3, b: &crate::case::BoxSpec, w: Option<&oracle::geom::SegmentHit>) -> Local {
    let mut out = intersect(s0, s1, &Shape::Plane(tangent_plane(w)), None, None, w);
    let size = box_size(b) + max_abs(*s0) + max_abs(*s1);
    out.point.magnitude = clean(out.point.magnitude + size);
    // The margin is the segment's distance from the box, or how deep it
    // passes (its least push out): the shapes' sizes, as box–box overlap's,
    // not the tangent plane's (a segment starting inside and running along
    // its nearest face is not a grazing one).
    out.margin = Size::new(clean(size), 0.0);
    if let Some(h) = w {
        // The slabs' entries in the box's frame: the gap between the entering
        // one and the next, as a length along the segment.
        let u0 = in_box_frame(b, s0);
        let u1 = in_box_frame(b, s1);
        let len = distance(s0, s1);
        let mut entries: Vec<f64> = (0..3)
            .filter_map(|i| {
                let d = u1[i] - u0[i];
                (d != 0.0).then(|| {
                    let hi = b.half_extents[i].abs();
                    ((-hi - u0[i]) / d).min((hi - u0[i]) / d)
                })
            })
            .collect();
        entries.sort_by(|x, y| y.total_cmp(x));
        let gap = if h.t == 0.0 {
            nearest_face_gap(&b.half_extents, &u0)
        } else if entries.len() >= 2 {
            clean((entries[0] - entries[1]).abs() * len)
        } else {
            f64::INFINITY
        };
        out.normal.condition = clean(out.normal.condition + tie(1.0, size, gap));
    }
    out
}

/// A segment's first hit on a capsule: as on the plane tangent at the hit
/// (a grazing segment's `t` and point move by the sizes over the sine of its
/// incidence), plus the capsule's own size; the normal, `(hit − foot)/r`,
/// turns by the point's move over `r`.
fn intersect_capsule(s0: &P3, s1: &P3, c: &oracle::geom::Capsule, w: Option<&oracle::geom::SegmentHit>) -> Local {
    let mut out = intersect(s0, s1, &Shape::Plane(tangent_plane(w)), None, None, w);
    let size = capsule_size(c) + max_abs(*s0) + max_abs(*s1);
    out.point.magnitude = clean(out.point.magnitude + size);
    out.margin = Size::new(clean(out.margin.magnitude + size), out.margin.condition);
    if w.is_some() {
        let turn = ratio(out.point.magnitude + out.point.condition, c.radius).min(std::f64::consts::PI / f64::EPSILON);
        out.normal.condition = clean(out.normal.condition + turn);
    }
    out
}

/// The size of a contact's margin (its signed depth) when the referee says
/// apart: the sizes of the shapes the distance is measured between.
fn contact_margin_size(a: &Shape, b: &Shape) -> Size {
    let size = |s: &Shape| match s {
        Shape::Sphere(s) => max_abs(s.center) + s.radius,
        Shape::Plane(p) => plane_offset(&p.normal, p.offset).0,
        Shape::Triangle(t) => t.vertices.iter().copied().map(max_abs).fold(0.0, f64::max),
        Shape::Box(b) => box_size(b),
        Shape::Capsule(c) => capsule_size(c),
        _ => 0.0,
    };
    let tilt = match (a, b) {
        (Shape::Sphere(s), Shape::Triangle(t)) | (Shape::Triangle(t), Shape::Sphere(s)) => {
            let tri = TriangleShape::new(&t.vertices);
            tri.height(&s.center) * tri.tilt()
        }
        // The distance to a sliver's plane tilts with it, from the farther
        // of the axis's ends or the box's centre (plus its reach).
        (Shape::Capsule(c), Shape::Triangle(t)) => {
            let tri = TriangleShape::new(&t.vertices);
            tri.height(&c.start).max(tri.height(&c.end)) * tri.tilt()
        }
        (Shape::Box(b), Shape::Triangle(t)) => {
            let tri = TriangleShape::new(&t.vertices);
            (tri.height(&b.center) + box_size(b)) * tri.tilt()
        }
        _ => 0.0,
    };
    Size::new(size(a) + size(b), tilt)
}

fn intersect(
    s0: &P3,
    s1: &P3,
    b: &Shape,
    tri: Option<&TriangleShape>,
    mesh_size: Option<f64>,
    w: Option<&oracle::geom::SegmentHit>,
) -> Local {
    let (m0, m1) = (max_abs(*s0), max_abs(*s1));
    let len = distance(s0, s1);
    // The surface's unit normal, its offset's size at the hit, and its tilt.
    let (normal, surface, tilt) = match (b, tri) {
        (Shape::Plane(p), _) => {
            let (dn, n) = plane_offset(&p.normal, p.offset);
            (n, dn, 0.0)
        }
        (_, Some(t)) => {
            let at = w.map(|h| h.point).unwrap_or(*s0);
            (t.normal, t.weighted_size(&at), t.tilt())
        }
        // A mesh hit without a face (none reported): its vertices' size.
        _ => ([0.0; 3], mesh_size.unwrap_or(0.0), 0.0),
    };
    let Some(w) = w else {
        let size = m0 + m1 + surface;
        return Local { margin: Size::new(size, len * tilt), ..Local::default() };
    };
    // Each end's signed distance from the surface moves, per ε, by its own
    // size (twice: itself, and the normal's turn acting on it), the surface's
    // offset at the hit, and the tilt acting on its distance from the hit.
    let (d0, d1) = (distance(s0, &w.point), distance(s1, &w.point));
    let h_cond = 2.0 * (m0 + m1) + 2.0 * surface + tilt * (d0 + d1);
    let (dir, k) = diff(s1, s0);
    // Without a known surface normal (a mesh hit whose face is not reported),
    // the whole length counts as across: no near-parallel allowance is given
    // that the data cannot show.
    #[allow(clippy::float_cmp, reason = "exactly zero marks a hit without a reported face")]
    let across = if normal == [0.0; 3] { len } else { clean(dot(dir, normal).abs() * k) };
    // t = h0/(h0 − h1): moved by (δh0 + δh1)/|h0 − h1|, |h0 − h1| the
    // segment's extent across the surface.
    let t_cond = ratio(h_cond, across).min(1.0 / f64::EPSILON);
    let pm = max_abs(w.point);
    let point = Size::new(m0 + m1 + pm + surface, (t_cond * len).min(f64::MAX));
    let mut out = Local {
        point,
        t: Size::new(1.0, t_cond),
        normal: Size::new(1.0, tilt.min(std::f64::consts::PI / f64::EPSILON)),
        margin: Size::new(point.magnitude, point.condition),
        ..Local::default()
    };
    if let (Some(t), Some(l)) = (tri, w.barycentric) {
        let moved = point.magnitude + point.condition + t.coords_size(&l);
        let size = l.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
        out.barycentric = Size::new(size, ratio(moved, t.min_alt()));
    }
    out
}

fn barycentric(p: &P3, t: &TriangleShape, l: &P3) -> Local {
    // A coordinate is an area over the whole: moving the point by δ changes
    // it by δ/altitude, moving a vertex j by δ_j by |λ_j| δ_j/altitude, and a
    // point at height D off the plane moves its projection by D times the
    // plane's tilt.
    let height = t.height(p);
    let moved = max_abs(*p) + t.coords_size(l) + height * t.tilt();
    let size = l.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    Local { barycentric: Size::new(size, ratio(moved, t.min_alt())), ..Local::default() }
}

/// The sizes of a contact at `t = 0`: the static contact's of the shapes as
/// they stand ([`contact`]; a mesh's face nearest the centre), from the
/// referee's point and normal at `t = 0` and the signed depth they give —
/// so that the same answer gets the same verdict as a time of impact at
/// `t = 0` and as a contact (see `judge::toi_allowance` for what motion adds).
fn contact_at_start(lc: &LoadedCase, a: &crate::case::SphereSpec, b: &Shape, h: &oracle::geom::Toi) -> Local {
    let sphere = Shape::Sphere(crate::case::SphereSpec { velocity: None, mass: None, ..a.clone() });
    // The signed depth in f64 (a size needs no more): the radius less the
    // centre's signed distance from the point on b's surface along the normal
    // (for a plane, from the plane itself).
    let along = |q: &P3| {
        let (d, k) = diff(&a.center, q);
        let along = dot(d, h.normal);
        clean(along.abs() * k) * along.signum()
    };
    let depth = match b {
        // A box's point is on the face the normal leaves (a centre inside
        // it is behind that face: the depth is r plus the distance).
        Shape::Sphere(_) | Shape::Plane(_) | Shape::Box(_) => a.radius - along(&h.point),
        _ => a.radius - distance(&a.center, &h.point),
    };
    let c = oracle::geom::Contact { point: h.point, normal: h.normal, depth };
    match b {
        Shape::Mesh(_) => match nearest_face(lc, a) {
            Some(face) => contact(&sphere, &face, Some(&c)),
            None => Local::default(),
        },
        _ => contact(&sphere, b, Some(&c)),
    }
}

fn toi(lc: &LoadedCase, a: &crate::case::SphereSpec, b: &Shape, w: &oracle::geom::ToiAnswer) -> Local {
    if let Some(h) = &w.toi
        && h.t == 0.0
    {
        let t_max = lc.case.t_max();
        return Local { t: Size::new(t_max, 0.0), ..contact_at_start(lc, a, b, h) };
    }
    let va = a.velocity.unwrap_or_default();
    let vb = b.velocity();
    let t_max = lc.case.t_max();
    let b_size = match b {
        Shape::Sphere(s) => max_abs(s.center) + s.radius,
        Shape::Plane(p) => plane_offset(&p.normal, p.offset).0,
        Shape::Triangle(t) => match w.toi {
            // The triangle's share at the impact point, taken back to t = 0.
            Some(h) => {
                let s = h.t;
                let at = [h.point[0] - vb[0] * s, h.point[1] - vb[1] * s, h.point[2] - vb[2] * s];
                TriangleShape::new(&t.vertices).weighted_size(&at) + max_abs(at)
            }
            None => t.vertices.iter().copied().map(max_abs).fold(0.0, f64::max),
        },
        Shape::Mesh(_) => {
            lc.meshes[1].as_ref().map(|m| m.vertices.iter().copied().map(max_abs).fold(0.0, f64::max)).unwrap_or(0.0)
        }
        // Its corners' reach: an engine's rotation rounds them at this size.
        Shape::Box(bx) => max_abs(bx.center) + bx.half_extents.iter().map(|h| h.abs()).sum::<f64>(),
        _ => 0.0,
    };
    let moving = max_abs(va) + max_abs(vb);
    // The sizes at the impact (or, without one, over the whole interval): the
    // shapes have moved by then.
    let (until, at) = match w.toi {
        Some(h) => (h.t.abs(), max_abs(h.point)),
        None => (t_max, 0.0),
    };
    let reach = Size::new(max_abs(a.center) + a.radius + b_size + at + moving * until, 0.0);
    Local { point: reach, margin: reach, t: Size::new(t_max, 0.0), normal: Size::new(1.0, 0.0), ..Local::default() }
}

/// A `ccd` answer's time: its magnitude is `t_max` (as a `toi`'s), and its
/// condition is how far the first root of the coplanarity cubic
/// `f(t) = det[B, C, P](t)` moves when every input position moves by `ε` of the
/// largest one, `X`: each column (a difference of two positions, at any time a
/// convex combination of the ends) moves by at most `2εX`, so `f` by at most
/// `2εX·(‖B‖‖C‖ + ‖C‖‖P‖ + ‖B‖‖P‖)`, and the root by that over `|f′(t*)|`. A
/// tangent root (`f′(t*) = 0`) and coplanar motion (the referee's degenerate
/// flag: `f ≡ 0`, where any perturbation of the inputs moves the first time
/// anywhere in the interval) are capped by `t_max`. The cubic is taken in f64
/// on the positions scaled by a power of two (exact) so that the largest is
/// about 1: a size, not a decision.
fn ccd(a: &Shape, b: &Shape, w: &oracle::geom::CcdAnswer, t_max: f64) -> Local {
    let t_size = match w.t {
        Some(t) if !w.degenerate => {
            let cond = ccd_columns(a, b).map_or(f64::INFINITY, |(x, cols)| {
                let at = |k: usize| {
                    let (c0, c1) = cols[k];
                    let p = [0, 1, 2].map(|i| c0[i] + t * (c1[i] - c0[i]));
                    (p, sub(c1, c0))
                };
                let ((bb, db), (cc, dc), (pp, dp)) = (at(0), at(1), at(2));
                let det = |u: P3, v: P3, w: P3| dot(cross(u, v), w);
                let slope = (det(db, cc, pp) + det(bb, dc, pp) + det(bb, cc, dp)).abs();
                let (nb, nc, np) = (norm(&bb), norm(&cc), norm(&pp));
                ratio(2.0 * x * (nb * nc + nc * np + nb * np), slope)
            });
            Size::new(t_max, cond.min(t_max / f64::EPSILON))
        }
        Some(_) => Size::new(t_max, t_max / f64::EPSILON),
        None => Size::new(t_max, 0.0),
    };
    Local { t: t_size, ..Local::default() }
}

/// The columns `B, C, P` of a `ccd` case's coplanarity determinant, each at
/// `t = 0` and `t = 1`, with the positions scaled by a power of two so that the
/// largest coordinate is in `[1, 2)`, and that scale `X` in the scaled units
/// (so about 1). `None` for shapes that are not a `ccd` pair, or all zero.
fn ccd_columns(a: &Shape, b: &Shape) -> Option<(f64, [(P3, P3); 3])> {
    // Vertex–face: B = v1 − v0, C = v2 − v0, P = p − v0. Edge–edge:
    // B = a1 − a0, C = b0 − a0, P = b1 − a0.
    let (origin, rest): ([P3; 2], [[P3; 2]; 3]) = match (a, b) {
        (Shape::MovingPoint(p), Shape::MovingTriangle(t)) => {
            ([t.t0[0], t.t1[0]], [[t.t0[1], t.t1[1]], [t.t0[2], t.t1[2]], [p.t0, p.t1]])
        }
        (Shape::MovingSegment(a), Shape::MovingSegment(b)) => {
            ([a.t0[0], a.t1[0]], [[a.t0[1], a.t1[1]], [b.t0[0], b.t1[0]], [b.t0[1], b.t1[1]]])
        }
        _ => return None,
    };
    let m = rest.iter().flatten().chain(&origin).copied().map(max_abs).fold(0.0, f64::max);
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    // A power of two, in two halves so that neither overflows for a subnormal
    // `m`: scaling by it is exact (but for subnormal results, far below what a
    // size needs).
    let e = -(m.log2().floor() as i32);
    let (k1, k2) = (2f64.powi(e / 2), 2f64.powi(e - e / 2));
    let s = |p: P3| p.map(|x| x * k1 * k2);
    let col = |q: [P3; 2]| (sub(s(q[0]), s(origin[0])), sub(s(q[1]), s(origin[1])));
    Some((m * k1 * k2, rest.map(col)))
}

fn response(a: &crate::case::SphereSpec, b: &Shape, w: &oracle::geom::ResponseAnswer) -> Local {
    let va = a.velocity.unwrap_or_default();
    let vb = b.velocity();
    let (v, k) = diff(&va, &vb);
    let rel = clean(norm(&v) * k);
    let size = max_abs(va) + max_abs(vb) + max_abs(w.velocity_a) + max_abs(w.velocity_b);
    // The impulse acts along the normal; a normal from two centres turns by
    // (‖ca‖ + ‖cb‖)/‖ca − cb‖ per ε, and the change of velocity (up to twice
    // the relative one) turns with it. A plane's normal is an input.
    let turn = match b {
        Shape::Sphere(sb) => ratio(max_abs(a.center) + max_abs(sb.center), distance(&a.center, &sb.center))
            .min(std::f64::consts::PI / f64::EPSILON),
        _ => 1.0,
    };
    Local { velocity: Size::new(size, 2.0 * rel * turn), ..Local::default() }
}

/// The scene's scale: the largest magnitude among the case's coordinates, radii and
/// plane offsets (offsets in units of the normal's length), or 1 for an empty or
/// all-zero scene. Errors of lengths are divided by it.
pub fn scene_scale(lc: &LoadedCase) -> f64 {
    let mut m: f64 = 0.0;
    let mut p3 = |p: &P3| m = p.iter().fold(m, |m, x| m.max(x.abs()));
    let mut scalars = Vec::new();
    for (slot, shape) in [Some(&lc.case.a), lc.case.b.as_ref()].into_iter().enumerate() {
        match shape {
            Some(Shape::Sphere(s)) => {
                p3(&s.center);
                scalars.push(s.radius);
            }
            Some(Shape::Plane(p)) => {
                let n = p.normal.iter().map(|x| x * x).sum::<f64>().sqrt();
                if n > 0.0 && n.is_finite() {
                    scalars.push(p.offset / n);
                }
            }
            Some(Shape::Segment(s)) => {
                p3(&s.start);
                p3(&s.end);
            }
            Some(Shape::Triangle(t)) => t.vertices.iter().for_each(&mut p3),
            Some(Shape::Point(p)) => p3(&p.at),
            Some(Shape::Points(p)) => p.points.iter().for_each(&mut p3),
            Some(Shape::Mesh(_)) => {
                if let Some(mesh) = &lc.meshes[slot] {
                    mesh.vertices.iter().for_each(&mut p3);
                }
            }
            Some(Shape::Aabb(b)) => {
                p3(&b.min);
                p3(&b.max);
            }
            Some(Shape::MovingPoint(p)) => {
                p3(&p.t0);
                p3(&p.t1);
            }
            Some(Shape::MovingSegment(s)) => s.t0.iter().chain(&s.t1).for_each(&mut p3),
            Some(Shape::MovingTriangle(t)) => t.t0.iter().chain(&t.t1).for_each(&mut p3),
            Some(Shape::Box(b)) => {
                p3(&b.center);
                p3(&b.half_extents);
            }
            Some(Shape::Capsule(c)) => {
                p3(&c.start);
                p3(&c.end);
                scalars.push(c.radius);
            }
            Some(Shape::Convex(c)) => c.points.iter().for_each(&mut p3),
            None => {}
        }
    }
    let m = scalars.iter().fold(m, |m, x| m.max(x.abs()));
    if m > 0.0 && m.is_finite() { m } else { 1.0 }
}

/// The length scale of a case's answer, for relative errors in reports: the
/// magnitude of the sizes its point, depth and margin are judged by (at least
/// the smallest positive number, never 0).
pub fn answer_scale(lc: &LoadedCase, truth: &Answer) -> f64 {
    let l = local(lc, truth);
    let m = l.point.magnitude.max(l.depth.magnitude).max(l.margin.magnitude).max(l.velocity.magnitude);
    if m > 0.0 && m.is_finite() {
        m
    } else if m > 0.0 {
        f64::MAX
    } else {
        scene_scale(lc)
    }
}

// --- Box–box, box–triangle, capsule–box and capsule–triangle contact -------------
//
// Sizes of box–box, box–triangle, capsule–box and capsule–triangle contact:
// the shapes' own sizes, and what conditions the separating axis the
// referee's answer stands on.
//
// - **A cross-product axis** `aᵢ × bⱼ` of two edges at a small angle `θ`
//   turns by `ε/sin θ` when the edges turn by `ε`: the normal's condition is
//   `1/sin θ`, and the depth and the point (which project along it) move by
//   the sizes over `sin θ`.
// - **A near tie**: the next-least push in another direction within `gap` of
//   the least could take over under a perturbation; the normal then jumps (by
//   up to 2, the chord between unit normals) and the point across the shapes,
//   weighed as the other pairs weigh a tie (`tie`).
// - **Nearly collinear edges**: a corner of the region where an edge of `a`
//   crosses one of `b` slides along them by the sizes over the sine of
//   their angle, within the shorter edge; edges on one line decide between
//   a stretch and a point.
// - **A capsule apart from the solid** (its axis at distance `d > 0`): the
//   normal turns by the sizes over `d` (as sphere–capsule), and an axis nearly
//   parallel to a face slides its closest point along its length (as
//   capsule–capsule).
//
// The pushes are computed in `f64` on the scene scaled by a power of two to
// unit size (no square overflows or underflows), for sizes only: the answer
// is the referee's.

/// A polytope in `f64`, scaled: its vertices, edge directions and face normals.
struct Poly {
    vertices: Vec<P3>,
    /// Edges as pairs of vertex indices.
    edges: Vec<(usize, usize)>,
    directions: Vec<P3>,
    normals: Vec<P3>,
}

fn scaled(p: &P3, k: f64) -> P3 {
    p.map(|x| x * k)
}

fn of_box(b: &crate::case::BoxSpec, k: f64) -> Poly {
    let r = b.to_geom().rotation_matrix();
    let axes: Vec<P3> = (0..3).map(|j| [r[0][j], r[1][j], r[2][j]]).collect();
    let c = scaled(&b.center, k);
    let h = b.half_extents.map(|x| x.abs() * k);
    let vertices = (0..8usize)
        .map(|s| {
            std::array::from_fn(|i| {
                c[i] + (0..3).map(|j| if s >> j & 1 == 1 { h[j] } else { -h[j] } * axes[j][i]).sum::<f64>()
            })
        })
        .collect();
    let edges =
        (0..8usize).flat_map(|s| (0..3).filter(move |i| s >> i & 1 == 0).map(move |i| (s, s | 1 << i))).collect();
    Poly { vertices, edges, directions: axes.clone(), normals: axes }
}

fn of_triangle(v: &[P3; 3], k: f64) -> Poly {
    let v = v.map(|p| scaled(&p, k));
    let directions = vec![sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])];
    let normals = vec![cross(sub(v[1], v[0]), sub(v[2], v[0]))];
    Poly { vertices: v.to_vec(), edges: vec![(0, 1), (1, 2), (2, 0)], directions, normals }
}

fn of_segment(p0: &P3, p1: &P3, k: f64) -> Poly {
    let (p0, p1) = (scaled(p0, k), scaled(p1, k));
    Poly { vertices: vec![p0, p1], edges: vec![(0, 1)], directions: vec![sub(p1, p0)], normals: vec![] }
}

/// A push in `f64`: its amount over `‖L‖`, its unit direction, and the sine
/// of the angle of the two edges it crosses (1 for a face normal).
struct Push {
    amount: f64,
    direction: P3,
    sine: f64,
}

fn pushes(a: &Poly, b: &Poly) -> Vec<Push> {
    let mut axes: Vec<(P3, f64)> = a.normals.iter().chain(&b.normals).map(|n| (*n, 1.0)).collect();
    for da in &a.directions {
        for db in &b.directions {
            let l = cross(*da, *db);
            let (ua, ub) = (unit(da), unit(db));
            axes.push((l, norm(&cross(ua, ub))));
        }
    }
    let project = |p: &Poly, u: &P3| {
        p.vertices
            .iter()
            .map(|v| dot(*u, *v))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)))
    };
    let mut out = Vec::new();
    for (l, sine) in axes {
        let u = unit(&l);
        if u.iter().all(|x| *x == 0.0) {
            continue;
        }
        let ((lo_a, hi_a), (lo_b, hi_b)) = (project(a, &u), project(b, &u));
        out.push(Push { amount: hi_b - lo_a, direction: u, sine });
        out.push(Push { amount: hi_a - lo_b, direction: u.map(|x| -x), sine });
    }
    out
}

/// The least push's sine, and the gap to the next least in another direction
/// (`f64::MAX` when there is none), unscaled by `1/k`.
fn least_and_gap(a: &Poly, b: &Poly, k: f64) -> (f64, f64) {
    let mut all = pushes(a, b);
    all.sort_by(|x, y| x.amount.total_cmp(&y.amount));
    let Some(least) = all.first() else { return (1.0, f64::MAX) };
    let other = all[1..].iter().find(|p| dot(p.direction, least.direction) < SAME_PUSH_COSINE);
    let gap = other.map_or(f64::MAX, |p| clean((p.amount - least.amount) / k));
    (least.sine, gap)
}

/// The power of two that brings the largest coordinate of `points` near 1.
fn unit_scale(points: &[P3]) -> f64 {
    let m = points.iter().copied().map(max_abs).fold(0.0, f64::max);
    if m == 0.0 || !m.is_finite() { 1.0 } else { 2f64.powi(-(m.log2().floor() as i32)) }
}

/// Two pushes go the same way when their unit directions' cosine is at least
/// this (within 1.4e-6 rad: parallel candidate axes, such as `aᵢ × bⱼ`
/// along one of `a`'s own axes, computed in `f64`); a push any further off
/// is another direction, whose gap to the least is a tie's.
const SAME_PUSH_COSINE: f64 = 1.0 - 1e-12;

/// The scene is scaled to a largest coordinate near 1, then by this more,
/// so that a box's corners (its centre plus three half-extents) stay below
/// 4 and no product of two of them overflows or loses its scale.
const SCENE_HEADROOM: f64 = 4.0;

/// How far a corner of the region can slide: where an edge of `a` and an
/// edge of `b` nearly on one line overlap, a perturbation decides whether
/// the one runs inside or outside the other's face, and the region is their
/// shared stretch or one point (a capsule's axis along a triangle's edge);
/// crossing at a small angle `θ`, their crossing moves by the sizes over
/// `sin θ`. Weighed as a tie of the shorter edge's length with the gap
/// `max(sin θ · length, the edges' distance)`: edges side by side (parallel
/// faces of two boxes) are as far from crossing as they are apart.
fn slide(a: &Poly, b: &Poly, k: f64, size: f64) -> f64 {
    let mut worst = 0.0f64;
    for &(i, j) in &a.edges {
        let (p0, p1) = (a.vertices[i], a.vertices[j]);
        for &(m, n) in &b.edges {
            let (q0, q1) = (b.vertices[m], b.vertices[n]);
            let (da, db) = (sub(p1, p0), sub(q1, q0));
            let len = clean(norm(&da).min(norm(&db)) / k);
            if len == 0.0 {
                continue;
            }
            let sine = norm(&cross(unit(&da), unit(&db)));
            let apart = segment_distance(&p0, &p1, &q0, &q1) / k;
            worst = worst.max(tie(len, size, clean((sine * len).max(apart))));
        }
    }
    worst
}

/// The distance between segments `[p0, p1]` and `[q0, q1]` in plain `f64`
/// (Ericson's closest points of two segments, §5.1.9), for sizes only.
fn segment_distance(p0: &P3, p1: &P3, q0: &P3, q1: &P3) -> f64 {
    let (d1, d2, r) = (sub(*p1, *p0), sub(*q1, *q0), sub(*p0, *q0));
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    let (mut s, mut t);
    if a == 0.0 && e == 0.0 {
        (s, t) = (0.0, 0.0);
    } else if a == 0.0 {
        (s, t) = (0.0, (f / e).clamp(0.0, 1.0));
    } else {
        let c = dot(d1, r);
        if e == 0.0 {
            (s, t) = ((-c / a).clamp(0.0, 1.0), 0.0);
        } else {
            let b = dot(d1, d2);
            let denom = a * e - b * b;
            s = if denom > 0.0 { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
            t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
        }
    }
    let at = |o: &P3, d: &P3, x: f64| [o[0] + d[0] * x, o[1] + d[1] * x, o[2] + d[2] * x];
    clean(norm(&sub(at(p0, &d1, s), at(q0, &d2, t))))
}

/// The sizes of a contact between polytopes `a` and `b` (a capsule's axis
/// when it meets the solid), `size` the shapes' and the answer's sizes.
fn resting(a: &Poly, b: &Poly, k: f64, size: f64, across: f64) -> Local {
    let (sine, gap) = least_and_gap(a, b, k);
    let turn = ratio(1.0, sine).min(std::f64::consts::PI / f64::EPSILON);
    let depth = Size::new(size, clean(size * (turn - 1.0)));
    Local {
        point: Size::new(size, clean(size * (turn - 1.0) + tie(across, size, gap) + slide(a, b, k, size))),
        depth,
        normal: Size::new(1.0, clean(turn + tie(2.0, size, gap))),
        margin: depth,
        ..Local::default()
    }
}

fn triangle_size(v: &[P3; 3]) -> f64 {
    v.iter().copied().map(max_abs).fold(0.0, f64::max)
}

/// The sizes of the four pairs; `None` for another pair.
fn contact_convex(a: &Shape, b: &Shape, w: &oracle::geom::Contact) -> Option<Local> {
    let extra = max_abs(w.point) + w.depth.abs();
    Some(match (a, b) {
        (Shape::Box(ba), Shape::Box(bb)) => {
            let k = unit_scale(&[ba.center, ba.half_extents, bb.center, bb.half_extents]) / SCENE_HEADROOM;
            let (pa, pb) = (of_box(ba, k), of_box(bb, k));
            let size = clean(box_size(ba) + box_size(bb) + extra);
            resting(&pa, &pb, k, size, size)
        }
        (Shape::Box(ba), Shape::Triangle(t)) => {
            let k =
                unit_scale(&[ba.center, ba.half_extents, t.vertices[0], t.vertices[1], t.vertices[2]]) / SCENE_HEADROOM;
            let (pa, pb) = (of_box(ba, k), of_triangle(&t.vertices, k));
            let size = clean(box_size(ba) + triangle_size(&t.vertices) + extra);
            resting(&pa, &pb, k, size, size)
        }
        (Shape::Capsule(c), Shape::Box(_) | Shape::Triangle(_)) => {
            let (k, pb, b_size) = match b {
                Shape::Box(bb) => {
                    let k = unit_scale(&[c.start, c.end, bb.center, bb.half_extents]) / SCENE_HEADROOM;
                    (k, of_box(bb, k), box_size(bb))
                }
                Shape::Triangle(t) => {
                    let k = unit_scale(&[c.start, c.end, t.vertices[0], t.vertices[1], t.vertices[2]]) / SCENE_HEADROOM;
                    (k, of_triangle(&t.vertices, k), triangle_size(&t.vertices))
                }
                _ => return None,
            };
            let size = clean(capsule_size(c) + b_size + extra);
            let pa = of_segment(&c.start, &c.end, k);
            let d = c.radius - w.depth;
            if d > 0.0 {
                // The axis apart from the solid: the closest pair's normal
                // turns by the sizes over d; near parallel to a face, the
                // closest point slides along the axis.
                let turn = ratio(size, d).min(std::f64::consts::PI / f64::EPSILON);
                let axis = sub(pa.vertices[1], pa.vertices[0]);
                let len = clean(norm(&axis) / k);
                let slide = tie(len, size, clean(dot(axis, unit(&w.normal)).abs() / k));
                let depth = Size::new(size, 0.0);
                Local {
                    point: Size::new(size, clean(size * turn + slide)),
                    depth,
                    normal: Size::new(1.0, turn),
                    margin: depth,
                    ..Local::default()
                }
            } else {
                resting(&pa, &pb, k, size, size)
            }
        }
        _ => return None,
    })
}

// Distance (`docs/FORMAT.md`, "Distance"): every solid is a polytope (its
// core) grown by a radius, and the answer's sizes are those of the cores':
//
// - **Cores apart** (`distance + r > 0`, `r` the radii's sum): the distance is
//   as well-conditioned as a distance is (moving every input by ε of the
//   shapes' size moves it by at most 2ε of that size); the normal turns by the
//   sizes over the cores' distance, as a capsule apart from a box; the
//   witnesses move with it, and where two of a core's vertices are nearly as
//   low along the normal (faces nearly parallel), a perturbation swaps them:
//   a tie of the core's extent with their height gap.
// - **Cores meeting**: the sizes of a resting contact of the two polytopes
//   (`resting`: the least push's edge angle, its gap to the next push in
//   another direction, the region's slide), plus the same support ties.
// - **A plane** (`b`): its normal is an input; the witness ties as above.

/// The referee's other answers to `lc` where its least push is reached in
/// several directions (`oracle::referee::distance_alternatives`), each with
/// its sizes and witness sets; empty for every other case.
pub fn alternatives(lc: &LoadedCase, truth: &Answer) -> Vec<(Answer, Local)> {
    let (Query::Distance, Some(b), Answer::Distance(w)) = (lc.case.query, lc.case.b.as_ref(), truth) else {
        return Vec::new();
    };
    if !w.degenerate {
        return Vec::new();
    }
    let a = &lc.case.a;
    let (Ok(sa), Ok(sb)) = (crate::engine::SolidValue::of(a), crate::engine::SolidValue::of(b)) else {
        return Vec::new();
    };
    let Ok(alts) = oracle::referee::distance_alternatives(sa.solid(), sb.solid()) else { return Vec::new() };
    alts.into_iter()
        .map(|(alt, witnesses)| {
            let (region_a, region) = witnesses.and_then(|(wa, wb)| Some((Region::of(&wa)?, Region::of(&wb)?))).unzip();
            let sizes = Local { region, region_a, ..distance_sizes(a, b, &alt) };
            (Answer::Distance(alt), sizes)
        })
        .collect()
}

/// The referee's witness sets of a distance case, `a`'s and `b`'s, where the
/// witnesses are not unique.
pub(crate) fn distance_regions(a: &Shape, b: &Shape) -> Option<(Region, Region)> {
    let (a, b) = (crate::engine::SolidValue::of(a).ok()?, crate::engine::SolidValue::of(b).ok()?);
    let (wa, wb) = oracle::referee::distance_witnesses(a.solid(), b.solid()).ok()??;
    Some((Region::of(&wa)?, Region::of(&wb)?))
}

/// The core of a solid in `f64`, scaled by `k`, with its radius (unscaled).
/// A hull's faces and edges are built only when `faces` asks (the resting
/// sizes of meeting cores); otherwise its points stand for its vertices.
fn core_of(s: &Shape, k: f64, faces: bool) -> Option<(Poly, f64)> {
    Some(match s {
        Shape::Sphere(x) => (
            Poly { vertices: vec![scaled(&x.center, k)], edges: vec![], directions: vec![], normals: vec![] },
            x.radius,
        ),
        Shape::Capsule(c) => (of_segment(&c.start, &c.end, k), c.radius),
        Shape::Box(b) => (of_box(b, k), 0.0),
        Shape::Triangle(t) => (of_triangle(&t.vertices, k), 0.0),
        Shape::Convex(c) if !faces => {
            let vertices = c.points.iter().map(|v| scaled(v, k)).collect();
            (Poly { vertices, edges: vec![], directions: vec![], normals: vec![] }, 0.0)
        }
        Shape::Convex(c) => {
            let (vertices, edges, normals) = oracle::referee::hull::hull_outline(&c.points).ok()?;
            let vertices: Vec<P3> = vertices.iter().map(|v| scaled(v, k)).collect();
            let directions = edges.iter().map(|&(i, j)| sub(vertices[j], vertices[i])).collect();
            (Poly { vertices, edges, directions, normals }, 0.0)
        }
        _ => return None,
    })
}

/// The points that set a solid's scale (for the power-of-two scaling).
fn anchor_points(s: &Shape) -> Vec<P3> {
    match s {
        Shape::Sphere(x) => vec![x.center, [x.radius; 3]],
        Shape::Capsule(c) => vec![c.start, c.end, [c.radius; 3]],
        Shape::Box(b) => vec![b.center, b.half_extents],
        Shape::Triangle(t) => t.vertices.to_vec(),
        Shape::Convex(c) => c.points.clone(),
        Shape::Plane(p) => vec![p.normal],
        _ => vec![],
    }
}

/// A solid's size: its core's largest coordinate plus its radius (unscaled).
fn solid_size(core: &Poly, r: f64, k: f64) -> f64 {
    clean(core.vertices.iter().copied().map(max_abs).fold(0.0, f64::max) / k + r)
}

/// The witness tie of a core along `n` (unit, pointing away from the core's
/// witness side when `lowest`): its extent over the gap between its lowest
/// two heights, unscaled.
fn support_tie(core: &Poly, n: &P3, lowest: bool, k: f64, size: f64) -> f64 {
    let mut h: Vec<f64> = core.vertices.iter().map(|v| if lowest { dot(*n, *v) } else { -dot(*n, *v) }).collect();
    if h.len() < 2 {
        return 0.0;
    }
    h.sort_by(f64::total_cmp);
    // The extent by the bounding box's diagonal: at most √3 times the
    // diameter, in one pass (a hull of a thousand points has a million pairs).
    let (lo, hi) = core.vertices.iter().fold(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]), |(lo, hi), v| {
        ([0, 1, 2].map(|i| lo[i].min(v[i])), [0, 1, 2].map(|i| hi[i].max(v[i])))
    });
    let extent = norm(&sub(hi, lo));
    // The first height that differs from the least: ties exactly at the
    // least are the referee's region.
    let gap = h.iter().map(|x| x - h[0]).find(|g| *g > 0.0).unwrap_or(0.0);
    tie(clean(extent / k), size, clean(gap / k))
}

fn distance_sizes(a: &Shape, b: &Shape, w: &oracle::geom::DistanceAnswer) -> Local {
    let mut anchors = anchor_points(a);
    anchors.extend(anchor_points(b));
    let k = unit_scale(&anchors) / SCENE_HEADROOM;
    let meeting = |ra: f64, rb: f64| w.distance + ra + rb <= 0.0;
    let radius = |s: &Shape| match s {
        Shape::Sphere(x) => x.radius,
        Shape::Capsule(c) => c.radius,
        _ => 0.0,
    };
    let faces = meeting(radius(a), radius(b));
    let Some((pa, ra)) = core_of(a, k, faces) else { return Local::default() };
    let extra = max_abs(w.point_a).max(max_abs(w.point_b)) + w.distance.abs();
    if let Shape::Plane(p) = b {
        let size = clean(solid_size(&pa, ra, k) + ratio(p.offset.abs(), norm(&p.normal)) + extra);
        let n = unit(&p.normal);
        let point = Size::new(size, support_tie(&pa, &n, true, k, size));
        return Local { point, depth: Size::new(size, 0.0), normal: Size::new(1.0, 0.0), ..Local::default() };
    }
    let Some((pb, rb)) = core_of(b, k, faces) else { return Local::default() };
    let size = clean(solid_size(&pa, ra, k) + solid_size(&pb, rb, k) + extra);
    let n = unit(&w.normal);
    let ties = support_tie(&pa, &n, true, k, size) + support_tie(&pb, &n, false, k, size);
    let core_gap = w.distance + ra + rb;
    if core_gap > 0.0 {
        let turn = ratio(size, core_gap).min(std::f64::consts::PI / f64::EPSILON);
        Local {
            point: Size::new(size, clean(size * turn + ties)),
            depth: Size::new(size, 0.0),
            normal: Size::new(1.0, turn),
            ..Local::default()
        }
    } else {
        let mut l = resting(&pa, &pb, k, size, size);
        l.point.condition = clean(l.point.condition + ties);
        l.margin = Size::default();
        l
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distances here are exact in binary and the closest-point arithmetic
    /// on coordinates near 1 rounds a few times: a few ulps.
    const REGION_DISTANCE_REL: f64 = 8.0 * f64::EPSILON;

    #[test]
    fn region_distance_holds_at_every_scale() {
        // The square [0, 1]² at z = 0: a point above its middle is 1 away, a
        // point in it 0, a point beside its edge 1 from the edge.
        for s in [1.0, 1e-226, 2f64.powi(-1060), 1e300] {
            let square = Region::of(&[[0.0, 0.0, 0.0], [s, 0.0, 0.0], [s, s, 0.0], [0.0, s, 0.0]]).expect("a patch");
            let above = square.distance(&[s / 2.0, s / 2.0, s]);
            assert!((above - s).abs() <= REGION_DISTANCE_REL * s, "{s:e}: {above:e}");
            let inside = square.distance(&[s / 4.0, s / 2.0, 0.0]);
            assert!(inside <= REGION_DISTANCE_REL * s, "{s:e}: inside, {inside:e}");
            let beside = square.distance(&[2.0 * s, s / 2.0, 0.0]);
            assert!((beside - s).abs() <= REGION_DISTANCE_REL * s, "{s:e}: {beside:e}");
            let segment = Region::of(&[[0.0, 0.0, 0.0], [s, 0.0, 0.0]]).expect("a segment");
            let off = segment.distance(&[s / 2.0, s, 0.0]);
            assert!((off - s).abs() <= REGION_DISTANCE_REL * s, "{s:e}: {off:e}");
        }
    }
}
