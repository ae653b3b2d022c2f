#!/usr/bin/env python3
"""fcl: FCL 0.7 (the Flexible Collision Library, through the Python package
python-fcl) behind crashtest-engine/1. See README.md for what it answers, the
convention table and the divergences found.

Every number in an answer is FCL's; the adapter only builds FCL's shapes from
the case and translates FCL's conventions into the format's, in ONE place:
`to_format_contact` below.
"""
import os
import sys

# --- protect the protocol -------------------------------------------------------
# FCL writes warnings to std::cerr, but a native library may also print to fd 1.
# The protocol keeps a duplicate of fd 1; fd 1 itself is pointed at stderr before
# the engine is imported, so nothing but protocol messages reaches crashtest.
_PROTO_FD = os.dup(1)
os.dup2(2, 1)
sys.stdout = os.fdopen(_PROTO_FD, "w", encoding="utf-8", newline="\n")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from crashtest_engine import Unsupported, package_version, serve, timed  # noqa: E402

import numpy as np  # noqa: E402
import fcl  # noqa: E402

# --- settings (echoed in the hello's provenance) ----------------------------------
GJK_SOLVER = fcl.GJKSolverType.GST_LIBCCD  # FCL's default; every pair answered has a
#                                            dedicated (non-GJK) routine under it
REQUEST = dict(enable_contact=True, num_max_contacts=1, gjk_solver_type=GJK_SOLVER)

PROVENANCE = {
    "python-fcl": package_version("python-fcl"),
    "fcl.__version__": getattr(fcl, "__version__", "unknown"),
    "libfcl": "0.7.0 (ambi-robotics/fcl tag v0.7.0, as python-fcl's build script pins; libfcl.so.0.7.0)",
    "libccd": "2.1, double precision (python-fcl's build script)",
    "numpy": package_version("numpy"),
    "precision": "f64 (FCL instantiated with double, libccd built with ENABLE_DOUBLE_PRECISION)",
    "gjk_solver_type": "GST_LIBCCD",
    "collision_request": "enable_contact=True, num_max_contacts=1 (sphere-mesh: one per face; the deepest "
                         "taken, ties to the lowest face index)",
    "margins": "none (FCL shapes have no margin or envelope)",
    "plane": "fcl.Halfspace(n, d): solid n.x <= d (FCL normalizes n and d)",
    "triangle": "fcl.BVHModel (OBBRSS) holding the one triangle: FCL has no sphere-TriangleP collision",
    "mesh": "fcl.BVHModel (OBBRSS) holding every face; sphere-mesh: num_max_contacts = the number of "
            "faces (FCL's mesh-shape traversal, one contact per touching face), the deepest taken, "
            "ties to the lowest face index",
    "aabb": "fcl.Box(max - min) at translation 0.5*min + 0.5*max",
    "stdout": "fd 1 redirected to stderr before import; protocol on a duplicate of fd 1",
}


# --- building FCL's objects (no answers computed here) ----------------------------
# Each builder returns (geometry, CollisionObject). python-fcl's Contact.o1/o2 are the
# Python geometries given to collide (fcl.pyx, c_to_python_collision_geometry), so the
# geometry is kept to tell which shape FCL put first.
def vec(x):
    return np.array(x, dtype=np.float64)


def sphere_obj(s):
    g = fcl.Sphere(s["radius"])
    return g, fcl.CollisionObject(g, fcl.Transform(vec(s["center"])))


def halfspace_obj(p):
    g = fcl.Halfspace(vec(p["normal"]), p["offset"])
    return g, fcl.CollisionObject(g, fcl.Transform())


def triangle_obj(t):
    g = fcl.BVHModel()
    g.beginModel(1, 3)
    g.addSubModel([vec(v) for v in t["vertices"]], [[0, 1, 2]])
    g.endModel()
    return g, fcl.CollisionObject(g, fcl.Transform())


def box_obj(b):
    lo, hi = vec(b["min"]), vec(b["max"])
    g = fcl.Box(*(hi - lo))
    return g, fcl.CollisionObject(g, fcl.Transform(0.5 * lo + 0.5 * hi))


def mesh_obj(m):
    # every face of the mesh in one BVHModel (OBBRSS), as for the triangle; the wire's
    # indices arrive as JSON numbers (floats), hence int()
    verts = [vec(v) for v in m["vertices"]]
    tris = [[int(i) for i in t] for t in m["triangles"]]
    # FCL does not check indices (one past the vertices is read from beyond the array and
    # the process dies): malformed input, never sent by crashtest, refused here.
    if any(i < 0 or i >= len(verts) for t in tris for i in t):
        raise ValueError("mesh index out of range (FCL would read past its vertex array)")
    g = fcl.BVHModel()
    g.beginModel(len(tris), len(verts))
    g.addSubModel(verts, tris)
    g.endModel()
    return g, fcl.CollisionObject(g, fcl.Transform())


BUILD = {"sphere": sphere_obj, "plane": halfspace_obj, "triangle": triangle_obj, "mesh": mesh_obj}


def fcl_collide(o1, o2, max_contacts=1):
    req = fcl.CollisionRequest(**{**REQUEST, "num_max_contacts": max_contacts})
    res = fcl.CollisionResult()
    fcl.collide(o1, o2, req, res)
    return res


# --- THE CONVENTION TRANSLATION (the only one) ------------------------------------
# FCL's Contact (include/fcl/narrowphase/contact.h): `normal` points from the
# contact's o1 to its o2, `pos` is FCL's contact point, `penetration_depth` its depth.
# The format: normal from b toward a, point on b's surface (b's deepest point),
# depth >= 0.
#  - normal: FCL may put the mesh first whatever the call's order (collision-inl.h
#    swaps a shape-BVH call to BVH-shape and does not flip back), so the direction is
#    read from the contact's own o1: o1 is a -> negate; o1 is b -> keep.
#  - depth: sphere-sphere and sphere-halfspace give penetration > 0; the sphere-triangle
#    routine (sphere_triangle-inl.h, sphereTriangleIntersect) gives -(r - distance),
#    so it is negated for the triangle pairs.
#  - point: p_b = pos + n * depth * W, W per pair from where FCL puts `pos`:
#      sphere-sphere (sphere_sphere-inl.h): pos = c1 + (c2 - c1) r1/(r1 + r2)
#        -> W = r_b/(r_a + r_b)
#      sphere-halfspace, either order (halfspace-inl.h): pos = midway between the
#        sphere's deepest point and the plane -> W = 1/2
#      sphere-triangle: pos is the closest point of the triangle (on b) -> W = 0
#      triangle-sphere: pos is on the triangle (a); the sphere's deepest point is
#        depth further along n -> W = 1
#  - sphere-mesh: FCL's mesh-shape traversal runs the same per-face sphere-triangle
#    routine as the one-triangle BVHModel of the triangle pairs, so the same convention:
#    o1 is the mesh (= b, normal kept; b1 = the face index, b2 = -1), depth negated, pos
#    the face's closest point (W = 0) (checked on the tetrahedron fixtures: all agree).
#    FCL reports one contact per touching face, in its BVH traversal order, and stops at
#    num_max_contacts; so the mesh pair asks for one per face and `pick_contact` takes
#    the deepest by FCL's own depth, on a tie the lowest face index (FCL's primitive id,
#    Contact.b1 or b2 on the mesh's side). With num_max_contacts=1 FCL answers the first
#    face its traversal meets, which need not be the nearest.
DEPTH_SIGN = {("sphere", "sphere"): 1.0, ("sphere", "plane"): 1.0, ("plane", "sphere"): 1.0,
              ("sphere", "triangle"): -1.0, ("triangle", "sphere"): -1.0,
              ("sphere", "mesh"): -1.0}


def point_weight(ka, kb, a, b):
    if ka == "sphere" and kb == "sphere":
        ra, rb = a["sphere"]["radius"], b["sphere"]["radius"]
        return rb / (ra + rb)
    if "plane" in (ka, kb):
        return 0.5
    return 0.0 if kb in ("triangle", "mesh") else 1.0


def pick_contact(case, contacts, geom_b):
    """The contact the format asks for among FCL's (one per touching face for a mesh):
    the deepest by FCL's depth, ties to the lowest face index."""
    ka, kb = next(iter(case["a"])), next(iter(case["b"]))
    sign = DEPTH_SIGN[(ka, kb)]

    def key(c):
        face = c.b1 if c.o1 is geom_b else c.b2
        return (-sign * float(c.penetration_depth), face)
    return min(contacts, key=key)


def to_format_contact(case, contact, geom_b):
    ka, kb = next(iter(case["a"])), next(iter(case["b"]))
    nf = np.array(contact.normal, dtype=np.float64)
    n = nf if contact.o1 is geom_b else -nf  # contact.o1: the geometry FCL put first
    depth = DEPTH_SIGN[(ka, kb)] * float(contact.penetration_depth)
    p = np.array(contact.pos, dtype=np.float64) + n * (depth * point_weight(ka, kb, case["a"], case["b"]))
    return {"contact": {"point": [float(x) for x in p], "normal": [float(x) + 0.0 for x in n], "depth": depth}}
# --- end of the convention translation ------------------------------------------


def contact(case):
    (ka, sa), = case["a"].items()
    (kb, sb), = case["b"].items()
    _, oa = BUILD[ka](sa)
    gb, ob = BUILD[kb](sb)
    # a mesh: room for one contact per face (see the translation's sphere-mesh note)
    res = timed(fcl_collide, oa, ob, max(1, len(sb["triangles"])) if kb == "mesh" else 1)
    if not res.contacts:
        return {"contact": None}
    return to_format_contact(case, pick_contact(case, res.contacts, gb), gb)


def overlap(case):
    _, o1 = box_obj(case["a"]["aabb"])
    _, o2 = box_obj(case["b"]["aabb"])
    req = fcl.CollisionRequest(gjk_solver_type=GJK_SOLVER)
    res = fcl.CollisionResult()
    timed(fcl.collide, o1, o2, req, res)
    return {"overlap": bool(res.is_collision)}


HANDLERS = {
    ("contact", "sphere", "sphere"): contact,
    ("contact", "sphere", "plane"): contact,
    ("contact", "plane", "sphere"): contact,
    ("contact", "sphere", "triangle"): contact,
    ("contact", "triangle", "sphere"): contact,
    ("contact", "sphere", "mesh"): contact,
    ("overlap", "aabb", "aabb"): overlap,
}

if __name__ == "__main__":
    sys.exit(serve("fcl", package_version("python-fcl"), 53, HANDLERS, PROVENANCE))
