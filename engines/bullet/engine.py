#!/usr/bin/env python3
"""bullet: Bullet Physics (pybullet 3.2.7) behind crashtest-engine/1.

Every answer is pybullet's own: getClosestPoints (btCollisionWorld::contactPairTest)
for `contact` and `overlap`, rayTest (btCollisionWorld::rayTest, ClosestRayResultCallback)
for `intersect`. The conventions Bullet uses are translated in ONE place, the section
"CONVENTION TRANSLATION" below; README.md has the table and the sources.
"""
import math
import os
import sys

# --- Protecting the protocol's standard output --------------------------------------
# pybullet prints "pybullet build time: ..." with C printf to fd 1 on import, and its
# b3Warning/b3Printf messages go to fd 1 too. The protocol gets a duplicate of the real
# fd 1; fd 1 itself is pointed at standard error before pybullet is imported, so nothing
# the C library prints can reach crashtest's reader. sys.stdout (which the common
# module's `send` writes to) is the duplicate.
_PROTOCOL_FD = os.dup(1)
os.dup2(2, 1)
sys.stdout = os.fdopen(_PROTOCOL_FD, "w", encoding="utf-8", newline="\n")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from crashtest_engine import Unsupported, package_version, serve, timed  # noqa: E402

import pybullet as p  # noqa: E402  (prints its build time to fd 1 = standard error)

CLIENT = p.connect(p.DIRECT)

# --- Engine settings (echoed in the hello's provenance) -----------------------------
MARGIN = 0.0           # collisionMargin set with changeDynamics on every non-sphere body
DISTANCE = 0.0         # getClosestPoints' distance: points with contactDistance <= 0 only
RESET_EVERY = 256      # bodies created before p.resetSimulation() frees the leaked shapes

# pybullet cannot free a collision shape once a body has used it (removeCollisionShape
# answers "Don't remove collision shape: it is used" even after removeBody), so the
# world is reset now and then, outside the timed calls. resetSimulation() keeps
# gContactBreakingThreshold and the other settings used here.
_created = 0


def _housekeeping():
    global _created
    if _created >= RESET_EVERY:
        p.resetSimulation()
        _created = 0


def _body(shape, position):
    """A static (mass 0) body of `shape` at `position`, identity orientation."""
    global _created
    _created += 1
    return p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition=position)


def _zero_margin(body):
    p.changeDynamics(body, -1, collisionMargin=MARGIN)


# --- Building Bullet's shapes from the case's shapes -------------------------------
# Only the inputs are converted here; nothing about the answer is computed.

def make_sphere(s):
    # btSphereShape: its margin *is* its radius (btSphereShape::getMargin returns
    # getRadius()), so a collisionMargin setting has no effect on it and is not sent.
    shape = p.createCollisionShape(p.GEOM_SPHERE, radius=s["radius"])
    return _body(shape, s["center"])


def make_plane(pl):
    # GEOM_PLANE is btStaticPlaneShape(n, constant) with pybullet's constant always 0;
    # Bullet normalizes n itself. The plane n.x = d is placed by moving the body to the
    # point (d/|n|) * n/|n| (the input converted; |n| by math.hypot).
    n = pl["normal"]
    ln = math.hypot(*n)
    s = pl["offset"] / ln
    body = _body(p.createCollisionShape(p.GEOM_PLANE, planeNormal=n), [n[0] / ln * s, n[1] / ln * s, n[2] / ln * s])
    _zero_margin(body)
    return body


def make_trimesh(vertices, triangles):
    # vertices + indices: pybullet always builds a btBvhTriangleMeshShape (concave, static)
    # inside a btCompoundShape (PhysicsServerCommandProcessor.cpp, GEOM_MESH with
    # m_numIndices); GEOM_FORCE_CONCAVE_TRIMESH is passed only to make that explicit.
    indices = [int(i) for t in triangles for i in t]
    # pybullet does not check indices: one past the vertices reads memory beyond the
    # upload buffer (PhysicsServerCommandProcessor.cpp, "convert trimesh2"). Such a mesh
    # is malformed input (crashtest never sends it) and is refused here, not passed on.
    if any(i < 0 or i >= len(vertices) for i in indices):
        raise ValueError("mesh index out of range (pybullet would read past its vertex buffer)")
    shape = p.createCollisionShape(p.GEOM_MESH, vertices=vertices, indices=indices, flags=p.GEOM_FORCE_CONCAVE_TRIMESH)
    body = _body(shape, [0.0, 0.0, 0.0])
    _zero_margin(body)
    return body


def make_box(b):
    # GEOM_BOX is btBoxShape(half extents) centred on the body; halves taken before the
    # difference and the sum so that no finite input overflows.
    lo, hi = b["min"], b["max"]
    half = [0.5 * hi[i] - 0.5 * lo[i] for i in range(3)]
    centre = [0.5 * lo[i] + 0.5 * hi[i] for i in range(3)]
    body = _body(p.createCollisionShape(p.GEOM_BOX, halfExtents=half), centre)
    _zero_margin(body)
    return body


def make(shape):
    kind, s = next(iter(shape.items()))
    if kind == "sphere":
        return make_sphere(s)
    if kind == "plane":
        return make_plane(s)
    if kind == "triangle":
        return make_trimesh(s["vertices"], [[0, 1, 2]])
    if kind == "mesh":
        return make_trimesh(s["vertices"], s["triangles"])
    if kind == "aabb":
        return make_box(s)
    raise Unsupported(f"no Bullet shape for {kind}")


def _cross(u, v):
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


# ======================= CONVENTION TRANSLATION (the only one) =======================
# getClosestPoints(A, B) returns points (.., positionOnA, positionOnB, contactNormalOnB,
# contactDistance, ..): the normal points from B toward A, positionOnB lies on B's
# surface, contactDistance < 0 is penetration. pybullet reorders Bullet's manifold into
# (A, B) itself (isSwapped in PhysicsServerCommandProcessor.cpp), so for every order:
#   point = positionOnB, normal = contactNormalOnB, depth = -contactDistance.
# Several points (not seen for these pairs): the one with the smallest contactDistance.
def contact_from_points(points):
    if not points:
        return {"contact": None}
    pt = min(points, key=lambda q: q[8])
    return {"contact": {"point": list(pt[6]), "normal": list(pt[7]), "depth": -pt[8]}}


# rayTest(from, to) returns (objectUniqueId, linkIndex, hitFraction, hitPosition,
# hitNormal); objectUniqueId -1 is no hit. t = hitFraction, point = hitPosition.
# btTriangleRaycastCallback flips the face normal toward the ray's start when the ray
# enters from the back (pybullet never sets kF_KeepUnflippedNormal). For a plane and a
# triangle the face is known, so the normal is flipped back when it opposes the face
# normal given in the case (plane: n; triangle: (v1 - v0) x (v2 - v0)); only its sign is
# read. For a mesh pybullet does not say which face was hit, so the normal is left as
# Bullet gives it (facing the segment's start). No barycentric, no face index, no
# `parallel`: pybullet reports none of them.
def hit_from_ray(result, face_normal):
    obj, _link, frac, pos, nrm = result
    if obj < 0:
        return {"hit": None}
    n = list(nrm)
    if face_normal is not None and sum(n[i] * face_normal[i] for i in range(3)) < 0:
        n = [-n[0], -n[1], -n[2]]
    return {"hit": {"t": frac, "point": list(pos), "normal": n}}
# =====================================================================================


def contact(case):
    _housekeeping()
    a, b = make(case["a"]), make(case["b"])
    try:
        points = timed(p.getClosestPoints, a, b, DISTANCE)
    finally:
        p.removeBody(a)
        p.removeBody(b)
    return contact_from_points(points)


def intersect(case):
    _housekeeping()
    seg = case["a"]["segment"]
    kind, s = next(iter(case["b"].items()))
    if kind == "plane":
        face = s["normal"]
    elif kind == "triangle":
        v = s["vertices"]
        face = _cross([v[1][i] - v[0][i] for i in range(3)], [v[2][i] - v[0][i] for i in range(3)])
    else:
        face = None
    body = make(case["b"])
    try:
        result = timed(p.rayTest, seg["start"], seg["end"])[0]
    finally:
        p.removeBody(body)
    return hit_from_ray(result, face)


def overlap(case):
    # Two btBoxShape bodies with margin 0; getClosestPoints(distance 0) runs Bullet's
    # convex-convex closest-point algorithm (GJK, EPA when penetrating). Any point with
    # contactDistance <= 0 means the boxes overlap (touching included).
    _housekeeping()
    a, b = make(case["a"]), make(case["b"])
    try:
        points = timed(p.getClosestPoints, a, b, DISTANCE)
    finally:
        p.removeBody(a)
        p.removeBody(b)
    return {"overlap": len(points) > 0}


HANDLERS = {
    ("contact", "sphere", "sphere"): contact,
    ("contact", "sphere", "plane"): contact,
    ("contact", "plane", "sphere"): contact,
    ("contact", "sphere", "triangle"): contact,
    ("contact", "triangle", "sphere"): contact,
    ("intersect", "segment", "plane"): intersect,
    ("intersect", "segment", "triangle"): intersect,
    ("intersect", "segment", "mesh"): intersect,
    ("overlap", "aabb", "aabb"): overlap,
}

PROVENANCE = {
    "pybullet": package_version("pybullet"),
    "pybullet_api_version": str(p.getAPIVersion()),
    "bullet_source": "bulletphysics/bullet3 6c888f4 (2025-01-29), the pybullet 3.2.7 build",
    "precision": "f64 (setup.py builds Bullet with -DBT_USE_DOUBLE_PRECISION)",
    "connection": "p.DIRECT",
    "collision_margin": "0 via changeDynamics(collisionMargin=0) on plane, mesh and box bodies "
                        "(pybullet's default is 0.001); a sphere's margin is its radius by definition",
    "contact_query": "getClosestPoints(bodyA, bodyB, distance=0): contactDistance <= 0 only",
    "contact_breaking_threshold": "Bullet default gContactBreakingThreshold 0.02 (not changed)",
    "ray_query": "rayTest(from, to): ClosestRayResultCallback, flags kF_UseGjkConvexCastRaytest, "
                 "normal flipped back to the face's own for plane and triangle",
    "triangle_shape": "GEOM_MESH vertices+indices -> btBvhTriangleMeshShape in a btCompoundShape (two-sided)",
    "plane_shape": "GEOM_PLANE -> btStaticPlaneShape(n, 0), body at (d/|n|) n/|n|",
}

if __name__ == "__main__":
    sys.exit(serve("bullet", package_version("pybullet"), 53, HANDLERS, PROVENANCE))
