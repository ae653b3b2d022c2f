//! The table of query pairs: which (query, shape `a`, shape `b`) combinations the
//! fixture format has. [`PAIRS`] is the only place that lists them.
//!
//! Everything else is derived from it: the loader accepts a case exactly when
//! [`Pair::find`] knows its kinds; the harness's dispatch to [`crate::engine::Queries`],
//! the referee's answers and margins and the generators are `match`es over
//! [`Pair`], so the compiler refuses a pair that one of them forgets; and a
//! coverage test walks [`Pair::ALL`] to check that every pair has a generator,
//! fixtures, a referee answer and a sweep or a stated reason why not.
//!
//! A new pair is a new [`Pair`] variant and its [`PAIRS`] row; `docs/PAIRS.md`
//! lists the files the compiler then sends you to.

use std::fmt;

/// The query kinds of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema),
    serde(rename_all = "lowercase")
)]
pub enum Query {
    /// Sphere, box or capsule against its partners: point, normal, depth.
    Contact,
    /// Segment against plane, triangle, mesh or box: first hit.
    Intersect,
    /// Signed barycentric coordinates of a point's projection on a triangle.
    Barycentric,
    /// AABB and minimal bounding sphere of points, a mesh or a box.
    Bounds,
    /// Box against box (axis-aligned or oriented).
    Overlap,
    /// Time of impact of a moving sphere.
    Toi,
    /// Velocities after one frictionless impulse.
    Response,
    /// Continuous collision of linearly moving points: vertex–face and edge–edge.
    Ccd,
    /// Signed distance of two solids (GJK and EPA's query).
    Distance,
}

impl Query {
    /// Every query kind, in the format's order.
    pub const ALL: [Query; 9] = [
        Query::Contact,
        Query::Intersect,
        Query::Barycentric,
        Query::Bounds,
        Query::Overlap,
        Query::Toi,
        Query::Response,
        Query::Ccd,
        Query::Distance,
    ];

    /// The name used in fixture files.
    pub fn as_str(self) -> &'static str {
        match self {
            Query::Contact => "contact",
            Query::Intersect => "intersect",
            Query::Barycentric => "barycentric",
            Query::Bounds => "bounds",
            Query::Overlap => "overlap",
            Query::Toi => "toi",
            Query::Response => "response",
            Query::Ccd => "ccd",
            Query::Distance => "distance",
        }
    }

    /// The query named `s` in fixture files.
    pub fn parse(s: &str) -> Option<Query> {
        Query::ALL.into_iter().find(|q| q.as_str() == s)
    }

    /// The pairs of this query, in table order.
    pub fn pairs(self) -> impl Iterator<Item = Pair> {
        Pair::ALL.into_iter().filter(move |p| p.query() == self)
    }
}

impl fmt::Display for Query {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The shape kinds of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema),
    serde(rename_all = "snake_case")
)]
pub enum ShapeKind {
    /// `sphere`.
    Sphere,
    /// `plane`.
    Plane,
    /// `segment`.
    Segment,
    /// `triangle`.
    Triangle,
    /// `point`.
    Point,
    /// `points`.
    Points,
    /// `mesh`.
    Mesh,
    /// `aabb`.
    Aabb,
    /// `moving_point`.
    MovingPoint,
    /// `moving_segment`.
    MovingSegment,
    /// `moving_triangle`.
    MovingTriangle,
    /// `box`: a solid box that may be rotated.
    Box,
    /// `capsule`.
    Capsule,
    /// `convex`: the convex hull of points.
    Convex,
}

impl ShapeKind {
    /// The shape's key in fixture files.
    pub fn as_str(self) -> &'static str {
        match self {
            ShapeKind::Sphere => "sphere",
            ShapeKind::Plane => "plane",
            ShapeKind::Segment => "segment",
            ShapeKind::Triangle => "triangle",
            ShapeKind::Point => "point",
            ShapeKind::Points => "points",
            ShapeKind::Mesh => "mesh",
            ShapeKind::Aabb => "aabb",
            ShapeKind::MovingPoint => "moving_point",
            ShapeKind::MovingSegment => "moving_segment",
            ShapeKind::MovingTriangle => "moving_triangle",
            ShapeKind::Box => "box",
            ShapeKind::Capsule => "capsule",
            ShapeKind::Convex => "convex",
        }
    }
}

impl fmt::Display for ShapeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One (query, shape `a`, shape `b`) combination of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[allow(missing_docs, reason = "each variant is its row of `PAIRS`, which says what it is")]
pub enum Pair {
    ContactSphereSphere,
    ContactSpherePlane,
    ContactPlaneSphere,
    ContactSphereTriangle,
    ContactTriangleSphere,
    ContactSphereMesh,
    ContactSphereBox,
    ContactBoxPlane,
    ContactSphereCapsule,
    ContactCapsuleCapsule,
    ContactCapsulePlane,
    ContactBoxBox,
    ContactBoxTriangle,
    ContactCapsuleBox,
    ContactCapsuleTriangle,
    IntersectSegmentPlane,
    IntersectSegmentTriangle,
    IntersectSegmentMesh,
    IntersectSegmentBox,
    IntersectSegmentCapsule,
    BarycentricPointTriangle,
    BoundsPoints,
    BoundsMesh,
    BoundsBox,
    OverlapAabbAabb,
    OverlapBoxBox,
    OverlapBoxAabb,
    ToiSphereSphere,
    ToiSpherePlane,
    ToiSphereTriangle,
    ToiSphereMesh,
    ToiSphereBox,
    ResponseSphereSphere,
    ResponseSpherePlane,
    CcdPointTriangle,
    CcdSegmentSegment,
    DistanceSphereSphere,
    DistanceSpherePlane,
    DistanceSphereTriangle,
    DistanceSphereBox,
    DistanceSphereCapsule,
    DistanceSphereConvex,
    DistanceBoxPlane,
    DistanceBoxBox,
    DistanceBoxTriangle,
    DistanceCapsuleCapsule,
    DistanceCapsulePlane,
    DistanceCapsuleBox,
    DistanceCapsuleTriangle,
    DistanceCapsuleConvex,
    DistanceConvexConvex,
    DistanceConvexPlane,
    DistanceConvexBox,
    DistanceConvexTriangle,
}

/// A row of the pair table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PairRow {
    /// The pair.
    pub pair: Pair,
    /// Its query.
    pub query: Query,
    /// Shape `a`'s kind.
    pub a: ShapeKind,
    /// Shape `b`'s kind (`None` for `bounds`, which takes one shape).
    pub b: Option<ShapeKind>,
}

const fn row(pair: Pair, query: Query, a: ShapeKind, b: Option<ShapeKind>) -> PairRow {
    PairRow { pair, query, a, b }
}

use Pair as P;
use Query as Q;
use ShapeKind as K;

/// The pair table, in report order (query by query, as the format lists them).
pub const PAIRS: [PairRow; 54] = [
    row(P::ContactSphereSphere, Q::Contact, K::Sphere, Some(K::Sphere)),
    row(P::ContactSpherePlane, Q::Contact, K::Sphere, Some(K::Plane)),
    row(P::ContactPlaneSphere, Q::Contact, K::Plane, Some(K::Sphere)),
    row(P::ContactSphereTriangle, Q::Contact, K::Sphere, Some(K::Triangle)),
    row(P::ContactTriangleSphere, Q::Contact, K::Triangle, Some(K::Sphere)),
    row(P::ContactSphereMesh, Q::Contact, K::Sphere, Some(K::Mesh)),
    row(P::ContactSphereBox, Q::Contact, K::Sphere, Some(K::Box)),
    row(P::ContactBoxPlane, Q::Contact, K::Box, Some(K::Plane)),
    row(P::ContactSphereCapsule, Q::Contact, K::Sphere, Some(K::Capsule)),
    row(P::ContactCapsuleCapsule, Q::Contact, K::Capsule, Some(K::Capsule)),
    row(P::ContactCapsulePlane, Q::Contact, K::Capsule, Some(K::Plane)),
    row(P::ContactBoxBox, Q::Contact, K::Box, Some(K::Box)),
    row(P::ContactBoxTriangle, Q::Contact, K::Box, Some(K::Triangle)),
    row(P::ContactCapsuleBox, Q::Contact, K::Capsule, Some(K::Box)),
    row(P::ContactCapsuleTriangle, Q::Contact, K::Capsule, Some(K::Triangle)),
    row(P::IntersectSegmentPlane, Q::Intersect, K::Segment, Some(K::Plane)),
    row(P::IntersectSegmentTriangle, Q::Intersect, K::Segment, Some(K::Triangle)),
    row(P::IntersectSegmentMesh, Q::Intersect, K::Segment, Some(K::Mesh)),
    row(P::IntersectSegmentBox, Q::Intersect, K::Segment, Some(K::Box)),
    row(P::IntersectSegmentCapsule, Q::Intersect, K::Segment, Some(K::Capsule)),
    row(P::BarycentricPointTriangle, Q::Barycentric, K::Point, Some(K::Triangle)),
    row(P::BoundsPoints, Q::Bounds, K::Points, None),
    row(P::BoundsMesh, Q::Bounds, K::Mesh, None),
    row(P::BoundsBox, Q::Bounds, K::Box, None),
    row(P::OverlapAabbAabb, Q::Overlap, K::Aabb, Some(K::Aabb)),
    row(P::OverlapBoxBox, Q::Overlap, K::Box, Some(K::Box)),
    row(P::OverlapBoxAabb, Q::Overlap, K::Box, Some(K::Aabb)),
    row(P::ToiSphereSphere, Q::Toi, K::Sphere, Some(K::Sphere)),
    row(P::ToiSpherePlane, Q::Toi, K::Sphere, Some(K::Plane)),
    row(P::ToiSphereTriangle, Q::Toi, K::Sphere, Some(K::Triangle)),
    row(P::ToiSphereMesh, Q::Toi, K::Sphere, Some(K::Mesh)),
    row(P::ToiSphereBox, Q::Toi, K::Sphere, Some(K::Box)),
    row(P::ResponseSphereSphere, Q::Response, K::Sphere, Some(K::Sphere)),
    row(P::ResponseSpherePlane, Q::Response, K::Sphere, Some(K::Plane)),
    row(P::CcdPointTriangle, Q::Ccd, K::MovingPoint, Some(K::MovingTriangle)),
    row(P::CcdSegmentSegment, Q::Ccd, K::MovingSegment, Some(K::MovingSegment)),
    row(P::DistanceSphereSphere, Q::Distance, K::Sphere, Some(K::Sphere)),
    row(P::DistanceSpherePlane, Q::Distance, K::Sphere, Some(K::Plane)),
    row(P::DistanceSphereTriangle, Q::Distance, K::Sphere, Some(K::Triangle)),
    row(P::DistanceSphereBox, Q::Distance, K::Sphere, Some(K::Box)),
    row(P::DistanceSphereCapsule, Q::Distance, K::Sphere, Some(K::Capsule)),
    row(P::DistanceSphereConvex, Q::Distance, K::Sphere, Some(K::Convex)),
    row(P::DistanceBoxPlane, Q::Distance, K::Box, Some(K::Plane)),
    row(P::DistanceBoxBox, Q::Distance, K::Box, Some(K::Box)),
    row(P::DistanceBoxTriangle, Q::Distance, K::Box, Some(K::Triangle)),
    row(P::DistanceCapsuleCapsule, Q::Distance, K::Capsule, Some(K::Capsule)),
    row(P::DistanceCapsulePlane, Q::Distance, K::Capsule, Some(K::Plane)),
    row(P::DistanceCapsuleBox, Q::Distance, K::Capsule, Some(K::Box)),
    row(P::DistanceCapsuleTriangle, Q::Distance, K::Capsule, Some(K::Triangle)),
    row(P::DistanceCapsuleConvex, Q::Distance, K::Capsule, Some(K::Convex)),
    row(P::DistanceConvexConvex, Q::Distance, K::Convex, Some(K::Convex)),
    row(P::DistanceConvexPlane, Q::Distance, K::Convex, Some(K::Plane)),
    row(P::DistanceConvexBox, Q::Distance, K::Convex, Some(K::Box)),
    row(P::DistanceConvexTriangle, Q::Distance, K::Convex, Some(K::Triangle)),
];

impl Pair {
    /// Every pair, in table order.
    pub const ALL: [Pair; PAIRS.len()] = {
        let mut all = [Pair::ContactSphereSphere; PAIRS.len()];
        let mut i = 0;
        while i < PAIRS.len() {
            all[i] = PAIRS[i].pair;
            i += 1;
        }
        all
    };

    /// This pair's row of the table.
    pub fn row(self) -> &'static PairRow {
        // The table is in variant order (a test says so), so the variant's index
        // is its row.
        &PAIRS[self as usize]
    }

    /// Its query.
    pub fn query(self) -> Query {
        self.row().query
    }

    /// The pair of these kinds, if the format has it.
    pub fn find(query: Query, a: ShapeKind, b: Option<ShapeKind>) -> Option<Pair> {
        PAIRS.iter().find(|r| r.query == query && r.a == a && r.b == b).map(|r| r.pair)
    }

    /// `contact sphere–triangle`, `bounds mesh`: the pair as reports name it.
    pub fn label(self) -> String {
        let r = self.row();
        match r.b {
            Some(b) => format!("{} {}–{}", r.query, r.a, b),
            None => format!("{} {}", r.query, r.a),
        }
    }
}

impl fmt::Display for Pair {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.label())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_in_variant_order_and_each_row_is_unique() {
        for (i, r) in PAIRS.iter().enumerate() {
            assert_eq!(r.pair as usize, i, "row {i} ({}) is out of variant order", r.pair);
            assert_eq!(Pair::find(r.query, r.a, r.b), Some(r.pair), "row {i} is shadowed by an earlier row");
        }
    }

    #[test]
    fn every_query_has_a_pair_and_parses_from_its_name() {
        for q in Query::ALL {
            assert!(q.pairs().next().is_some(), "{q} has no pair");
            assert_eq!(Query::parse(q.as_str()), Some(q));
        }
    }

    #[test]
    fn a_combination_outside_the_table_is_not_found() {
        assert_eq!(Pair::find(Query::Contact, ShapeKind::Plane, Some(ShapeKind::Plane)), None);
        assert_eq!(Pair::find(Query::Bounds, ShapeKind::Mesh, Some(ShapeKind::Mesh)), None);
        assert_eq!(Pair::find(Query::Toi, ShapeKind::Sphere, Some(ShapeKind::Segment)), None);
    }
}
