#!/usr/bin/env python3
"""fcl: FCL 0.7 (the Flexible Collision Library, through the Python package
python-fcl) behind crashtest-engine/1. See README.md for what it answers, the
convention table and the divergences found.

Every number in an answer is FCL's; the adapter only builds FCL's shapes from
the case and translates FCL's conventions into the format's, in ONE place:
`to_format_contact` below (and beside it `to_format_distance` for distance). The
first argument chooses FCL's GJK solver: `libccd` (the engine fcl/libccd, the
default) or `indep` (fcl/indep, distance only).
"""
import ctypes
import json
import math
import os
import resource
import select
import signal
import sys
import time

# --- protect the protocol -------------------------------------------------------
# FCL writes warnings to std::cerr, but a native library may also print to fd 1.
# The protocol keeps a duplicate of fd 1; fd 1 itself is pointed at stderr before
# the engine is imported, so nothing but protocol messages reaches crashtest.
_PROTO_FD = os.dup(1)
os.dup2(2, 1)
sys.stdout = os.fdopen(_PROTO_FD, "w", encoding="utf-8", newline="\n")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import crashtest_engine  # noqa: E402
from crashtest_engine import DISTANCE_PAIRS, Unsupported, convex_hull, package_version, serve, timed  # noqa: E402
from reproduce import reproductions  # noqa: E402  (this folder's reproduce.py)

import numpy as np  # noqa: E402
import fcl  # noqa: E402

# --- settings (echoed in the hello's provenance) ----------------------------------
GJK_SOLVER = fcl.GJKSolverType.GST_LIBCCD  # FCL's default; every pair answered has a
#                                            dedicated (non-GJK) routine under it
REQUEST = dict(enable_contact=True, num_max_contacts=1, gjk_solver_type=GJK_SOLVER)

# toi: FCL's continuous collision, chosen once (see README.md, "toi"). In FCL 0.7.0 the
# conservative-advancement solver ignores the request's num_max_iterations and toc_err
# (FCL_UNUSED(request) in conservative_advancement_func_matrix-inl.h; its traversal
# nodes stop when a step falls below their own t_err = 1e-4 of the motion); they are
# given FCL's defaults. GST_INDEP: with GST_LIBCCD, sphere-halfspace advancement
# crashes the process (SIGSEGV) on every moving case; sphere-sphere and
# sphere-triangle have dedicated distance routines under both solvers.
CCD_REQUEST = dict(num_max_iterations=10, toc_err=1e-4,
                   ccd_motion_type=fcl.CCDMotionType.CCDM_TRANS,
                   gjk_solver_type=fcl.GJKSolverType.GST_INDEP,
                   ccd_solver_type=fcl.CCDSolverType.CCDC_CONSERVATIVE_ADVANCEMENT)
WORKERS = max(1, min(4, len(os.sched_getaffinity(0))))  # a batch's toi cases run in this many
#                                                          forked workers at once (below, "toi")
DISTANCE_REQUEST = dict(enable_nearest_points=True, gjk_solver_type=fcl.GJKSolverType.GST_INDEP)

PROVENANCE = {
    "python-fcl": package_version("python-fcl"),
    "fcl.__version__": getattr(fcl, "__version__", "unknown"),
    "libfcl": "0.7.0 (ambi-robotics/fcl tag v0.7.0, as python-fcl's build script pins; libfcl.so.0.7.0)",
    "libccd": "2.1, double precision (python-fcl's build script)",
    "numpy": package_version("numpy"),
    "precision": "f64 (FCL instantiated with double, libccd built with ENABLE_DOUBLE_PRECISION)",
    "gjk_solver_type": "GST_LIBCCD (contact, overlap)",
    "collision_request": "enable_contact=True, num_max_contacts=1 (sphere-mesh: one per face; the deepest "
                         "taken, ties to the lowest face index)",
    "margins": "none (FCL shapes have no margin or envelope)",
    "plane": "fcl.Halfspace(n, d): solid n.x <= d (FCL normalizes n and d)",
    "triangle": "fcl.BVHModel (OBBRSS) holding the one triangle: FCL has no sphere-TriangleP collision",
    "mesh": "fcl.BVHModel (OBBRSS) holding every face; sphere-mesh: num_max_contacts = the number of "
            "faces (FCL's mesh-shape traversal, one contact per touching face), the deepest taken, "
            "ties to the lowest face index",
    "aabb": "fcl.Box(max - min) at translation 0.5*min + 0.5*max",
    "box": "fcl.Box(2*half_extents) at Transform(q/|q|, centre), q = [w, x, y, z] (python-fcl's order)",
    "capsule": "fcl.Capsule(r, |end - start|) (along its local z, centred) at Transform(rotation z -> "
               "end - start, start/2 + end/2)",
    "capsule-capsule": "no dedicated routine under GST_LIBCCD: libccd MPR (ccdMPRPenetration)",
    "box-box": "boxBoxIntersect (box_box-inl.h, ODE's dBoxBox: up to 4 contacts, the deepest kept by "
               "num_max_contacts=1)",
    "capsule-box": "no dedicated routine under GST_LIBCCD: libccd MPR (ccdMPRPenetration)",
    "box-triangle, capsule-triangle": "the triangle as the one-face BVHModel; FCL's mesh-shape leaf test -> "
                                      "shapeTriangleIntersect: libccd MPR (no dedicated routine for a box or a capsule)",
    "toi": "fcl.continuousCollide(a, a's pose at t_max, b, b's pose at t_max) from the poses at 0 (each shape "
           "translated by velocity*t_max, a box's rotation kept); t = time_of_contact * t_max when is_collide, else null; the "
           "contact at t from FCL's static queries with both shapes moved by velocity*t: fcl.collide's "
           "contact (as for contact) if they touch, else fcl.distance's nearest points",
    "toi ccd_request": "ccd_solver_type=CCDC_CONSERVATIVE_ADVANCEMENT, ccd_motion_type=CCDM_TRANS, "
                       "gjk_solver_type=GST_INDEP, num_max_iterations=10, toc_err=1e-4 (the last two are "
                       "ignored by FCL 0.7.0's conservative advancement: it stops at a step below t_err = 1e-4, "
                       "hard-coded in its traversal nodes)",
    "toi distance_request": "fcl.DistanceRequest(enable_nearest_points=True, gjk_solver_type=GST_INDEP), which "
                            "python-fcl hands FCL as rel_err = 1.0 with the solver left at GST_LIBCCD "
                            "(DistanceRequestd(bool, bool, GJKSolverType) meets FCL's (bool, bool, S rel_err, ...))",
    "toi crash containment": "each toi case runs in a forked child (os.fork), which returns its answer and "
                             "the ns of its FCL calls through a pipe; a child killed by a signal is that "
                             "case's error, naming the FCL call",
    "toi workers": f"{WORKERS} forked children at once (one per core, at most 4), each on one case at a time",
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


def unit_quaternion(q):
    """The case's quaternion [w, x, y, z] (any non-zero length) made unit (math.hypot: no
    overflow or underflow). python-fcl's Transform takes [w, x, y, z] and Eigen's
    toRotationMatrix, which it calls, assumes a unit quaternion."""
    n = math.hypot(*q)
    return np.array([x / n for x in q], dtype=np.float64)


def obox_obj(b):
    # fcl.Box takes full side lengths: 2 h (exact but for overflow past 2^1023); placed
    # at the centre with the case's rotation, made unit
    sides = [2.0 * h for h in b["half_extents"]]
    if not all(math.isfinite(x) for x in sides):
        raise Unsupported("FCL's Box takes the full side lengths 2h, and 2h overflows f64 here")
    g = fcl.Box(*sides)
    return g, fcl.CollisionObject(g, fcl.Transform(unit_quaternion(b.get("rotation", [1.0, 0.0, 0.0, 0.0])),
                                                   vec(b["center"])))


def capsule_pose(c):
    """THE CAPSULE PLACEMENT (the only one): fcl.Capsule(r, lz) is the segment from
    (0, 0, -lz/2) to (0, 0, lz/2) of its own frame, swept by r. The case's capsule is
    placed by the rotation taking z to u = (end - start)/|end - start| — for u_z >= 0 the
    quaternion [1 + u_z, -u_y, u_x, 0] (half the angle about z x u), for u_z < 0 the half
    turn about x followed by the rotation from -z to u, [-u_y, 1 - u_z, 0, u_x] (no
    cancellation near u = -z), made unit; the identity for equal ends — and the
    translation start/2 + end/2, with lz = |end - start| (math.hypot). Returns (quaternion
    [w, x, y, z], translation, lz)."""
    s, e = vec(c["start"]), vec(c["end"])
    d = [c["end"][i] - c["start"][i] for i in range(3)]
    lz = math.hypot(*d)
    if not math.isfinite(lz):
        raise Unsupported("FCL's Capsule takes the length |end - start|, which overflows f64 here")
    d = vec(d)
    mid = 0.5 * s + 0.5 * e
    if not lz > 0:
        return np.array([1.0, 0.0, 0.0, 0.0]), mid, 0.0
    u = d / lz
    q = [1.0 + u[2], -u[1], u[0], 0.0] if u[2] >= 0 else [-u[1], 1.0 - u[2], 0.0, u[0]]
    return unit_quaternion(q), mid, lz


def capsule_obj(c):
    q, mid, lz = capsule_pose(c)
    g = fcl.Capsule(c["radius"], lz)
    return g, fcl.CollisionObject(g, fcl.Transform(q, mid))


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


BUILD = {"sphere": sphere_obj, "plane": halfspace_obj, "triangle": triangle_obj, "mesh": mesh_obj,
         "box": obox_obj, "capsule": capsule_obj, "aabb": box_obj}


# --- distance: FCL's signed distance (fcl.distance), under the engine's GJK solver --------
# The engine's variant is its first argument: `libccd` (fcl/libccd, GST_LIBCCD: FCL's
# default, which this adapter also uses for contact and overlap) or `indep` (fcl/indep,
# GST_INDEP: FCL's own GJK/EPA, distance only).
VARIANT = sys.argv[1] if len(sys.argv) > 1 else "libccd"
if VARIANT not in ("libccd", "indep"):
    sys.exit(f"fcl: unknown variant {VARIANT!r} (libccd or indep)")
NAME = f"fcl/{VARIANT}"
DISTANCE_SOLVER = fcl.GJKSolverType.GST_INDEP if VARIANT == "indep" else fcl.GJKSolverType.GST_LIBCCD
DISTANCE_TOLERANCE = 1e-6  # DistanceRequest::distance_tolerance, FCL's default (the only value
#                            python-fcl can give); FCL copies it into the solver (distance-inl.h)

# GST_INDEP cannot be asked for through python-fcl (reproduce.py, LIBFCL_DISTANCE: its
# request puts the solver type in rel_err), so fcl/indep calls libfcl's own
# fcl::distance<double> with FCL's DistanceRequest, built field for field; the text is
# reproduce.py's, run here, so that engine and reproduction are the same code.
from reproduce import CONVEX_FACES, LIBFCL_DISTANCE  # noqa: E402
if VARIANT == "indep":
    exec(LIBFCL_DISTANCE)  # defines libfcl_distance and cpp_pointer
    # Python's view of python-fcl's objects: the C++ pointer is Cython's first field after
    # the header (fcl.cpp: struct __pyx_obj_3fcl_3fcl_CollisionObject {PyObject_HEAD;
    # CollisionObjectd *thisptr; PyObject *geom; bool _no_instance}). Checked once here:
    # the object's `geom` field is the geometry given, and FCL's answer names the
    # geometries by the pointers read the same way.
    _g = fcl.Sphere(1.0)
    _o = fcl.CollisionObject(_g, fcl.Transform())
    _res = libfcl_distance(_o, fcl.CollisionObject(fcl.Sphere(1.0), fcl.Transform(np.array([0.0, 0.0, 3.0]))),
                           DISTANCE_SOLVER, DISTANCE_TOLERANCE)
    if not (ctypes.c_void_p.from_address(id(_o) + object.__basicsize__ + 8).value == id(_g)
            and _res.o1 == cpp_pointer(_g) and _res.min_distance == 1.0):
        sys.exit("fcl/indep: python-fcl's objects are not laid out as expected; libfcl cannot be called")
exec(CONVEX_FACES)  # defines convex_faces(hull)
# The hull's Qhull (scipy.spatial) is loaded here, once: the forked workers that answer
# distance inherit it, where each new worker would otherwise import it again (~0.3 s).
convex_hull([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])

PLANE_CRASH = ("FCL 0.7.0 dies (SIGSEGV) on every distance to a Halfspace under GST_LIBCCD: libccd's GJK "
               "has no support function for it (gjk_libccd.h: GJKInitializer<S, Halfspace<S>> is not "
               "specialised, so the generic one hands libccd a null support function and a null object); "
               "not called")


def convex_obj(c):
    """fcl.Convex of the hull of the points (crashtest_engine.convex_hull: input preparation,
    its vertices are input points): its triangles as FCL's faces ([3, i, j, k] each), a flat
    hull's polygon once per side, a segment or a point with no face. fcl.Convex searches its
    vertices one by one up to 32 of them (convex-inl.h, findExtremeVertex), and beyond by
    walking the faces' edges when they close up (ValidateTopology: watertight, every vertex
    on a face), else one by one again. At the identity."""
    h = convex_hull(c["points"])
    g = fcl.Convex([vec(v) for v in h.vertices], *convex_faces(h))
    return g, fcl.CollisionObject(g, fcl.Transform())


DIST_BUILD = {**BUILD, "convex": convex_obj}


def fcl_distance(oa, ob):
    """FCL's distance of the two objects under the engine's solver, with nearest points
    and signed distance: (min_distance, nearest point 0, nearest point 1, the C++ or Python
    identity of the result's o1)."""
    if VARIANT == "indep":
        res = libfcl_distance(oa, ob, DISTANCE_SOLVER, DISTANCE_TOLERANCE)
        p = list(res.nearest_points)
        return res.min_distance, p[:3], p[3:], res.o1
    req = fcl.DistanceRequest(enable_nearest_points=True, enable_signed_distance=True,
                              gjk_solver_type=DISTANCE_SOLVER)
    res = fcl.DistanceResult()
    ret = fcl.distance(oa, ob, req, res)
    if res.nearest_points[0] is None:  # python-fcl copies FCL's result only below its own DBL_MAX
        raise RuntimeError(f"FCL gave no distance below DBL_MAX (fcl.distance returned {ret!r}; python-fcl "
                           f"keeps FCL's result only when its min_distance is below that)")
    return res.min_distance, res.nearest_points[0], res.nearest_points[1], res.o1


def is_geometry(o1, geom):
    return o1 == cpp_pointer(geom) if VARIANT == "indep" else o1 is geom


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
#  - toi (fcl.distance, for a pair apart at FCL's time of contact): FCL's DistanceResult
#    holds nearest_points[0] on its o1 and [1] on its o2. Shape-BVH calls are swapped to
#    BVH-shape (distance-inl.h) without swapping back, so b's point is read from the
#    result's own o1/o2. Frames: shape-shape distance answers in world coordinates;
#    BVH-shape distance (the triangle and mesh pairs) answers each point in its own
#    object's frame (checked: a triangle at translation (0,0,0.5) gives its point at z = 0,
#    the sphere's as centre-relative), so those points are mapped to world by the
#    object's own translation (every object here has the identity rotation).
#    point = b's nearest point. normal: FCL puts the sphere's (a's) nearest point at
#    centre - r n (sphere_sphere / sphere_triangle distance), so n = (a's centre - a's
#    nearest point) / its length (math.hypot): FCL's own direction, read at the length r.
#    (The difference of the two nearest points says the same, but at FCL's time of contact
#    the gap is tiny and that difference cancels: 1e-4 rad off on fast small spheres.)
#    depth = -distance (a gap; the toi answer drops it).
#  - boxes and capsules (o1 is a in every one of these pairs; depth > 0 in all):
#      sphere-box (sphere_box-inl.h, sphereBoxIntersect): pos midway between the sphere's
#        deepest point and the box's surface point -> W = 1/2 (checked: centre outside,
#        inside, at a corner, flat box)
#      box-halfspace, capsule-halfspace (halfspace-inl.h): pos midway between the solid's
#        deepest point and the plane, as sphere-halfspace -> W = 1/2 (the plane rule)
#      sphere-capsule (sphere_capsule-inl.h, sphereCapsuleIntersect): pos = the axis point
#        nearest the centre + depth along the normal toward the sphere: on b's surface only
#        when depth = r_b, on neither surface otherwise. Taken as FCL gives it (W = 0): the
#        point FCL reports is shown as it is (README, "boxes and capsules")
#      capsule-capsule: no dedicated routine under GST_LIBCCD; libccd's MPR
#        (ccdMPRPenetration), whose pos is its portal's estimate of the middle of the
#        overlap -> W = 1/2
#      box-box (box_box-inl.h, boxBoxIntersect -> boxBox2, ODE's dBoxBox): o1 = a, normal
#        from a to b (negated), up to 4 contacts, each with its own depth dep[i] (the
#        clipped point's depth below the reference face; -s, the least overlap of the 15
#        axes, for an edge-edge contact); with num_max_contacts = 1 FCL's
#        ShapeCollisionTraversalNode keeps the deepest (partial_sort by depth). pos:
#        reference face of a (code < 4): b's incident point + normal*dep/2; of b: a's
#        incident point - normal*dep/2; edge-edge: (pa + pb)/2 -> midway in all three,
#        W = 1/2. NB: boxBox2 prefers a face axis over an edge-edge one unless the
#        edge's overlap is 5% smaller (fudge_factor 1.05), so its normal may not be the
#        least push (README)
#      capsule-box: no dedicated routine under GST_LIBCCD (gjk_solver_libccd-inl.h lists
#        none): ShapeIntersectLibccdImpl -> GJKCollide -> libccd's ccdMPRPenetration with
#        o1 = a. MPR's pos (libccd mpr.c, findPos) is (p1 + p2)/2 with p1, p2 the same
#        barycentric mix (the origin's coordinates in the final portal tetrahedron) of the
#        support points on a and on b; the origin = p1 - p2, so p1 = p2: pos is a point
#        of a ∩ b, inside b, not on its surface, and no fixed shift along n reaches b's
#        surface. W = 1/2 as for capsule-capsule (its offset from b's surface, measured on
#        the campaign, is spread about zero: README, "boxes and capsules")
#      box-triangle, capsule-triangle: the triangle is the one-face BVHModel; FCL swaps the
#        call to BVH-shape (o1 = the triangle = b, normal kept) and its mesh-shape leaf
#        test (mesh_shape_collision_traversal_node-inl.h) runs shapeTriangleIntersect, for
#        a box or a capsule the generic ShapeTransformedTriangleIntersectLibccdImpl:
#        GJKCollide (MPR) shape vs triangle, depth > 0 (unlike sphere-triangle's
#        dedicated routine), normal negated into the Contact (from the triangle to the
#        shape). pos is MPR's point of a ∩ b (above), here a point of the flat triangle,
#        so on b's surface as it is -> W = 0 (checked: 192 of 226 box-triangle contacts
#        whose depth FCL gets right have their point exactly on the referee's region
#        with W = 0; the rest are edge contacts, where a point of a ∩ triangle need not
#        be in the touching set)
DEPTH_SIGN = {("sphere", "sphere"): 1.0, ("sphere", "plane"): 1.0, ("plane", "sphere"): 1.0,
              ("sphere", "triangle"): -1.0, ("triangle", "sphere"): -1.0,
              ("sphere", "mesh"): -1.0,
              ("sphere", "box"): 1.0, ("box", "plane"): 1.0, ("sphere", "capsule"): 1.0,
              ("capsule", "capsule"): 1.0, ("capsule", "plane"): 1.0,
              ("box", "box"): 1.0, ("box", "triangle"): 1.0, ("capsule", "box"): 1.0,
              ("capsule", "triangle"): 1.0}


def point_weight(ka, kb, a, b):
    if ka == "sphere" and kb == "sphere":
        ra, rb = a["sphere"]["radius"], b["sphere"]["radius"]
        return rb / (ra + rb)
    if "plane" in (ka, kb) or (ka, kb) in (("sphere", "box"), ("capsule", "capsule"), ("box", "box"),
                                           ("capsule", "box")):
        return 0.5
    if (ka, kb) in (("sphere", "capsule"), ("box", "triangle"), ("capsule", "triangle")):
        return 0.0
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


def to_format_contact(case, contact, geom_b, frames=None):
    """FCL's answer -> the format's contact. `contact` is an fcl.Contact (from collide),
    or an fcl.DistanceResult (from distance, toi only) with `frames` = (translation of
    a's object, translation of b's object) for the BVH-shape local frames."""
    ka, kb = next(iter(case["a"])), next(iter(case["b"]))
    if isinstance(contact, fcl.DistanceResult):
        ib = 0 if contact.o1 is geom_b else 1
        p_b = np.array(contact.nearest_points[ib], dtype=np.float64)
        p_a = np.array(contact.nearest_points[1 - ib], dtype=np.float64)
        if kb in ("triangle", "mesh"):  # BVH-shape: each point in its own object's frame
            p_a, p_b = p_a + frames[0], p_b + frames[1]
        d = frames[0] - p_a  # a is the sphere, centred at frames[0]: FCL's p_a = centre - r n
        length = math.hypot(*d)
        if not length > 0:
            raise ValueError(f"fcl.distance: a's nearest point at its centre (distance "
                             f"{contact.min_distance!r}): no normal")
        n = d / length
        return {"contact": {"point": [float(x) for x in p_b], "normal": [float(x) + 0.0 for x in n],
                            "depth": -float(contact.min_distance)}}
    nf = np.array(contact.normal, dtype=np.float64)
    n = nf if contact.o1 is geom_b else -nf  # contact.o1: the geometry FCL put first
    depth = DEPTH_SIGN[(ka, kb)] * float(contact.penetration_depth)
    p = np.array(contact.pos, dtype=np.float64) + n * (depth * point_weight(ka, kb, case["a"], case["b"]))
    return {"contact": {"point": [float(x) for x in p], "normal": [float(x) + 0.0 for x in n], "depth": depth}}


#  - distance (fcl.distance: enable_nearest_points and enable_signed_distance, under the
#    engine's solver): FCL's DistanceResult (distance_result.h) holds min_distance, the
#    signed distance (negative: minus the penetration depth), nearest_points[0] on its o1
#    and [1] on its o2, and no normal. The format: distance as it is; point_a, point_b the
#    points on a and on b; normal from b toward a with point_a = point_b + d n.
#      o1/o2: shape-shape keeps the call's order; a shape-BVH call (a triangle as b) is
#        swapped to BVH-shape (distance-inl.h) and not swapped back, so a's point is read
#        from the result's own o1/o2 (as for toi above).
#      frames: shape-shape and shape-triangle GJK answer world points; FCL's
#        sphereTriangleDistance with a mesh transform (sphere_triangle-inl.h) puts the
#        sphere's point in the SPHERE'S frame (tf.inverse() * p1) and the triangle's in the
#        mesh's (the identity here): for sphere-triangle at d > 0 (the only d that routine
#        answers) the sphere's point is moved by its centre (its rotation is the identity).
#      overlap: under GST_LIBCCD FCL gives shapes libccd's EPA (ccdGJKSignedDist,
#        gjk_libccd-inl.h): min_distance = -depth, nearest points a's deepest point in b
#        and b's point it must reach (penEPAPosClosest), as the format's. For a triangle
#        (a BVHModel) under both solvers, and for every overlap under GST_INDEP (whose
#        shapeSignedDistance is its unsigned GJK, gjk_solver_indep-inl.h: "TODO: should
#        implement the signed distance version"), distance() replaces the answer by its
#        collide's (distance-inl.h: min_distance = -the largest penetration_depth, both
#        nearest points = that contact's pos, documented "NOT guaranteed to be on the
#        surface", NP_X in distance_request.h), and drops the contact's normal.
#      normal: FCL gives none, so it is read from FCL's points: (p_a - p_b)/|p_a - p_b|
#        when d > 0, (p_b - p_a)/|p_b - p_a| when d < 0 (a's deepest point must reach b's
#        point: the format's EPA convention). Where FCL's two points coincide (an overlap
#        replaced by collide's contact) or d = 0 (touching: the points are one point, any
#        difference between them is rounding) FCL's answer has no direction, and the
#        normal is the zero vector: nothing is made up for it. (The contact distance()
#        takes its point from is not at hand: its collide runs with the distance solver's
#        collision_tolerance, eps^(7/8), where python-fcl's collide can only ask for 1e-6,
#        and the two contacts differ.)
def to_format_distance(case, d, q0, q1, o1, gb):
    ka, kb = next(iter(case["a"])), next(iter(case["b"]))
    q0, q1 = vec(q0), vec(q1)
    p_a, p_b = (q1, q0) if is_geometry(o1, gb) else (q0, q1)
    d = float(d)
    if d > 0 and (ka, kb) == ("sphere", "triangle"):
        p_a = p_a + vec(case["a"]["sphere"]["center"])
    diff = p_a - p_b
    length = math.hypot(*diff)
    n = (diff / length if d > 0 else -diff / length) if length > 0 and d != 0 else np.zeros(3)
    return {"distance": d, "point_a": [float(x) for x in p_a], "point_b": [float(x) for x in p_b],
            "normal": [float(x) + 0.0 for x in n]}


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
    (ka, sa), = case["a"].items()
    (kb, sb), = case["b"].items()
    _, o1 = BUILD[ka](sa)
    _, o2 = BUILD[kb](sb)
    req = fcl.CollisionRequest(gjk_solver_type=GJK_SOLVER)
    res = fcl.CollisionResult()
    timed(fcl.collide, o1, o2, req, res)
    return {"overlap": bool(res.is_collision)}


# --- toi and distance: FCL in a forked child ----------------------------------------
# The worker: a child forked from this process (os.fork) that runs FCL's calls for one
# toi or distance case at a time, so that a crash of FCL (SIGSEGV) ends the child and not
# the engine. It is kept for the next case while it lives (forking here costs ~2-4 ms a case,
# which over a campaign would be most of the time) and forked again after a crash.
CHILD_STACK = 1 << 20  # bytes: FCL's shape-mesh advancement can recurse without end
#                        (distanceRecurse); 1 MiB ends it in ms rather than the tens of ms
#                        the default 8 MiB takes (a balanced BVH needs a few KiB)
CHILD_TIMEOUT = {"toi": 20.0, "distance": 0.25}  # s per case, by query: a worker that does not
#                                                    answer is killed, the case failed. A distance takes
#                                                    FCL 9 us (median), 0.35 ms (p99), 6 ms at most over
#                                                    3,000 campaign cases; libccd's EPA can loop without
#                                                    end (README), and each such case costs this budget


class EngineCrash(Exception):
    """The forked child running FCL was killed by a signal (or did not answer)."""


def charge(ns):
    """Charges `ns` (FCL's time, measured in the child) to the current case
    (crashtest_engine's `timed` charges only calls made in this process)."""
    crashtest_engine._charged.append(float(ns))


def toi_in_child(case, emit):
    """Runs in the worker: builds FCL's objects, FCL's CCD, then FCL's contact at that
    time. `emit(obj)` sends one line to the parent; {"stage": name} before every FCL call
    names the call if the worker dies in it."""
    (ka, sa), = case["a"].items()
    (kb, sb), = case["b"].items()
    ga, oa = BUILD[ka](sa)
    gb, ob = BUILD[kb](sb)
    t_max = float(case.get("t_max", 1.0))
    start_a, start_b = oa.getTranslation(), ob.getTranslation()
    va, vb = vec(sa.get("velocity", [0, 0, 0])), vec(sb.get("velocity", [0, 0, 0]))
    ns = 0

    def call(stage, fn, *args):
        nonlocal ns
        emit({"stage": stage})
        t0 = time.perf_counter_ns()
        out = fn(*args)
        ns += time.perf_counter_ns() - t0
        return out

    req = fcl.ContinuousCollisionRequest(**CCD_REQUEST)
    res = fcl.ContinuousCollisionResult()
    # The poses at t_max: translated, each rotation kept (a box's is fixed while it moves).
    call("continuousCollide", fcl.continuousCollide, oa, fcl.Transform(oa.getRotation(), start_a + t_max * va),
         ob, fcl.Transform(ob.getRotation(), start_b + t_max * vb), req, res)
    if not res.is_collide:
        return {"answer": {"toi": None}, "ns": ns}
    t = float(res.time_of_contact) * t_max  # FCL's time is a fraction of the motion
    ta, tb = start_a + t * va, start_b + t * vb  # both shapes moved by velocity * t
    oa.setTranslation(ta)
    ob.setTranslation(tb)
    cres = call("collide", fcl_collide, oa, ob, max(1, len(sb["triangles"])) if kb == "mesh" else 1)
    if cres.contacts:
        c = to_format_contact(case, pick_contact(case, cres.contacts, gb), gb)["contact"]
    else:
        dres = fcl.DistanceResult()
        call("distance", fcl.distance, oa, ob, fcl.DistanceRequest(**DISTANCE_REQUEST), dres)
        c = to_format_contact(case, dres, gb, frames=(ta, tb))["contact"]
    return {"answer": {"toi": {"t": t, "point": c["point"], "normal": c["normal"]}}, "ns": ns}


def worker_loop(rfd, wfd):
    """The worker's life: one case a line on `rfd`, its lines on `wfd`; ends at EOF."""
    os.close(_PROTO_FD)  # the protocol is the parent's alone
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))  # a crash leaves no core file
    hard = resource.getrlimit(resource.RLIMIT_STACK)[1]
    stack = CHILD_STACK if hard == resource.RLIM_INFINITY else min(CHILD_STACK, hard)
    resource.setrlimit(resource.RLIMIT_STACK, (stack, hard))

    def emit(obj):
        os.write(wfd, (json.dumps(obj, allow_nan=True) + "\n").encode())
    with os.fdopen(rfd, "rb") as cases:
        for line in cases:
            try:
                case = json.loads(line)
                emit({"result": IN_CHILD[case["query"]](case, emit)})
            except Exception as exc:
                emit({"exception": [type(exc).__name__, str(exc)]})


class Worker:
    """One forked worker (`worker_loop`): its pid, the write end of its case pipe, the
    read end of its answers with what has arrived of a line, the case it is on (an index
    into the cases being run, None when idle), the FCL call it last named, and the time
    by which it must have said something."""

    def __init__(self, siblings):
        to_r, to_w = os.pipe()
        from_r, from_w = os.pipe()
        pid = os.fork()
        if pid == 0:  # the worker: never returns
            status = 0
            try:
                # The other workers' pipe ends are the engine's alone: a worker keeping a
                # sibling's case pipe open would keep that sibling waiting for cases after
                # the engine closed its end, and every fork would inherit more of them.
                for fd in siblings:
                    os.close(fd)
                os.close(to_w)
                os.close(from_r)
                worker_loop(to_r, from_w)
            except BaseException:
                status = 1
            finally:
                os._exit(status)
        os.close(to_r)
        os.close(from_w)
        self.pid, self.to_w, self.fd, self.buf = pid, to_w, from_r, b""
        self.case, self.stage, self.deadline = None, None, None

    def send(self, index, case):
        os.write(self.to_w, (json.dumps(case, allow_nan=False) + "\n").encode())
        self.case, self.stage = index, "the adapter"
        self.timeout = CHILD_TIMEOUT[case["query"]]
        self.deadline = time.monotonic() + self.timeout

    def read(self):
        """What has arrived: its complete lines as JSON, and whether the worker is gone (EOF)."""
        chunk = os.read(self.fd, 65536)
        if not chunk:
            return [], True
        self.buf += chunk
        *done, self.buf = self.buf.split(b"\n")
        return [json.loads(line) for line in done], False

    def end(self, kill):
        """Ends the worker (SIGKILL first when `kill`) and returns its wait status."""
        if kill:
            os.kill(self.pid, signal.SIGKILL)
        os.close(self.to_w)
        os.close(self.fd)
        return os.waitpid(self.pid, 0)[1]


_pool = []      # the live workers, kept from batch to batch
_prepared = {}  # id(case) -> its outcome, from `prepare`, for `toi` to hand back


def crash_text(status, stage):
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        return f"FCL crashed (signal {sig}, {signal.Signals(sig).name}) in {stage}"
    return f"the FCL worker exited (status {os.waitstatus_to_exitcode(status)}) in {stage}"


def run_in_workers(cases):
    """Runs toi and distance `cases` in the workers, up to WORKERS at a time, each worker
    one case at a time: per case ("answer", answer, ns), ("exception", type name, text) or
    ("crash", message). A worker that dies is that case's crash and is replaced by a new
    fork; one silent for its query's CHILD_TIMEOUT is killed and replaced."""
    out = [None] * len(cases)
    todo = list(range(len(cases) - 1, -1, -1))  # popped from the end: case order
    busy = {}  # read fd -> the worker on a case

    def fork():
        w = Worker([fd for v in _pool for fd in (v.to_w, v.fd)])
        _pool.append(w)
        return w

    def feed(w):
        if todo:
            i = todo.pop()
            w.send(i, cases[i])
            busy[w.fd] = w

    def done(w, outcome):
        out[w.case] = outcome
        w.case = None
        del busy[w.fd]
        feed(w)

    def retire(w, kill):
        """Ends `w` (out of `busy` first: its fd number may come back with the next fork),
        forks its successor while cases remain, and returns its wait status."""
        busy.pop(w.fd, None)
        _pool.remove(w)
        status = w.end(kill)
        if todo:
            feed(fork())
        return status

    while len(_pool) < min(WORKERS, len(cases)):
        fork()
    for w in list(_pool):
        feed(w)
    while busy:
        wait = max(0.0, min(w.deadline for w in busy.values()) - time.monotonic())
        ready, _, _ = select.select(list(busy), [], [], wait)
        if not ready:
            for w in [w for w in busy.values() if w.deadline <= time.monotonic()]:
                i, stage = w.case, w.stage
                retire(w, kill=True)
                out[i] = ("crash", f"FCL did not answer within {w.timeout:g} s in {stage} (the worker was killed)")
            continue
        for fd in ready:
            w = busy.get(fd)
            if w is None:
                continue
            msgs, gone = w.read()
            for msg in msgs:
                if "stage" in msg:
                    w.stage = msg["stage"]
                elif "exception" in msg:
                    done(w, ("exception", *msg["exception"]))
                else:
                    done(w, ("answer", msg["result"]["answer"], msg["result"]["ns"]))
            if gone:  # it died in its case
                i, stage = w.case, w.stage
                status = retire(w, kill=False)
                if i is not None:
                    out[i] = ("crash", crash_text(status, stage))
    return out


def prepare(cases):
    """A batch's toi and distance cases, run in the workers side by side before they are
    answered one by one (crashtest_engine.serve's `prepare`); `toi` and `distance` hand
    each case's outcome back."""
    _prepared.clear()
    mine = []
    for c in cases:
        try:
            if HANDLERS.get(crashtest_engine.pair_of(c)) in (toi, distance) and not refused(c):
                mine.append(c)
        except Exception:
            pass  # a malformed case: answered (with its error) one by one
    for c, outcome in zip(mine, run_in_workers(mine)):
        _prepared[id(c)] = outcome


def from_worker(case):
    """A toi or distance case's outcome from the workers: its answer (FCL's time charged),
    or its exception raised as it would be in-process, or the crash as EngineCrash."""
    outcome = _prepared.pop(id(case), None) or run_in_workers([case])[0]
    if outcome[0] == "answer":
        charge(outcome[2])
        return outcome[1]
    if outcome[0] == "exception" and outcome[1] == "Unsupported":
        raise Unsupported(outcome[2])
    if outcome[0] == "exception":
        raise type(outcome[1], (Exception,), {})(outcome[2])  # shown as it would be in-process
    raise EngineCrash(outcome[1])


def toi(case):
    return from_worker(case)


HANDLERS = {
    ("contact", "sphere", "sphere"): contact,
    ("contact", "sphere", "plane"): contact,
    ("contact", "plane", "sphere"): contact,
    ("contact", "sphere", "triangle"): contact,
    ("contact", "triangle", "sphere"): contact,
    ("contact", "sphere", "mesh"): contact,
    ("contact", "sphere", "box"): contact,
    ("contact", "box", "plane"): contact,
    ("contact", "sphere", "capsule"): contact,
    ("contact", "capsule", "capsule"): contact,
    ("contact", "capsule", "plane"): contact,
    ("contact", "box", "box"): contact,
    ("contact", "box", "triangle"): contact,
    ("contact", "capsule", "box"): contact,
    ("contact", "capsule", "triangle"): contact,
    ("overlap", "aabb", "aabb"): overlap,
    ("overlap", "box", "box"): overlap,
    ("overlap", "box", "aabb"): overlap,
    ("toi", "sphere", "sphere"): toi,
    ("toi", "sphere", "plane"): toi,
    ("toi", "sphere", "triangle"): toi,
    ("toi", "sphere", "mesh"): toi,
    ("toi", "sphere", "box"): toi,
}


def provenance():
    """The hello's provenance: fcl/libccd echoes every setting of its queries; fcl/indep
    (distance only) the versions and the distance settings."""
    solver = ("GJKSolver_indep: gjk_max_iterations 128, gjk_tolerance = distance_tolerance, epa_max_face_num 128, "
              "epa_max_vertex_num 64, epa_max_iterations 255, epa_tolerance 1e-6, cached guess off "
              "(gjk_solver_indep-inl.h, GJKSolver_indep(); distance-inl.h sets gjk_tolerance)"
              if VARIANT == "indep" else
              "GJKSolver_libccd: max_collision_iterations 500, max_distance_iterations 1000, collision_tolerance "
              "1e-6, distance_tolerance = the request's (gjk_solver_libccd-inl.h, GJKSolver_libccd(); "
              "distance-inl.h sets distance_tolerance); libccd's GJK/EPA run with dist_tolerance = epa_tolerance "
              "= distance_tolerance and max_iterations = max_distance_iterations (gjk_libccd-inl.h, GJKDistanceImpl)")
    dist = {
        "distance_solver": "GST_INDEP" if VARIANT == "indep" else "GST_LIBCCD",
        "distance_request": f"enable_nearest_points=True, enable_signed_distance=True, rel_err=0, abs_err=0, "
                            f"distance_tolerance={DISTANCE_TOLERANCE!r}, gjk_solver_type="
                            + ("GST_INDEP" if VARIANT == "indep" else "GST_LIBCCD"),
        "distance_call": ("libfcl's fcl::distance<double>(CollisionObject*, CollisionObject*, DistanceRequest, "
                          "DistanceResult) through ctypes with FCL's DistanceRequest built field for field "
                          "(python-fcl 0.7.0.11 cannot select GST_INDEP: its DistanceRequestd(bool, bool, "
                          "GJKSolverType) puts the solver type in rel_err); the objects are python-fcl's"
                          if VARIANT == "indep" else
                          "fcl.distance(CollisionObject, CollisionObject, DistanceRequest, DistanceResult) "
                          "(python-fcl hands FCL rel_err = 0.0 for GST_LIBCCD, FCL's default)"),
        "distance_solver_settings": solver,
        "distance normal": "FCL's DistanceResult has none: (p_a - p_b)/|p_a - p_b| of FCL's nearest points (d > 0), "
                           "(p_b - p_a)/|...| (d < 0); the zero vector where FCL's two points coincide (an overlap "
                           "FCL answers from its collide's contact, both points that contact's pos) or d = 0",
        "distance plane": ("fcl.Halfspace(n, d)" if VARIANT == "indep" else
                           "unsupported: FCL 0.7.0 crashes (SIGSEGV) on a Halfspace's distance under GST_LIBCCD"),
        "distance triangle": "fcl.BVHModel (OBBRSS) of the one triangle (FCL's distance matrix has no TriangleP)",
        "distance convex": "fcl.Convex(hull vertices, faces) at the identity; hull: " + crashtest_engine.HULL_NOTE,
        "scipy": package_version("scipy"),
    }
    if VARIANT == "libccd":
        return {**PROVENANCE, **dist}
    keep = ("python-fcl", "fcl.__version__", "libfcl", "libccd", "numpy", "precision", "margins", "box", "capsule",
            "stdout")
    return {**{k: PROVENANCE[k] for k in keep}, **dist}


def refused(case):
    """Why the adapter does not ask FCL this case at all, or None. A plane is FCL's
    Halfspace: under GST_LIBCCD FCL crashes on every distance to it (PLANE_CRASH)."""
    if case["query"] == "distance" and VARIANT == "libccd" and "plane" in case["b"]:
        return PLANE_CRASH
    return None


def distance_in_child(case, emit):
    """Runs in a worker (as toi_in_child does): FCL's objects, fcl.distance (signed, with
    nearest points) under the engine's solver, then to_format_distance. FCL dies (SIGSEGV)
    on some inputs (huge and tiny magnitudes, README): the worker dies with it, not the
    engine, and the case fails naming the call."""
    (ka, sa), = case["a"].items()
    (kb, sb), = case["b"].items()
    _, oa = DIST_BUILD[ka](sa)
    gb, ob = DIST_BUILD[kb](sb)
    emit({"stage": "distance"})
    t0 = time.perf_counter_ns()
    d, q0, q1, o1 = fcl_distance(oa, ob)
    ns = time.perf_counter_ns() - t0
    return {"answer": to_format_distance(case, d, q0, q1, o1, gb), "ns": ns}


IN_CHILD = {"toi": toi_in_child, "distance": distance_in_child}


def distance(case):
    """fcl.distance of a and b, asked in a forked worker (distance_in_child), translated
    there by to_format_distance; a case the adapter does not ask (`refused`) is
    `unsupported`."""
    why = refused(case)
    if why:
        raise Unsupported(why)
    return from_worker(case)


DISTANCE_HANDLERS = {("distance", a, b): distance for a, b in DISTANCE_PAIRS}
if VARIANT == "libccd":
    HANDLERS.update(DISTANCE_HANDLERS)
else:  # fcl/indep answers distance only
    HANDLERS = DISTANCE_HANDLERS

if __name__ == "__main__":
    sys.exit(serve(NAME, package_version("python-fcl"), 53, HANDLERS, provenance(),
                   reproductions=reproductions(HANDLERS, VARIANT), prepare=prepare))
