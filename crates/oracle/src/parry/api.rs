//! The two engines ([`Parry64`], [`Parry32`]), the queries they answer for
//! crashtest ([`ParryEngine`]) and what no translation of conventions removes
//! ([`KnownDivergence`]): what the adapters beside this file implement and
//! use, so that they import it, never the module that re-exports them.

use crate::geom::{Aabb, Ball, BarycentricAnswer, BoundsAnswer, ContactAnswer, IntersectAnswer};
use crate::geom::{Capsule, DistanceAnswer, OrientedBox, P3, Plane, Segment, Solid, Sphere, Triangle};

/// The parry release both engines are pinned to (`=0.31.1` in the workspace
/// manifest); reports print it beside each engine's name.
pub const PARRY_VERSION: &str = "0.31.1";

/// parry3d-f64: parry in double precision.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Parry64;

impl Parry64 {
    /// The engine's name in reports and in [`KnownDivergence::engine`].
    pub const NAME: &'static str = "parry3d-f64";
}

/// parry3d: parry in single precision. Inputs are rounded to `f32` at the edge and
/// answers widened back to `f64`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Parry32;

impl Parry32 {
    /// The engine's name in reports and in [`KnownDivergence::engine`].
    pub const NAME: &'static str = "parry3d";
}

/// The queries parry answers for crashtest, in crashtest's conventions (see the
/// module documentation for the translation and [`known_divergences`] for what
/// cannot be translated). Implemented by [`Parry64`] and [`Parry32`] from one body.
pub trait ParryEngine {
    /// The engine's name: [`Parry64::NAME`] or [`Parry32::NAME`].
    fn name(&self) -> &'static str;

    /// Contact between spheres `a` and `b`.
    ///
    /// **Formula** (parry's `contact_ball_ball`, `query/contact/contact_ball_ball.rs`):
    /// with `Δ = M_b − M_a`, a contact exists when `‖Δ‖² < (r_a + r_b)²`; then
    /// `normal1 = Δ/‖Δ‖`, `point2 = M_b − r_b normal1`, `dist = ‖Δ‖ − r_a − r_b`.
    /// Translated: normal `(M_a − M_b)/‖M_a − M_b‖`, point `M_b + r_b n`, depth
    /// `r_a + r_b − ‖M_a − M_b‖` — the lecture's `p = M2 + r2 n`.
    ///
    /// **Deviation:** exactly touching spheres give no contact (strict `<`): a known
    /// divergence, reported raw.
    ///
    /// **Degenerate input:** concentric centres (`‖Δ‖² = 0` in the engine's scalar,
    /// parry's own branch condition, which an underflowing `‖Δ‖²` also meets):
    /// parry's fallback `normal1 = +x`, so normal `−x`, point `M_b − r_b x̂`, depth
    /// `r_a + r_b`, flagged `degenerate` (crashtest's fallback normal is `+z`: a
    /// known divergence). A radius that is not positive, or any input that is not
    /// finite in the engine's scalar: no contact, flagged.
    fn contact_sphere_sphere(&self, a: Sphere, b: Sphere) -> ContactAnswer;

    /// Contact between sphere `a` and the solid half-space `b` (`n · x ≤ d`).
    ///
    /// **Formula** (parry's `contact_support_map_halfspace`,
    /// `query/contact/contact_halfspace_support_map.rs`): the ball's support point
    /// against the normal, `s = M − r n̂`, has signed height `h = n̂ · s − d/‖n‖`;
    /// a contact exists when `h ≤ 0`, with `normal1 = −n̂` (from the ball toward
    /// the plane), `point2 = s − h n̂` (the projection of `s`, hence of `M`, onto
    /// the plane), `dist = h`. Translated: normal `n̂`, point `M − (r − x) n̂` with
    /// depth `x = −h` — the lecture's formula. Touching counts.
    ///
    /// **Defect of parry 0.31.1, reported raw:** in this argument order (support
    /// map first, half-space second) parry's `contact_support_map_halfspace` hands
    /// the pose of shape 2 relative to shape 1 to `contact_halfspace_support_map`,
    /// which expects the inverse; the ball is then treated as if mirrored through
    /// the half-space's anchor point `(d/‖n‖) n̂`: depth `r + n̂ · M − d/‖n‖` (the
    /// sign of the height flipped), point `2(d/‖n‖) n̂ − M` projected onto the plane.
    /// The answer is right only for a centre on the plane's anchor point. It is not
    /// a convention and is not listed among [`known_divergences`]: crashtest's
    /// comparisons show it as the disagreement it is, and a test pins it so that a
    /// fixed parry is noticed. [`ParryEngine::contact_plane_sphere`] is unaffected.
    ///
    /// **Degenerate input:** a plane normal that cannot be normalized (zero, or
    /// non-finite in the engine's scalar), a radius that is not positive, or a
    /// non-finite input: no contact, flagged.
    fn contact_sphere_plane(&self, a: Sphere, b: Plane) -> ContactAnswer;

    /// Contact between the solid half-space `a` (`n · x ≤ d`) and sphere `b`: the
    /// same parry computation with the shapes in this order
    /// (`contact_halfspace_support_map`): `normal1 = n̂`, `point2 = M − r n̂` (the
    /// sphere's deepest point), `dist = n̂ · (M − r n̂) − d/‖n‖`. Translated: normal
    /// `−n̂` (from the sphere toward the plane), point on the sphere, depth `−dist`.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_plane`].
    fn contact_plane_sphere(&self, a: Plane, b: Sphere) -> ContactAnswer;

    /// Contact between sphere `a` and triangle `b` (two-sided, as a surface).
    ///
    /// **Formula** (parry's `contact_ball_convex_polyhedron`,
    /// `query/contact/contact_ball_convex_polyhedron.rs`, with the triangle's
    /// Voronoi-region projection of `query/point/point_triangle.rs`): `q` is the
    /// closest point of the triangle to `M`, `ℓ = ‖M − q‖`; a contact exists when
    /// `ℓ − r ≤ 0`, with normal (translated) `(M − q)/ℓ`, point `q`, depth `r − ℓ`.
    ///
    /// **Degenerate input:** when `ℓ` is below parry's `DEFAULT_EPSILON` (the
    /// scalar's machine epsilon, in absolute length units) parry takes its fallback:
    /// the triangle's face normal `(v1 − v0) × (v2 − v0)` normalized, depth `r`;
    /// the answer is then flagged `degenerate` (the flag mirrors parry's branch
    /// condition, computed with parry's own projection). That parry takes this
    /// branch for a centre merely *near* the triangle is a known divergence. A
    /// zero-area triangle is flagged and parry's answer kept (parry then projects
    /// onto the triangle's longest edge). Non-finite input or radius ≤ 0: no
    /// contact, flagged.
    fn contact_sphere_triangle(&self, a: Sphere, b: Triangle) -> ContactAnswer;

    /// Contact between triangle `a` and sphere `b`: parry's
    /// `contact_convex_polyhedron_ball` (same file as
    /// [`ParryEngine::contact_sphere_triangle`]), `normal1 = (M − q)/ℓ` from the
    /// triangle toward the sphere, `point2 = M − r normal1`. Translated: normal
    /// `(q − M)/ℓ` (from the sphere toward the triangle), point on the sphere,
    /// depth `r − ℓ`.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_triangle`] (the
    /// fallback normal is then the negated face normal).
    fn contact_triangle_sphere(&self, a: Triangle, b: Sphere) -> ContactAnswer;

    /// Contact between sphere `a` and a triangle mesh (`vertices`, `triangles`):
    /// parry's `contact` of a ball against its `TriMesh`
    /// (`query::details::contact_shape_composite_shape`: the deepest of the
    /// faces' contacts, each face as in [`ParryEngine::contact_sphere_triangle`]),
    /// translated as that pair is.
    ///
    /// **Degenerate input:** flagged when the centre is within parry's fallback
    /// distance of a face (as for one triangle), or a face has zero area; an
    /// empty mesh touches nothing. A mesh parry refuses, non-finite input or a
    /// radius ≤ 0: no contact, flagged.
    fn contact_sphere_mesh(&self, a: Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> ContactAnswer;

    /// First hit of a segment with the plane `n · x = d` (a surface: a segment
    /// starting on the solid side hits the plane where it crosses it).
    ///
    /// **Formula** (parry's `RayCast for HalfSpace`, `query/ray/ray_halfspace.rs`,
    /// `solid = false`, max time of impact 1): with ray origin `p0` and direction
    /// `p1 − p0` in the half-space's frame, `t = (d/‖n‖ − n̂ · p0) / (n̂ · (p1 − p0))`,
    /// a hit when `0 ≤ t ≤ 1` — the lecture's `r = n·(v0 − p0) / n·(p1 − p0)`. Point
    /// `p0 + t (p1 − p0)`, normal `n̂` (parry's, re-oriented when parry turned it
    /// toward the origin).
    ///
    /// **Parallel:** on a miss, `parallel` is parry's own verdict:
    /// `query::details::line_toi_with_halfspace` returns `None` exactly when
    /// `|n̂ · (p1 − p0)| ≤ ε`, the scalar's machine epsilon in absolute length
    /// units — a scale-dependent test and a known divergence. A hit is never
    /// parallel.
    ///
    /// **Degenerate input:** zero-length segment (`p1 − p0 = 0` in the engine's
    /// scalar), a normal that cannot be normalized, non-finite input: no hit, not
    /// parallel, flagged.
    fn intersect_segment_plane(&self, s: Segment, b: Plane) -> IntersectAnswer;

    /// First hit of a segment with a triangle (either side).
    ///
    /// **Formula** (parry's `local_ray_intersection_with_triangle`,
    /// `query/ray/ray_triangle.rs`, max time of impact 1): with `n = (b − a) × (c − a)`
    /// and `δ = n · (p1 − p0)`, `t = −n · (p0 − a) / δ`, and the hit is inside when
    /// its (unnormalized) barycentrics from `(p1 − p0) × (p0 − a)` lie in `[0, |δ|]`
    /// — the Möller–Trumbore-style test. Point `p0 + t (p1 − p0)`, normal the face
    /// normal (parry's re-oriented), barycentrics from parry's
    /// `project_local_point_and_get_location` at the hit point (`OnFace`, `OnEdge`
    /// or `OnVertex` coordinates, in the order `[v0, v1, v2]`).
    ///
    /// **Parallel:** parry returns no hit when `δ = 0` and says nothing more, so
    /// `parallel` is always `false` — a known divergence.
    ///
    /// **Degenerate input:** zero-length segment, zero-area triangle, non-finite
    /// input: no hit, flagged.
    fn intersect_segment_triangle(&self, s: Segment, b: Triangle) -> IntersectAnswer;

    /// Barycentric coordinates `[α, β, γ]` of `p` with respect to a triangle.
    ///
    /// **Formula** (parry's `project_local_point_and_get_location`,
    /// `query/point/point_triangle.rs`, after Catto's GJK notes): the point's
    /// Voronoi region of the triangle is found by dot and triple products; in the
    /// face region `v = v_b/(v_a + v_b + v_c)`, `w = v_c/(…)`, coordinates
    /// `[1 − v − w, v, w]` — those of the projection onto the plane, as crashtest
    /// defines them.
    ///
    /// **Deviation:** outside the triangle parry answers for the closest point of
    /// the triangle (an edge or vertex region: non-negative, clamped coordinates),
    /// not for the projection onto the plane — a known divergence, reported raw.
    ///
    /// **Degenerate input:** a zero-area triangle is flagged and parry's answer
    /// (the projection onto the longest edge) kept; a non-finite input or answer
    /// gives `[⅓, ⅓, ⅓]`, flagged.
    fn barycentric_triangle(&self, p: P3, b: Triangle) -> BarycentricAnswer;

    /// The tight axis-aligned box of a point set: parry's `Aabb::from_points`
    /// (component-wise minimum and maximum, `bounding_volume/aabb_utils.rs`).
    ///
    /// **Degenerate input:** an empty set (parry would panic) or a point that is
    /// not finite in the engine's scalar: `None`. In `f32` the box is that of the
    /// rounded points, so it may miss an input point by half an `f32` ulp.
    fn aabb_of_points(&self, points: &[P3]) -> Option<Aabb>;

    /// parry's bounding sphere of a point set:
    /// `bounding_volume::details::point_cloud_bounding_sphere`, the centroid
    /// `c = Σ pᵢ / N` (each point pre-scaled by `1/N`) and radius `max ‖pᵢ − c‖`
    /// (`bounding_volume/bounding_sphere_utils.rs`).
    ///
    /// **Deviation:** this sphere encloses the points but is not the smallest one
    /// — a known divergence wherever a minimal radius is asked for.
    ///
    /// **Degenerate input:** as [`ParryEngine::aabb_of_points`].
    fn bounding_sphere_of_points(&self, points: &[P3]) -> Option<Ball>;

    /// Both bounding volumes of a point set, as a `bounds` answer.
    fn bounds_of_points(&self, points: &[P3]) -> BoundsAnswer {
        BoundsAnswer { aabb: self.aabb_of_points(points), sphere: self.bounding_sphere_of_points(points) }
    }

    /// Whether two boxes overlap: parry's `BoundingVolume::intersects`,
    /// `a.min ≤ b.max ∧ a.max ≥ b.min` on every axis (`bounding_volume/aabb.rs`), so
    /// touching faces overlap, as crashtest asks.
    ///
    /// **Degenerate input:** none is refused: bounds rounded to infinity in `f32`
    /// compare as such, and a NaN bound compares false (no overlap).
    fn overlap_aabb_aabb(&self, a: Aabb, b: Aabb) -> bool;

    /// Contact of sphere `a` with box `b`: parry's `query::contact` on a `Ball`
    /// and a `Cuboid` (the box's half-extents, placed at its centre with the unit
    /// quaternion `q/‖q‖`, [`super::engine`]'s `cuboid`), which dispatches to
    /// `contact_ball_convex_polyhedron` (the centre projected on the cuboid,
    /// `query/contact/contact_ball_convex_polyhedron.rs`). Translated as every
    /// contact: normal `−normal1`, point `point2`, depth `−dist`.
    ///
    /// **Degenerate input:** parry flags nothing: `degenerate` is always false
    /// (a centre on an edge or equidistant from two faces, which crashtest
    /// flags, is shown as parry answers it). A radius that is not positive, a
    /// zero quaternion or any input not finite in the engine's scalar: no
    /// contact, flagged.
    fn contact_sphere_box(&self, a: Sphere, b: OrientedBox) -> ContactAnswer;

    /// Contact of box `a` with the solid half-space `b`: `query::contact` on a
    /// `Cuboid` and a `HalfSpace` (placed as for [`ParryEngine::contact_sphere_plane`]),
    /// which dispatches to `contact_support_map_halfspace`. Translated as every
    /// contact. That routine places the half-space with `pos12` where its siblings
    /// use `pos12.inverse()` (as for spheres): with a rotated box the difference
    /// is not a mirror image alone, and is shown as it comes.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_box`].
    fn contact_box_plane(&self, a: OrientedBox, b: Plane) -> ContactAnswer;

    /// Contact of sphere `a` with capsule `b`: `query::contact` on a `Ball` and
    /// parry's `Capsule` (its segment's two ends and radius, at the identity
    /// pose), dispatched to `contact_ball_convex_polyhedron`. Translated as every
    /// contact.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_box`] (a centre on
    /// the axis is not flagged).
    fn contact_sphere_capsule(&self, a: Sphere, b: Capsule) -> ContactAnswer;

    /// Contact of two capsules: `query::contact` on two parry `Capsule`s,
    /// dispatched to `contact_support_map_support_map` (GJK, then EPA when the
    /// cores overlap; `query/contact/contact_support_map_support_map.rs`).
    /// Translated as every contact.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_box`].
    fn contact_capsule_capsule(&self, a: Capsule, b: Capsule) -> ContactAnswer;

    /// Contact of capsule `a` with the solid half-space `b`: `query::contact`,
    /// dispatched to `contact_support_map_halfspace` (see
    /// [`ParryEngine::contact_box_plane`]).
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_box`].
    fn contact_capsule_plane(&self, a: Capsule, b: Plane) -> ContactAnswer;

    /// Contact of two boxes: `query::contact` on two `Cuboid`s, each at its
    /// pose, which dispatches to `contact_cuboid_cuboid` (parry's separating
    /// axes: `query/contact/contact_cuboid_cuboid.rs`). Translated as every
    /// contact.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_box`].
    fn contact_box_box(&self, a: OrientedBox, b: OrientedBox) -> ContactAnswer;

    /// Contact of box `a` with triangle `b`: `query::contact` on a `Cuboid`
    /// and parry's `Triangle` (its world vertices at the identity pose),
    /// dispatched to `contact_support_map_support_map` (GJK, then EPA).
    /// Translated as every contact.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_box`].
    fn contact_box_triangle(&self, a: OrientedBox, b: Triangle) -> ContactAnswer;

    /// Contact of capsule `a` with box `b`: `query::contact` on parry's
    /// `Capsule` and a `Cuboid`, dispatched to `contact_support_map_support_map`.
    /// Translated as every contact.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_box`].
    fn contact_capsule_box(&self, a: Capsule, b: OrientedBox) -> ContactAnswer;

    /// Contact of capsule `a` with triangle `b`: as
    /// [`ParryEngine::contact_capsule_box`], the triangle at the identity pose.
    ///
    /// **Degenerate input:** as [`ParryEngine::contact_sphere_box`].
    fn contact_capsule_triangle(&self, a: Capsule, b: Triangle) -> ContactAnswer;

    /// Signed distance of solids `a` and `b`: `query::contact` with a
    /// prediction of the scalar's largest value, so that separated shapes get
    /// their closest points too (support-map pairs go to GJK, then EPA when
    /// they overlap). Shapes as for the contacts; a convex hull is
    /// `ConvexPolyhedron::from_convex_hull` of its points, a plane a
    /// `HalfSpace`. **Translated:** `distance` = parry's `dist` (negative
    /// inside), `point_a` = `point1`, `point_b` = `point2`, `normal` =
    /// `−normal1` (parry's points from `a` toward `b`). parry has no
    /// degenerate flag: `degenerate` is always false.
    ///
    /// `Err` with parry's reason when it builds no shape (a hull whose points
    /// are flat, collinear or one point: `from_convex_hull` gives none) or
    /// returns no contact or a non-finite number.
    fn distance(&self, a: Solid<'_>, b: Solid<'_>) -> Result<DistanceAnswer, String>;

    /// First hit of a segment on the solid box `b`: parry's
    /// `RayCast::cast_ray_and_get_normal` on the `Cuboid` with `solid = true` and
    /// the ray `start + t (end − start)`, `t ≤ 1` (`query/ray/ray_cuboid.rs`,
    /// through the AABB's slab test). A start inside gives `t = 0` with parry's
    /// own normal there, shown as it comes. Not flagged; `parallel` false.
    ///
    /// **Degenerate input:** a zero-length segment or a non-finite input: no hit,
    /// flagged.
    fn intersect_segment_box(&self, s: Segment, b: OrientedBox) -> IntersectAnswer;

    /// First hit of a segment on the solid capsule `b`: parry's
    /// `RayCast::cast_ray_and_get_normal` on its `Capsule` (at the identity
    /// pose) with `solid = true`, the ray as for
    /// [`ParryEngine::intersect_segment_box`] (`query/ray/ray_capsule.rs`: a
    /// circle in the plane across the axis, then the end caps' spheres). A
    /// start inside gives `t = 0` with parry's own normal.
    /// Not flagged; `parallel` false.
    ///
    /// **Degenerate input:** as [`ParryEngine::intersect_segment_box`].
    fn intersect_segment_capsule(&self, s: Segment, b: Capsule) -> IntersectAnswer;

    /// The bounding volumes of box `b`: the `Cuboid`'s `aabb(pose)` (its
    /// half-extents turned by the absolute rotation matrix) and
    /// `bounding_sphere(pose)` (the centre, radius `‖h‖`).
    fn bounds_box(&self, b: OrientedBox) -> BoundsAnswer;

    /// Whether two boxes overlap: parry's `query::intersection_test` on two
    /// `Cuboid`s (`intersection_test_cuboid_cuboid`, separating axes).
    ///
    /// **Degenerate input:** a non-finite input or a zero quaternion: `false`.
    fn overlap_box_box(&self, a: OrientedBox, b: OrientedBox) -> bool;

    /// Whether a box overlaps an AABB: the AABB as a `Cuboid` at its centre
    /// (half-extents `(max − min)/2`, rounded in the engine's scalar) against the
    /// box, as [`ParryEngine::overlap_box_box`].
    fn overlap_box_aabb(&self, a: OrientedBox, b: Aabb) -> bool;

    /// A triangle mesh prepared once for many queries: parry's `TriMesh` (its
    /// vertices in the engine's scalar, its own BVH built by `TriMesh::new`), and
    /// what the translation needs ([`super::Parry64Mesh`] or [`super::Parry32Mesh`]).
    type Mesh: Send + Sync;

    /// Prepares a mesh (`vertices`, and `triangles` as 0-based index triples).
    ///
    /// `None` — answered by [`ParryEngine::intersect_segment_mesh`] as no hit,
    /// flagged `degenerate` — when a vertex is not finite in the engine's scalar
    /// or a face names a vertex that does not exist (or beyond `u32`). A mesh
    /// without faces is prepared (parry's `TriMesh::new` would refuse it) and
    /// answers every segment with a plain miss.
    fn mesh(&self, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<Self::Mesh>;

    /// First hit of a segment on a prepared mesh.
    ///
    /// **Formula** (parry's `RayCast for TriMesh`, `query/ray/ray_trimesh.rs` and
    /// `ray_composite_shape.rs`, `solid = false`, max time of impact 1): a
    /// best-first traversal of parry's BVH (`Bvh::find_best`), each leaf's
    /// triangle cast as in [`ParryEngine::intersect_segment_triangle`], the
    /// smallest time of impact kept. Point `p0 + t (p1 − p0)`, normal the hit
    /// face's own `(v1 − v0) × (v2 − v0)` normalized (parry's, re-oriented:
    /// parry turns it toward the ray's origin), barycentrics as for one
    /// triangle, `triangle` the face index — parry's `RayIntersection::subshape`
    /// (its `feature` is the triangle's own `Face(0)` or `Face(1)`, front or
    /// back, not the mesh's face).
    ///
    /// **Deviations** (known divergences): a hit exactly at the segment's end
    /// (`t = 1`) is missed, as `find_best` keeps only costs strictly below the
    /// maximum; a segment through an edge or vertex shared by faces reports the
    /// face the traversal reaches first, not the lowest index; a segment
    /// parallel to every face is a plain miss (`parallel` is always `false`, as
    /// for one triangle).
    ///
    /// **Degenerate input:** a zero-length segment or a non-finite input: no
    /// hit, flagged. A face parry cannot normalize (zero area in the engine's
    /// scalar) flags every answer `degenerate`, as the fixture format's mesh
    /// rule asks (parry itself skips such a face silently).
    fn intersect_segment_prepared_mesh(&self, s: Segment, mesh: &Self::Mesh) -> IntersectAnswer;

    /// First hit of a segment on a mesh: [`ParryEngine::mesh`], then
    /// [`ParryEngine::intersect_segment_prepared_mesh`]. Building parry's BVH
    /// costs about as much as a thousand queries on the bunny; prepare the mesh
    /// once when querying it often.
    fn intersect_segment_mesh(&self, s: Segment, vertices: &[P3], triangles: &[[usize; 3]]) -> IntersectAnswer {
        match self.mesh(vertices, triangles) {
            Some(m) => self.intersect_segment_prepared_mesh(s, &m),
            None => IntersectAnswer { hit: None, parallel: false, degenerate: true },
        }
    }
}

/// A difference between an engine and crashtest's definitions that no translation
/// of conventions removes. Each entry is pinned by a test showing it still happens.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct KnownDivergence {
    /// The engine's name ([`Parry64::NAME`] or [`Parry32::NAME`]).
    pub engine: &'static str,
    /// The fixture query it concerns (`contact`, `intersect`, `barycentric`, `bounds`).
    pub query: &'static str,
    /// The case it concerns and what the engine answers there.
    pub what: &'static str,
    /// Why: what the engine does, where (file in parry's sources), and why it is
    /// not translated.
    pub reason: &'static str,
}

/// Every known divergence of [`Parry64`] and [`Parry32`] (each entry once per engine).
pub fn known_divergences() -> &'static [KnownDivergence] {
    &KNOWN
}

/// A divergence shared by both precisions, before it is stamped with an engine.
#[derive(Clone, Copy, Debug)]
pub(super) struct Divergence {
    pub(super) query: &'static str,
    pub(super) what: &'static str,
    pub(super) reason: &'static str,
}

pub(super) const TOUCHING_SPHERES: Divergence = Divergence {
    query: "contact",
    what: "sphere–sphere: exactly touching spheres (‖M_a − M_b‖ = r_a + r_b) give no contact",
    reason: "contact_ball_ball tests ‖Δ‖² < (r_a + r_b)², strictly; crashtest counts touching. \
             A positive prediction distance would also report separated pairs, so parry's raw \
             answer is kept.",
};

pub(super) const CONCENTRIC_SPHERES: Divergence = Divergence {
    query: "contact",
    what: "sphere–sphere, concentric: fallback normal −x (point M_b − r_b x̂) instead of crashtest's +z",
    reason: "contact_ball_ball falls back to normal1 = +x when ‖Δ‖² = 0; the fallback direction \
             is parry's choice, and the point built from it differs from crashtest's.",
};

pub(super) const CENTRE_NEAR_TRIANGLE: Divergence = Divergence {
    query: "contact",
    what: "sphere–triangle: a centre within the scalar's machine epsilon (absolute) of the \
           triangle is taken as on it: face-normal fallback, depth r, even just behind the face",
    reason: "contact_convex_polyhedron_ball switches to the feature normal when ‖M − q‖ < \
             DEFAULT_EPSILON, an absolute threshold; crashtest falls back only for a centre \
             exactly on the triangle, so the normal can point away from the centre.",
};

pub(super) const NO_TRIANGLE_PARALLEL: Divergence = Divergence {
    query: "intersect",
    what: "segment–triangle: a segment parallel to (or in) the triangle's plane is a plain miss, \
           parallel = false",
    reason: "local_ray_intersection_with_triangle returns None when n · dir = 0 and exposes no \
             parallel verdict of its own.",
};

pub(super) const PLANE_PARALLEL_EPSILON: Divergence = Divergence {
    query: "intersect",
    what: "segment–plane: a missing segment with |n̂ · (p1 − p0)| ≤ machine epsilon is called \
           parallel although it is not",
    reason: "line_toi_with_halfspace treats relative_eq!(n̂ · dir, 0), i.e. an absolute \
             |n̂ · dir| ≤ ε in length units, as parallel; crashtest's parallel is exact.",
};

pub(super) const CLAMPED_BARYCENTRICS: Divergence = Divergence {
    query: "barycentric",
    what: "a point whose projection lies outside the triangle gets the clamped (non-negative) \
           coordinates of the triangle's closest point, not signed ones",
    reason: "project_local_point_and_get_location projects onto the triangle, not its plane; \
             its edge and vertex regions carry no signed coordinates to translate.",
};

pub(super) const CENTROID_SPHERE: Divergence = Divergence {
    query: "bounds",
    what: "bounding sphere: centroid and farthest point, larger than the minimal sphere",
    reason: "point_cloud_bounding_sphere centres the sphere on the centroid; it encloses the \
             points but does not reach min_radius in general.",
};

pub(super) const MESH_END_HIT: Divergence = Divergence {
    query: "intersect",
    what: "segment–mesh: a hit exactly at the segment's end (t = 1) is missed",
    reason: "the TriMesh ray cast runs Bvh::find_best with the maximum time of impact as its \
             starting cost and keeps a node or a triangle only when its cost is strictly below \
             the best so far (partitioning/bvh/bvh_traverse.rs), so a time of impact equal to the \
             maximum never qualifies; a single triangle's cast (toi ≤ max) keeps it.",
};

pub(super) const MESH_TIE_FACE: Divergence = Divergence {
    query: "intersect",
    what: "segment–mesh: a segment through an edge or vertex shared by faces reports the face \
           parry's BVH reaches first, not the lowest face index",
    reason: "Bvh::find_best replaces the best hit only by a strictly smaller time of impact, so \
             among equal ones the first visited wins, in the order of its traversal; crashtest's \
             rule (lowest index) is not parry's, and the face's normal and barycentrics follow it.",
};

pub(super) const MESH_NO_PARALLEL: Divergence = Divergence {
    query: "intersect",
    what: "segment–mesh: a segment parallel to every face (a flat mesh and a segment in its plane) \
           is a plain miss, parallel = false",
    reason: "the TriMesh ray cast goes through local_ray_intersection_with_triangle, which returns \
             None for n · dir = 0 and exposes no parallel verdict; the mesh has none either.",
};

pub(super) const BOX_RAY_FROM_INSIDE: Divergence = Divergence {
    query: "intersect",
    what: "segment–box: a segment starting in the box is hit at t = 0 with a zero normal",
    reason: "a solid Cuboid ray cast whose origin is inside returns time_of_impact 0 and a zero \
             normal (RayIntersection's documentation: at a time of impact of exactly zero the \
             normal is not reliable); crashtest's normal there is the face nearest the start, which \
             parry does not compute.",
};

pub(super) const CAPSULE_RAY_FROM_INSIDE: Divergence = Divergence {
    query: "intersect",
    what: "segment–capsule: a segment starting in the capsule is hit at t = 0 with a zero normal",
    reason: "the capsule's ray cast (query/ray/ray_capsule.rs) returns time_of_impact 0 and a zero \
             normal for an origin inside a solid capsule, as the cuboid's does (RayIntersection: at \
             a time of impact of exactly zero the normal is not reliable); crashtest's normal there \
             is the start's outward direction from the axis.",
};

pub(super) const BOX_TIE_NO_FLAG: Divergence = Divergence {
    query: "contact",
    what: "sphere–box: a centre tied between faces (on an edge or a corner, or as near to two \
           faces inside) is not flagged degenerate",
    reason: "parry's Contact has no degenerate flag: at a tie it answers one of the tied faces' \
             normals with the right point and depth, and nothing says that another face would do \
             as well (the rule covers only answers equal to the format's but for the flag).",
};

pub(super) const DISTANCE_NO_FLAG: Divergence = Divergence {
    query: "distance",
    what: "distance: witnesses that are not unique (parallel faces or edges) are not flagged degenerate",
    reason: "parry's Contact has no degenerate flag: it answers one pair of the witness sets, which the \
             format allows, and nothing says that another pair would do as well (the rule covers only \
             answers that differ from the referee's in the flag alone).",
};

/// The shared divergences, in the order [`known_divergences`] lists them per engine.
pub(super) const DIVERGENCES: [Divergence; 14] = [
    TOUCHING_SPHERES,
    CONCENTRIC_SPHERES,
    CENTRE_NEAR_TRIANGLE,
    NO_TRIANGLE_PARALLEL,
    PLANE_PARALLEL_EPSILON,
    CLAMPED_BARYCENTRICS,
    CENTROID_SPHERE,
    MESH_END_HIT,
    MESH_TIE_FACE,
    MESH_NO_PARALLEL,
    BOX_RAY_FROM_INSIDE,
    BOX_TIE_NO_FLAG,
    CAPSULE_RAY_FROM_INSIDE,
    DISTANCE_NO_FLAG,
];

static KNOWN: [KnownDivergence; 2 * DIVERGENCES.len()] = stamp_both_engines();

/// [`DIVERGENCES`] stamped with [`Parry64::NAME`], then with [`Parry32::NAME`].
const fn stamp_both_engines() -> [KnownDivergence; 2 * DIVERGENCES.len()] {
    const BLANK: KnownDivergence = KnownDivergence { engine: "", query: "", what: "", reason: "" };
    let mut out = [BLANK; 2 * DIVERGENCES.len()];
    let engines = [Parry64::NAME, Parry32::NAME];
    let mut e = 0;
    while e < engines.len() {
        let mut i = 0;
        while i < DIVERGENCES.len() {
            let d = DIVERGENCES[i];
            out[e * DIVERGENCES.len() + i] =
                KnownDivergence { engine: engines[e], query: d.query, what: d.what, reason: d.reason };
            i += 1;
        }
        e += 1;
    }
    out
}
