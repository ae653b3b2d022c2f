#!/usr/bin/env python3
"""coal: the Coal collision library (coal-library/coal, the successor of hpp-fcl),
through its Python bindings (`import coal`), behind crashtest-engine/1.

Every answer is Coal's own: `coal.collide` for contacts, `coal.AABB.overlap` for box
tests, `BVHModelBase.computeLocalAABB` for bounds. The only arithmetic this adapter does
is the convention translation in `to_format_contact` (negating Coal's normal and its
signed distance). See README.md for the convention table and the sources it rests on.
"""
import os
import sys

# Protect the protocol: keep the real standard output for the protocol's lines only,
# and point file descriptor 1 at standard error *before* Coal (a C++ library) is
# loaded, so that nothing the native code prints to fd 1 can land in the protocol
# stream. The common module writes to `sys.stdout`, which becomes the duplicated fd.
_PROTOCOL_FD = os.dup(1)
os.dup2(2, 1)
sys.stdout = os.fdopen(_PROTOCOL_FD, "w", encoding="utf-8", newline="\n")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from crashtest_engine import Unsupported, package_version, serve, timed  # noqa: E402
from reproduce import reproductions  # noqa: E402  (this folder's reproduce.py)

import numpy as np  # noqa: E402
import coal  # noqa: E402

NAME = "coal"

# ---------------------------------------------------------------------------------
# The engine's settings (all echoed in the hello's provenance).
# ---------------------------------------------------------------------------------
REQUEST = coal.CollisionRequest()
REQUEST.security_margin = 0.0      # no inflation: contact iff signed distance <= threshold
REQUEST.num_max_contacts = 1       # one contact: the deepest (the only one for these pairs)
REQUEST.enable_contact = True      # compute normal, witness points and signed distance
# break_distance (BVH traversal only), distance_upper_bound, GJK/EPA settings are left
# at Coal's defaults: sphere-sphere, sphere-halfspace and sphere-triangle are analytic
# in Coal (src/narrowphase/details.h) and never run GJK/EPA.
# `collision_distance_threshold` (QueryRequest, default Eigen dummy_precision = 1e-12)
# is not exposed by the Python bindings, so it stays at 1e-12.
COLLISION_DISTANCE_THRESHOLD = "1e-12 (Coal default, Eigen::NumTraits<double>::dummy_precision(); not exposed in the Python bindings)"


def _identity_at(p):
    tf = coal.Transform3s()
    tf.setTranslation(np.array(p, dtype=np.float64))
    return tf


def _identity():
    return coal.Transform3s()


def coal_shape(shape):
    """A case's shape as Coal geometry and its placement (no arithmetic on the inputs)."""
    kind, s = next(iter(shape.items()))
    if kind == "sphere":
        return coal.Sphere(float(s["radius"])), _identity_at(s["center"])
    if kind == "plane":
        # The format's contact plane is the solid half-space n.x <= d: Coal's Halfspace
        # (include/coal/shape/geometric_shapes.h: inside is {x | n.x < d}); Coal
        # normalizes n and d itself (Halfspace::unitNormalTest, src/shape/geometric_shapes.cpp).
        return coal.Halfspace(np.array(s["normal"], dtype=np.float64), float(s["offset"])), _identity()
    if kind == "triangle":
        v = [np.array(p, dtype=np.float64) for p in s["vertices"]]
        return coal.TriangleP(v[0], v[1], v[2]), _identity()
    if kind == "mesh":  # always inline on the wire; every face, each a two-sided triangle
        return mesh_model(s), _identity()
    raise Unsupported(f"no Coal shape for {kind}")


def mesh_model(s):
    """A BVHModelOBBRSS of the mesh's vertices and faces (the wire's numbers are floats;
    the indices are made integers)."""
    verts = np.array(s["vertices"], dtype=np.float64).reshape(-1, 3)
    tris = np.array([[int(i) for i in t] for t in s["triangles"]], dtype=np.int64).reshape(-1, 3)
    # Coal does not check indices (one past the vertices is read from beyond the array and
    # the process dies): malformed input, never sent by crashtest, refused here.
    if tris.size and (tris.min() < 0 or tris.max() >= len(verts)):
        raise ValueError("mesh index out of range (Coal would read past its vertex array)")
    model = coal.BVHModelOBBRSS()
    model.beginModel(len(tris), len(verts))
    model.addVertices(verts)
    model.addTriangles(tris)
    status = model.endModel()
    if status != 0:
        raise RuntimeError(f"BVHModel endModel returned {status}")
    return model


def mesh_request(faces):
    """REQUEST's settings with room for one contact per face: Coal's mesh-shape traversal
    (MeshShapeCollisionTraversalNode) adds one Contact per touching face, in its BVH
    order, and stops at num_max_contacts, so with 1 it answers the first face it meets,
    not the nearest."""
    r = coal.CollisionRequest()
    r.security_margin = REQUEST.security_margin
    r.enable_contact = REQUEST.enable_contact
    r.num_max_contacts = max(1, faces)
    return r


# ---------------------------------------------------------------------------------
# THE CONVENTION TRANSLATION (the only one in this adapter).
#
# Coal's Contact (include/coal/collision_data.h, struct Contact):
#   normal             unit, points from o1 (= case's a) to o2 (= case's b)
#   nearest_points[0]  witness point on o1, nearest_points[1] witness point on o2
#                      (getNearestPoint1/2 in Python; `pos` is their midpoint)
#   penetration_depth  the SIGNED distance (negative when the shapes overlap):
#                      ShapeShapeCollider builds Contact(o1, o2, .., p1, p2, normal,
#                      distance) (include/coal/internal/shape_shape_func.h)
# The format: normal from b toward a, point on b's surface, depth >= 0 the penetration.
# So: normal = -Coal normal, point = Coal's witness point on o2 = b, depth = -signed
# distance. Same rule for every pair and both orders (Coal handles the order itself).
# Sphere-mesh: the same rule (checked on the tetrahedron fixtures: o1 = the sphere,
# b1 = -1; o2 = the mesh, b2 = the face index; witness point 2 the face's closest point).
# Coal gives one Contact per touching face; `pick_contact` takes the deepest (smallest
# signed distance, Coal's own number), on a tie the lowest face index (b2).
# ---------------------------------------------------------------------------------
def pick_contact(result):
    contacts = [result.getContact(i) for i in range(result.numContacts())]
    return min(contacts, key=lambda c: (float(c.penetration_depth), int(c.b2)))


def to_format_contact(c):
    n = c.normal
    p = c.getNearestPoint2()
    return {
        "point": [float(p[0]), float(p[1]), float(p[2])],
        "normal": [-float(n[0]), -float(n[1]), -float(n[2])],
        "depth": -float(c.penetration_depth),
    }


def contact(case):
    ga, ta = coal_shape(case["a"])
    gb, tb = coal_shape(case["b"])
    kb = next(iter(case["b"]))
    request = mesh_request(len(case["b"]["mesh"]["triangles"])) if kb == "mesh" else REQUEST
    result = coal.CollisionResult()
    timed(coal.collide, ga, ta, gb, tb, request, result)
    if not result.isCollision():
        return {"contact": None}
    return {"contact": to_format_contact(pick_contact(result))}


def overlap(case):
    A, B = case["a"]["aabb"], case["b"]["aabb"]
    box_a = coal.AABB(np.array(A["min"], dtype=np.float64), np.array(A["max"], dtype=np.float64))
    box_b = coal.AABB(np.array(B["min"], dtype=np.float64), np.array(B["max"], dtype=np.float64))
    return {"overlap": bool(timed(box_a.overlap, box_b))}


def bounds(case):
    kind, s = next(iter(case["a"].items()))
    if kind == "points":
        model = coal.BVHModelOBBRSS()
        verts = np.array(s["points"], dtype=np.float64).reshape(-1, 3)
        model.beginModel(0, len(verts))
        model.addVertices(verts)
        status = model.endModel()
        if status != 0:
            raise RuntimeError(f"BVHModel endModel returned {status}")
    else:  # mesh (always inline on the wire)
        model = mesh_model(s)
    timed(model.computeLocalAABB)
    box = model.aabb_local
    lo, hi, c = box.min_, box.max_, model.aabb_center
    return {
        "aabb": {"min": [float(x) for x in lo], "max": [float(x) for x in hi]},
        "sphere": {"center": [float(x) for x in c], "radius": float(model.aabb_radius)},
    }


HANDLERS = {
    ("contact", "sphere", "sphere"): contact,
    ("contact", "sphere", "plane"): contact,
    ("contact", "plane", "sphere"): contact,
    ("contact", "sphere", "triangle"): contact,
    ("contact", "triangle", "sphere"): contact,
    ("contact", "sphere", "mesh"): contact,
    ("overlap", "aabb", "aabb"): overlap,
    ("bounds", "points", None): bounds,
    ("bounds", "mesh", None): bounds,
}


def provenance():
    r = REQUEST
    return {
        "coal (package)": package_version("coal"),
        "libcoal (package)": package_version("libcoal"),
        "coal library version": f"{coal.COAL_MAJOR_VERSION}.{coal.COAL_MINOR_VERSION}.{coal.COAL_PATCH_VERSION}",
        "eigenpy": package_version("eigenpy"),
        "numpy": package_version("numpy"),
        "python": sys.version.split()[0],
        "scalar": "double (CoalScalar = f64)",
        "contact call": "coal.collide(geom_a, tf_a, geom_b, tf_b, CollisionRequest, CollisionResult)",
        "plane as": "coal.Halfspace(n, d) (solid n.x <= d)",
        "triangle as": "coal.TriangleP (two-sided)",
        "mesh as": "coal.BVHModelOBBRSS of every face (contact: num_max_contacts = the number of faces, "
                   "the deepest contact taken, ties to the lowest face index)",
        "security_margin": repr(r.security_margin),
        "collision_distance_threshold": COLLISION_DISTANCE_THRESHOLD,
        "break_distance": repr(r.break_distance) + " (default; BVH traversal only, unused by these pairs)",
        "distance_upper_bound": repr(r.distance_upper_bound) + " (default)",
        "num_max_contacts": str(r.num_max_contacts) + " (sphere-mesh: the number of faces)",
        "enable_contact": str(r.enable_contact),
        "swept_sphere_radius": "0 (default on every shape)",
        "gjk": f"variant={r.gjk_variant}, tolerance={r.gjk_tolerance!r}, max_iterations={r.gjk_max_iterations}, "
               f"initial_guess={r.gjk_initial_guess}, convergence={r.gjk_convergence_criterion}/"
               f"{r.gjk_convergence_criterion_type} (defaults; unused: these pairs are analytic)",
        "epa": f"tolerance={r.epa_tolerance!r}, max_iterations={r.epa_max_iterations} (defaults; unused)",
        "overlap": "coal.AABB(min, max).overlap(other) (closed boxes)",
        "bounds": "BVHModelOBBRSS (point cloud or triangles) -> computeLocalAABB(): aabb_local, aabb_center, aabb_radius",
        "stdout": "fd 1 redirected to stderr before import; protocol on a duplicate of the original fd 1",
    }


if __name__ == "__main__":
    sys.exit(serve(NAME, package_version("coal"), 53, HANDLERS, provenance(),
                   reproductions=reproductions(HANDLERS)))
