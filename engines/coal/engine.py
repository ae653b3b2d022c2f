#!/usr/bin/env python3
"""coal: the Coal collision library (coal-library/coal, the successor of hpp-fcl),
through its Python bindings (`import coal`), behind crashtest-engine/1.

Every answer is Coal's own: `coal.collide` for contacts, `coal.AABB.overlap` for box
tests, `BVHModelBase.computeLocalAABB` for bounds, `coal.distance` for distance. The only
arithmetic this adapter does is the convention translation in `to_format_contact`
(negating Coal's normal and its signed distance) and `to_format_distance` (negating
Coal's normal). The first argument chooses Coal's GJK variant: none (the engine coal,
DefaultGJK), `nesterov` (coal/nesterov) or `polyak` (coal/polyak), the last two
distance only. See README.md for the convention table and the sources it rests on.
"""
import math
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
import crashtest_engine  # noqa: E402
from crashtest_engine import DISTANCE_PAIRS, Unsupported, convex_hull, package_version, serve, timed  # noqa: E402
from reproduce import reproductions  # noqa: E402  (this folder's reproduce.py)

import numpy as np  # noqa: E402
import coal  # noqa: E402

# The engine's GJK variant is its first argument: none (`coal`, Coal's DefaultGJK: contact,
# overlap, bounds and distance), `nesterov` (`coal/nesterov`, NesterovAcceleration) or
# `polyak` (`coal/polyak`, PolyakAcceleration), the last two distance only.
VARIANTS = {"default": ("coal", "DefaultGJK"), "nesterov": ("coal/nesterov", "NesterovAcceleration"),
            "polyak": ("coal/polyak", "PolyakAcceleration")}
VARIANT = sys.argv[1] if len(sys.argv) > 1 else "default"
if VARIANT not in VARIANTS:
    sys.exit(f"coal: unknown variant {VARIANT!r} (nesterov, polyak, or none)")
NAME, GJK_VARIANT = VARIANTS[VARIANT]

# ---------------------------------------------------------------------------------
# The engine's settings (all echoed in the hello's provenance).
# ---------------------------------------------------------------------------------
REQUEST = coal.CollisionRequest()
REQUEST.security_margin = 0.0      # no inflation: contact iff signed distance <= threshold
REQUEST.num_max_contacts = 1       # one contact: the deepest (the only one for these pairs)
REQUEST.enable_contact = True      # compute normal, witness points and signed distance
# break_distance (BVH traversal only), distance_upper_bound, GJK/EPA settings are left
# at Coal's defaults: sphere-sphere, sphere-halfspace and sphere-triangle are analytic
# in Coal (src/narrowphase/details.h) and never run GJK/EPA; box-box, box-triangle,
# capsule-box and capsule-triangle do run them (no analytic routine), with these defaults.
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
    if kind == "box":
        # coal.Box takes full side lengths (halfSide = side/2): 2h, exact but for overflow
        sides = [2.0 * float(h) for h in s["half_extents"]]
        if not all(math.isfinite(x) for x in sides):
            raise Unsupported("Coal's Box takes the full side lengths 2h, and 2h overflows f64 here")
        tf = coal.Transform3s(coal.Quaternion(*unit_quaternion(s.get("rotation", [1.0, 0.0, 0.0, 0.0]))),
                              np.array(s["center"], dtype=np.float64))
        return coal.Box(*sides), tf
    if kind == "capsule":
        q, mid, length = capsule_pose(s)
        return coal.Capsule(float(s["radius"]), length), coal.Transform3s(coal.Quaternion(*q), mid)
    if kind == "aabb":  # a coal.Box of max - min at the centre (rounded there; used by box-aabb)
        lo, hi = (np.array(s[k], dtype=np.float64) for k in ("min", "max"))
        return coal.Box(*(hi - lo)), _identity_at(0.5 * lo + 0.5 * hi)
    raise Unsupported(f"no Coal shape for {kind}")


def unit_quaternion(q):
    """The case's quaternion [w, x, y, z] (any non-zero length) made unit (math.hypot: no
    overflow or underflow); coal.Quaternion(w, x, y, z) takes that order, and Eigen's
    toRotationMatrix, which Transform3s uses, assumes a unit quaternion."""
    n = math.hypot(*q)
    return [float(x) / n for x in q]


def capsule_pose(c):
    """THE CAPSULE PLACEMENT (the only one): coal.Capsule(r, lz) is the segment from
    (0, 0, -lz/2) to (0, 0, lz/2) of its own frame (halfLength = lz/2), swept by r. The
    case's capsule is placed by the rotation taking z to u = (end - start)/|end - start| —
    for u_z >= 0 the quaternion [1 + u_z, -u_y, u_x, 0] (half the angle about z x u), for
    u_z < 0 the half turn about x followed by the rotation from -z to u, [-u_y, 1 - u_z, 0,
    u_x] (no cancellation near u = -z), made unit; the identity for equal ends — and the
    translation start/2 + end/2, with lz = |end - start| (math.hypot). Returns (unit
    quaternion [w, x, y, z], translation, lz)."""
    st, en = [float(x) for x in c["start"]], [float(x) for x in c["end"]]
    d = [en[i] - st[i] for i in range(3)]
    lz = math.hypot(*d)
    if not math.isfinite(lz):
        raise Unsupported("Coal's Capsule takes the length |end - start|, which overflows f64 here")
    mid = np.array([0.5 * st[i] + 0.5 * en[i] for i in range(3)], dtype=np.float64)
    if not lz > 0:
        return [1.0, 0.0, 0.0, 0.0], mid, 0.0
    u = [x / lz for x in d]
    q = [1.0 + u[2], -u[1], u[0], 0.0] if u[2] >= 0 else [-u[1], 1.0 - u[2], 0.0, u[0]]
    return unit_quaternion(q), mid, lz


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
# box-box, box-triangle, capsule-box, capsule-triangle: no analytic routine in Coal 3
# (src/collision_func_matrix.cpp: ShapeShapeCollide<Box, Box>, <Box, TriangleP>,
# <Capsule, Box>, <Capsule, TriangleP>; include/coal/internal/shape_shape_func.h has no
# specialization for them), so GJK + EPA: the same Contact (o1 = a, o2 = b, witness
# points on each, normal o1 -> o2, signed distance), the same rule (checked on the
# campaign's uniform cases: 1570 of 1570 agree, b's witness point on the referee's region).
# A non-finite Contact (NaN normal, -DBL_MAX distance: seen on capsule-triangle with the
# axis along an edge in the triangle's plane, and on flat coplanar boxes) is Coal's
# error, raised as such: never passed on.
# ---------------------------------------------------------------------------------
def pick_contact(result):
    contacts = [result.getContact(i) for i in range(result.numContacts())]
    return min(contacts, key=lambda c: (float(c.penetration_depth), int(c.b2)))


def to_format_contact(c):
    n = c.normal
    p = c.getNearestPoint2()
    raw = [float(x) for x in (*n, *p, c.penetration_depth)]
    if not all(math.isfinite(x) for x in raw):
        # Coal's own answer, shown as it is (an error, never a NaN passed on): seen on
        # capsule-triangle with the axis in the triangle's plane along an edge, or a zero-area
        # triangle: GJK/EPA reports isCollision() with a NaN normal and witness points and a
        # signed distance of -DBL_MAX (README, "boxes and capsules")
        raise RuntimeError(f"Coal reported a collision with a non-finite contact: normal {list(map(float, n))}, "
                           f"witness point on b {list(map(float, p))}, signed distance {float(c.penetration_depth)!r}")
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


OVERLAP_REQUEST = coal.CollisionRequest()
OVERLAP_REQUEST.security_margin = 0.0   # as REQUEST, without contacts: whether they meet
OVERLAP_REQUEST.num_max_contacts = 1
OVERLAP_REQUEST.enable_contact = False


def overlap_shapes(case):
    """box-box and box-aabb: coal.collide of the two as Coal shapes (an AABB as a Box),
    without contacts; overlap = isCollision()."""
    ga, ta = coal_shape(case["a"])
    gb, tb = coal_shape(case["b"])
    result = coal.CollisionResult()
    timed(coal.collide, ga, ta, gb, tb, OVERLAP_REQUEST, result)
    return {"overlap": bool(result.isCollision())}


def bounds_box(case):
    """A box's bounds: a coal.CollisionObject of the Box at its pose, computeAABB() (timed),
    then getAABB() — Coal's AABB of the rotated box in world coordinates — and the Box's
    bounding sphere: computeLocalAABB's aabb_radius about aabb_center, that centre taken to
    world coordinates by the object's own transform (Transform3s.transform)."""
    g, tf = coal_shape(case["a"])
    obj = coal.CollisionObject(g, tf)
    timed(obj.computeAABB)
    box = obj.getAABB()
    g.computeLocalAABB()
    c = tf.transform(g.aabb_center)
    return {
        "aabb": {"min": [float(x) for x in box.min_], "max": [float(x) for x in box.max_]},
        "sphere": {"center": [float(x) for x in c], "radius": float(g.aabb_radius)},
    }


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
    ("contact", "sphere", "box"): contact,
    ("contact", "box", "plane"): contact,
    ("contact", "sphere", "capsule"): contact,
    ("contact", "capsule", "capsule"): contact,
    ("contact", "capsule", "plane"): contact,
    ("contact", "box", "box"): contact,
    ("contact", "box", "triangle"): contact,
    ("contact", "capsule", "box"): contact,
    ("contact", "capsule", "triangle"): contact,
    ("overlap", "box", "box"): overlap_shapes,
    ("overlap", "box", "aabb"): overlap_shapes,
    ("bounds", "box", None): bounds_box,
}


# ---------------------------------------------------------------------------------
# DISTANCE: coal.distance (signed, with witness points and normal) under the engine's GJK
# variant; every other GJK/EPA setting is Coal's default, echoed in the provenance.
# ---------------------------------------------------------------------------------
DIST_REQUEST = coal.DistanceRequest()
DIST_REQUEST.enable_signed_distance = True  # Coal's default, set: EPA when the shapes overlap
DIST_REQUEST.gjk_variant = getattr(coal.GJKVariant, GJK_VARIANT)
# Coal's distance matrix has no TriangleP (src/distance_func_matrix.cpp: "Distance function
# between node type GEOM_SPHERE and node type GEOM_TRIANGLE is not yet supported"); its
# collide has (src/collision_func_matrix.cpp) and runs the very same shape-shape distance
# (include/coal/internal/shape_shape_func.h, ShapeShapeCollider: internal::ShapeShapeDistance
# with compute_penetration = enable_contact, then a Contact(o1, o2, p1, p2, normal, distance)
# when distance - security_margin <= collision_distance_threshold). So the triangle pairs ask
# collide with security_margin = DBL_MAX (every distance is a contact) and the distance
# request's GJK/EPA settings.
TRI_REQUEST = coal.CollisionRequest()
TRI_REQUEST.enable_contact = True
TRI_REQUEST.num_max_contacts = 1
TRI_REQUEST.security_margin = sys.float_info.max
for _field in ("gjk_variant", "gjk_tolerance", "gjk_max_iterations", "gjk_initial_guess", "gjk_convergence_criterion",
               "gjk_convergence_criterion_type", "epa_tolerance", "epa_max_iterations"):
    setattr(TRI_REQUEST, _field, getattr(DIST_REQUEST, _field))


def convex_shape(c):
    """coal.Convex(points, triangles) of the hull of the case's points (crashtest_engine.
    convex_hull: input preparation, its vertices are input points): a solid hull's triangles,
    a flat hull's polygon as two fans (one per side), a segment or a point with none. Coal
    searches up to 32 vertices one by one and more by walking the triangles' edges
    (src/narrowphase/support_functions.cpp, getShapeSupportLog; ConvexBase::neighbors built by
    the constructor). Not coal.ConvexBase.convexHull: Coal's own Qhull call kills the process
    (SIGSEGV) on a flat set of points, and refuses fewer than 4 ('You shouldn't use this
    function with less than 4 points'). At the identity."""
    h = convex_hull(c["points"])
    pts = coal.StdVec_Vec3s()
    for v in h.vertices:
        pts.append(np.array(v, dtype=np.float64))
    tris = coal.StdVec_Triangle()
    for t in h.triangles:
        tris.append(coal.Triangle(int(t[0]), int(t[1]), int(t[2])))
    return coal.Convex(pts, tris), _identity()


def distance_shape(shape):
    kind, s = next(iter(shape.items()))
    return convex_shape(s) if kind == "convex" else coal_shape(shape)


# THE DISTANCE TRANSLATION (the only one): Coal's DistanceResult (include/coal/collision_data.h):
# min_distance is the signed distance (negative: minus the penetration depth, EPA's); the
# nearest points nearest_points[0] on o1 (= a) and [1] on o2 (= b), getNearestPoint1/2 in
# Python; `normal` "pointing from o1 to o2 ... normal = (p2 - p1) / dist(o1, o2)" with the
# SIGNED distance, so "dist(o1, o2) * (p1 - p2) is the separation vector". The format:
# point_a = p1, point_b = p2, normal from b toward a = -normal (then point_a = point_b +
# d * normal holds as Coal's does). A collide Contact (the triangle pairs) carries the same
# three (getNearestPoint1/2, normal o1 -> o2, penetration_depth = the signed distance).
def to_format_distance(d, p1, p2, n):
    raw = [float(x) for x in (d, *p1, *p2, *n)]
    if not all(math.isfinite(x) for x in raw):
        raise RuntimeError(f"Coal answered a non-finite distance: {raw[0]!r}, witness points "
                           f"{raw[1:4]}, {raw[4:7]}, normal {raw[7:10]}")
    return {"distance": raw[0], "point_a": raw[1:4], "point_b": raw[4:7], "normal": [-x + 0.0 for x in raw[7:10]]}


def distance(case):
    ga, ta = distance_shape(case["a"])
    gb, tb = distance_shape(case["b"])
    if "triangle" in case["b"]:
        res = coal.CollisionResult()
        timed(coal.collide, ga, ta, gb, tb, TRI_REQUEST, res)
        if res.numContacts() != 1:
            raise RuntimeError(f"Coal's collide with security_margin = DBL_MAX gave {res.numContacts()} contacts")
        c = res.getContact(0)
        return to_format_distance(c.penetration_depth, c.getNearestPoint1(), c.getNearestPoint2(), c.normal)
    res = coal.DistanceResult()
    timed(coal.distance, ga, ta, gb, tb, DIST_REQUEST, res)
    return to_format_distance(res.min_distance, res.getNearestPoint1(), res.getNearestPoint2(), res.normal)


DISTANCE_HANDLERS = {("distance", a, b): distance for a, b in DISTANCE_PAIRS}
if VARIANT == "default":
    HANDLERS.update(DISTANCE_HANDLERS)
else:  # coal/nesterov and coal/polyak answer distance only
    HANDLERS = DISTANCE_HANDLERS


def distance_provenance():
    r = DIST_REQUEST
    return {
        "distance call": "coal.distance(geom_a, tf_a, geom_b, tf_b, DistanceRequest, DistanceResult); the triangle "
                         "pairs: coal.collide with security_margin = DBL_MAX, enable_contact, num_max_contacts 1 "
                         "(Coal's distance matrix has no TriangleP; collide runs the same shape-shape distance)",
        "distance gjk": f"variant={r.gjk_variant}, tolerance={r.gjk_tolerance!r}, max_iterations={r.gjk_max_iterations}, "
                        f"initial_guess={r.gjk_initial_guess}, convergence={r.gjk_convergence_criterion}/"
                        f"{r.gjk_convergence_criterion_type}",
        "distance epa": f"tolerance={r.epa_tolerance!r}, max_iterations={r.epa_max_iterations}",
        "distance request": f"enable_signed_distance={r.enable_signed_distance}, rel_err={r.rel_err!r}, "
                            f"abs_err={r.abs_err!r} (nearest points always computed in Coal 3)",
        "distance convex as": "coal.Convex(hull vertices, hull triangles) at the identity; hull: " + crashtest_engine.HULL_NOTE,
        "distance triangle as": "coal.TriangleP(v0, v1, v2)",
        "scipy": package_version("scipy"),
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
               f"{r.gjk_convergence_criterion_type} (defaults; used only by box-box, box-triangle, capsule-box, "
               f"capsule-triangle: the other pairs are analytic)",
        "epa": f"tolerance={r.epa_tolerance!r}, max_iterations={r.epa_max_iterations} (defaults; used as GJK is)",
        "overlap": "coal.AABB(min, max).overlap(other) (closed boxes); box-box and box-aabb: coal.collide "
                   "without contacts (an AABB as a Box of max - min at its centre), isCollision()",
        "box-box, box-triangle, capsule-box, capsule-triangle": "coal.collide -> ShapeShapeCollide: GJK + EPA "
                                                                "(no analytic routine for these pairs in Coal 3)",
        "box as": "coal.Box(2*half_extents) at Transform3s(Quaternion(w, x, y, z) made unit, centre)",
        "capsule as": "coal.Capsule(r, |end - start|) (lz, along its local z, centred) at Transform3s(rotation "
                      "z -> end - start, start/2 + end/2)",
        "bounds of a box": "CollisionObject(Box, tf).computeAABB() -> getAABB(); sphere: the Box's aabb_radius "
                           "about tf.transform(aabb_center)",
        "bounds": "BVHModelOBBRSS (point cloud or triangles) -> computeLocalAABB(): aabb_local, aabb_center, aabb_radius",
        "stdout": "fd 1 redirected to stderr before import; protocol on a duplicate of the original fd 1",
    }


def hello_provenance():
    """coal echoes every setting of its queries; coal/nesterov and coal/polyak (distance
    only) the versions and the distance settings."""
    full = provenance()
    if VARIANT == "default":
        return {**full, **distance_provenance()}
    keep = ("coal (package)", "libcoal (package)", "coal library version", "eigenpy", "numpy", "python", "scalar",
            "plane as", "box as", "capsule as", "swept_sphere_radius", "stdout")
    return {**{k: full[k] for k in keep}, **distance_provenance()}


if __name__ == "__main__":
    sys.exit(serve(NAME, package_version("coal"), 53, HANDLERS, hello_provenance(),
                   reproductions=reproductions(HANDLERS, GJK_VARIANT)))
