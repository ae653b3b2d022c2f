//! Sphere–mesh time of impact by conservative advancement, every face or the
//! faces a bounding volume hierarchy cannot rule out.

use super::feature_roots::{FirstContact, first_contact};
use super::sphere_triangle::{Advanced, Advancement, advance, amax, beyond_advancement, exact_answer, scale};
use super::sweep::{Sweep, sweep_faces};
use super::time_of_impact::{Toi, clamp_t_max};
use crate::mesh::{MeshBvh, MeshContact, TriMesh, contact_sphere_mesh_nearest};
use crate::real::{Real, Vec3, c, scale2, scale2v, unit_scale};
use crate::shapes::{Sphere, Triangle};

/// A time of impact against a mesh: the answer (in the convention of [`Toi`])
/// and the face it was found on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshToi<T: Real> {
    /// The time of impact and the contact then (the point on that face, the
    /// normal from the mesh toward the sphere).
    pub toi: Toi<T>,
    /// Index of the face (0-based, as in [`TriMesh::faces`]).
    pub triangle: usize,
}

/// A scene outside the plain range (see [`unit_scale`]) scaled by a power of
/// two `2^k` to about 1: the sphere, both velocities and a copy of the mesh
/// (rebuilt: only such scenes pay for it), with `k`. `None` for a scene in
/// the plain range.
#[allow(clippy::type_complexity)]
fn scaled_scene<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &TriMesh<T>,
    vb: &Vec3<T>,
) -> Option<(Sphere<T>, Vec3<T>, Vec3<T>, TriMesh<T>, i32)> {
    let boxed = b.aabb().map_or(T::zero(), |x| amax(&x.min).max(amax(&x.max)));
    let k = unit_scale(scale(a, &[]).max(boxed).max(amax(va)).max(amax(vb)))?;
    let vertices = b.vertices().iter().map(|p| scale2v(p, k)).collect();
    let mesh = TriMesh::new(vertices, b.faces().to_vec()).ok()?;
    let a2 = Sphere { center: scale2v(&a.center, k), radius: scale2(a.radius, k) };
    Some((a2, scale2v(va, k), scale2v(vb, k), mesh, k))
}

impl<T: Real> MeshToi<T> {
    /// The answer on a scene scaled by `2^k`, in the scene's own size: the
    /// point scaled back (times and directions do not scale).
    fn scaled_back(mut self, k: i32) -> Self {
        self.toi.point = scale2v(&self.toi.point, -k);
        self
    }

    /// The answer for a sphere already in contact at `t = 0`: the static
    /// contact with the face nearest its centre.
    fn penetrating(k: &MeshContact<T>) -> Self {
        Self { toi: Toi::penetrating(&k.contact), triangle: k.triangle }
    }
}

/// The best face so far: the earlier time, ties to the lower face index.
struct Best<T: Real> {
    face: usize,
    advanced: Advanced<T>,
}

impl<T: Real> Best<T> {
    fn beaten_by(best: &Option<Self>, t: T, face: usize) -> bool {
        best.as_ref().is_none_or(|b| t < b.advanced.t || (t == b.advanced.t && face < b.face))
    }
}

/// What both variants share: the tolerance, the relative motion, the answer.
struct Query<'a, T: Real> {
    a: &'a Sphere<T>,
    v: Vec3<T>,
    vb: &'a Vec3<T>,
    t_max: T,
    tol: T,
    max_steps: u32,
}

impl<'a, T: Real> Query<'a, T> {
    fn new(a: &'a Sphere<T>, va: &Vec3<T>, mesh: &TriMesh<T>, vb: &'a Vec3<T>, t_max: T, rule: &Advancement) -> Self {
        let corners: Vec<Vec3<T>> = mesh.aabb().map(|b| vec![b.min, b.max]).unwrap_or_default();
        let tol = c::<T>(rule.tol_eps) * T::EPSILON * scale(a, &corners);
        Self { a, v: va - vb, vb, t_max: clamp_t_max(t_max), tol, max_steps: rule.max_steps }
    }

    /// Advances against one face, within the best time so far; records a better
    /// answer.
    fn face(&self, best: &mut Option<Best<T>>, face: usize, tri: &Triangle<T>) {
        let limit = best.as_ref().map_or(self.t_max, |b| b.advanced.t);
        if let Some(adv) = advance(self.a, &self.v, tri, limit, self.tol, T::zero(), self.max_steps)
            && Best::beaten_by(best, adv.t, face)
        {
            *best = Some(Best { face, advanced: adv });
        }
    }

    fn answer(&self, best: Option<Best<T>>) -> Option<MeshToi<T>> {
        best.map(|b| MeshToi { toi: b.advanced.answer(self.a, &self.v, self.vb), triangle: b.face })
    }
}

/// Time of impact of sphere `a` (velocity `va`) and a mesh `b` (every vertex
/// moving with `vb`) over `[0, t_max]` by **conservative advancement against
/// every face** (the lecture's "test every triangle", with the robust method
/// per face).
///
/// **Definition.** Each face is a two-sided triangle (no inside, no thickness),
/// and the mesh's time of impact is the earliest over its faces: each face's by
/// the advancement of [`toi_sphere_triangle`](super::toi_sphere_triangle)
/// (the step `gap / closing` never passes that face's first contact), the
/// earliest time winning, ties to the lowest face index. Every face uses the
/// same gap tolerance, `rule.tol_eps · ε · scale` with the scale of the whole
/// scene (the radius, the centre's largest coordinate and the mesh's box), so
/// that answers compare alike across faces. A face is advanced only up to the
/// best time found so far: its steps do not depend on that limit, so the
/// winner is the same as if every face ran to `t_max`.
///
/// **Answer.** Already in contact at `t = 0` (touching counts): `t = 0`,
/// [`ToiStatus::Penetrating`](super::ToiStatus::Penetrating), the contact with
/// the face nearest the centre (each face's distance from the certified
/// sphere–triangle contact, accurate relative to itself, the lowest index on
/// a tie), answered as that triangle's
/// [`contact_sphere_triangle`](crate::contact::contact_sphere_triangle) — on
/// the scene as given, before any power-of-two scaling. Otherwise the winning face's answer: its time,
/// its closest point moved to time `t` and the normal from it toward the
/// centre; `iterations` counts that face's steps. When the winner ran out of
/// steps ([`ToiStatus::OutOfIterations`](super::ToiStatus::OutOfIterations)),
/// `t` is still a time before which the sphere touches no face: every other
/// face's first contact is at or after its own reported time.
///
/// **Scenes of widely mixed magnitudes.** Where the mesh's box reaches
/// beyond [`EXACT_RANGE_RATIO`](super::sphere_triangle::EXACT_RANGE_RATIO)
/// times the sphere's own scale (its radius, its centre, its distance from
/// the box), the shared tolerance, of the whole mesh's scale, can exceed the
/// gap to a face far smaller than the mesh, and each face is solved from its
/// features' exact equations instead (as
/// [`toi_sphere_triangle`](super::toi_sphere_triangle) does for one
/// triangle); the earliest time wins, ties to the lowest face index
/// (faces sharing an edge or a vertex round its time alike).
///
/// **Degenerate input.** A zero-area face is the segment or point it collapsed
/// to (as for one triangle); a face with a non-finite vertex is skipped; an
/// empty mesh is never hit. A sphere of zero radius gets the approach direction
/// `−v/‖v‖` as its normal, flagged; a centre on a face at `t = 0` the static
/// fallback, flagged. A negative or NaN `t_max` is read as 0. Never NaN, never
/// a panic; a contact point beyond the type's range is `None`, as for one
/// triangle.
pub fn toi_sphere_mesh_brute<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &TriMesh<T>,
    vb: &Vec3<T>,
    t_max: T,
    rule: &Advancement,
) -> Option<MeshToi<T>> {
    if let Some(k) = contact_sphere_mesh_nearest(a, b, None) {
        return Some(MeshToi::penetrating(&k));
    }
    if exact_scene(a, b) {
        let x = Exact::new(a, va, vb, t_max);
        let mut best = None;
        for face in 0..b.len() {
            if !b.has_nonfinite_vertex(face) {
                x.face(&mut best, face, &b.triangle(face));
            }
        }
        return x.answer(best);
    }
    brute_clear(a, va, b, vb, t_max, rule).filter(|r| r.toi.in_range())
}

/// Whether the mesh reaches so far beyond the sphere's own scale that its
/// faces are solved exactly (see
/// [`EXACT_RANGE_RATIO`](super::sphere_triangle::EXACT_RANGE_RATIO)): the
/// mesh's box decides, since advancement's tolerance here is of the whole
/// mesh's scale, and the distance from the box bounds the travel to every
/// face from below.
fn exact_scene<T: Real>(a: &Sphere<T>, b: &TriMesh<T>) -> bool {
    b.aabb().is_some_and(|x| beyond_advancement(a, &x.min, &x.max))
}

/// The exact per-face solve of a mesh query (see
/// [`first_contact`](super::feature_roots::first_contact)): the sphere, the
/// motion and the interval as given, the best face so far.
struct Exact<'a, T: Real> {
    a: &'a Sphere<T>,
    va: &'a Vec3<T>,
    vb: &'a Vec3<T>,
    t_max: T,
}

impl<'a, T: Real> Exact<'a, T> {
    fn new(a: &'a Sphere<T>, va: &'a Vec3<T>, vb: &'a Vec3<T>, t_max: T) -> Self {
        Self { a, va, vb, t_max: clamp_t_max(t_max) }
    }

    /// Solves one face and records it when it is earlier than the best so
    /// far, or as early with a lower index. Every face is solved over the
    /// whole `[0, t_max]` (not up to the best time), so that a tie is seen
    /// as a tie whatever order the faces come in.
    fn face(&self, best: &mut Option<(usize, FirstContact)>, face: usize, tri: &Triangle<T>) {
        if let Some(hit) = first_contact(self.a, self.va, tri, self.vb, self.t_max)
            && best.as_ref().is_none_or(|(f, b)| hit.t.total_cmp(&b.t).then(face.cmp(f)).is_lt())
        {
            *best = Some((face, hit));
        }
    }

    fn answer(&self, best: Option<(usize, FirstContact)>) -> Option<MeshToi<T>> {
        best.map(|(face, hit)| MeshToi { toi: exact_answer(self.a, self.va, self.vb, &hit), triangle: face })
            .filter(|r| r.toi.in_range())
    }
}

/// [`toi_sphere_mesh_brute`] for a sphere known to touch no face at `t = 0`.
fn brute_clear<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &TriMesh<T>,
    vb: &Vec3<T>,
    t_max: T,
    rule: &Advancement,
) -> Option<MeshToi<T>> {
    if let Some((a2, va2, vb2, mesh, k)) = scaled_scene(a, va, b, vb) {
        return brute_clear(&a2, &va2, &mesh, &vb2, t_max, rule).map(|r| r.scaled_back(k));
    }
    let q = Query::new(a, va, b, vb, t_max, rule);
    let mut best = None;
    for face in 0..b.len() {
        if !b.has_nonfinite_vertex(face) {
            q.face(&mut best, face, &b.triangle(face));
        }
    }
    q.answer(best)
}

/// Time of impact of sphere `a` (velocity `va`) and a mesh `b` (every vertex
/// moving with `vb`) over `[0, t_max]` by **conservative advancement over the
/// mesh's bounding volume hierarchy**: the same definition and answer as
/// [`toi_sphere_mesh_brute`], visiting only the faces the sphere can reach in
/// time to win.
///
/// **Traversal.** In `b`'s frame the centre moves on the ray `M + t v`
/// (`v = va − vb`). A node's box, grown by the radius, the gap tolerance and a
/// rounding margin, contains every point within `r + tol` of its faces, so the
/// time the ray enters that grown box (a slab test) is a lower bound on the
/// time any of its faces can be reached to within the tolerance — which is
/// when advancement stops. Nodes are visited nearer entry first with a
/// fixed-size stack; a node is skipped when the ray never enters its box within
/// `[0, t_max]` or enters it after the best time found so far (strictly: a tie
/// could still go to a lower face index). The faces skipped could therefore
/// neither win nor tie, and the answer equals the brute-force one, bit for bit,
/// whenever no face runs out of steps (with a capped face both report a time
/// before which nothing is touched, possibly a different one).
///
/// **Cost.** A sphere that passes nothing visits a few boxes; one that hits the
/// mesh advances against the faces whose boxes its path enters before the hit,
/// typically a handful (see crashtest's report and `benches/toi.rs`).
///
/// **Degenerate input and mixed magnitudes:** as [`toi_sphere_mesh_brute`]
/// (faces with a non-finite vertex are not in the tree; a scene solved
/// exactly per face is traversed the same way, with no gap tolerance in the
/// boxes' growth).
///
/// Source: Mirtich's conservative advancement per face; the swept-sphere box
/// test is Ericson §5.5.7 (moving sphere against an AABB, here its conservative
/// slab form).
pub fn toi_sphere_mesh<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &MeshBvh<T>,
    vb: &Vec3<T>,
    t_max: T,
    rule: &Advancement,
) -> Option<MeshToi<T>> {
    if let Some(k) = contact_sphere_mesh_nearest(a, b.mesh(), Some(b)) {
        return Some(MeshToi::penetrating(&k));
    }
    if exact_scene(a, b.mesh()) {
        return bvh_exact(a, va, b, vb, t_max);
    }
    bvh_clear(a, va, b, vb, t_max, rule).filter(|r| r.toi.in_range())
}

/// `1 + 2^−20`: the factor taking an `f64` time above its rounding to a
/// narrower type (`f32` rounds to 2^−24 relative), for the traversal's bound.
const BOUND_ROUND_UP: f64 = 1.0 + 1.0 / 1_048_576.0;

/// [`toi_sphere_mesh`] for a scene whose faces are solved exactly (see
/// [`exact_scene`]). The traversal only prunes: it runs on the tree as given,
/// or, for a scene outside the plain range, on a copy scaled by a power of
/// two to about 1 (its slab tests would overflow or lose their margin
/// otherwise). Scaling is exact but for what underflows, which lies within
/// the sweep's rounding margin of the scaled scene's size, so the scaled
/// boxes still bound every face's first contact from below; the faces
/// themselves are solved on the scene as given.
fn bvh_exact<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &MeshBvh<T>, vb: &Vec3<T>, t_max: T) -> Option<MeshToi<T>> {
    let x = Exact::new(a, va, vb, t_max);
    let mut best: Option<(usize, FirstContact)> = None;
    // The best time in the type, never below the exact solve's: a type
    // narrower than `f64` rounds it up by a margin above its rounding.
    let bound = |best: &Option<(usize, FirstContact)>| {
        best.as_ref().map(|(_, h)| {
            let t = T::of(h.t);
            if t.wide() >= h.t { t } else { T::of(h.t * BOUND_ROUND_UP) }
        })
    };
    let visit = |best: &mut Option<(usize, FirstContact)>, face: usize, _: &Triangle<T>| {
        x.face(best, face, &b.mesh().triangle(face));
    };
    if let Some((a2, va2, vb2, mesh, _)) = scaled_scene(a, va, b.mesh(), vb) {
        let tree = MeshBvh::new(mesh);
        let sweep = Sweep::new(&a2, &(va2 - vb2), T::zero(), tree.mesh().aabb());
        sweep_faces(&tree, &sweep, x.t_max, bound, &mut best, visit);
    } else {
        let sweep = Sweep::new(a, &(va - vb), T::zero(), b.mesh().aabb());
        sweep_faces(b, &sweep, x.t_max, bound, &mut best, visit);
    }
    x.answer(best)
}

/// [`toi_sphere_mesh`] for a sphere known to touch no face at `t = 0`.
fn bvh_clear<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &MeshBvh<T>,
    vb: &Vec3<T>,
    t_max: T,
    rule: &Advancement,
) -> Option<MeshToi<T>> {
    if let Some((a2, va2, vb2, mesh, k)) = scaled_scene(a, va, b.mesh(), vb) {
        return bvh_clear(&a2, &va2, &MeshBvh::new(mesh), &vb2, t_max, rule).map(|r| r.scaled_back(k));
    }
    let q = Query::new(a, va, b.mesh(), vb, t_max, rule);
    let sweep = Sweep::new(a, &q.v, q.tol, b.mesh().aabb());
    let mut best: Option<Best<T>> = None;
    sweep_faces(
        b,
        &sweep,
        q.t_max,
        |best: &Option<Best<T>>| best.as_ref().map(|b| b.advanced.t),
        &mut best,
        |best, face, tri| q.face(best, face, tri),
    );
    q.answer(best)
}
