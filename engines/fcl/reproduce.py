"""fcl's reproductions: for every pair engine.py answers, a standalone program
that asks FCL (python-fcl) one case the way engine.py does (the same shapes,
requests and calls) and prints the engine's raw answer, before engine.py's
convention translation. engine.py passes `reproductions(HANDLERS)` to `serve`,
which puts them in the hello; crashtest fills the placeholders (`{{a.radius}}`,
...) with a finding's shrunk case (docs/PROTOCOL.md, hello, `reproductions`).

Keep them in step with engine.py: a change to a builder, a request or a call
there is a change here.
"""
from crashtest_engine import pinned

# --- building FCL's objects, as engine.py's BUILD does (`@` is a or b) --------------
SHAPE = {
    "sphere": """\
g@ = fcl.Sphere({{@.radius}})
o@ = fcl.CollisionObject(g@, fcl.Transform(np.array({{@.center}}, dtype=np.float64)))
""",
    "plane": """\
g@ = fcl.Halfspace(np.array({{@.normal}}, dtype=np.float64), {{@.offset}})  # solid n.x <= d
o@ = fcl.CollisionObject(g@, fcl.Transform())
""",
    # FCL 0.7 has no sphere-TriangleP collision: the triangle is a one-face BVHModel
    "triangle": """\
g@ = fcl.BVHModel()  # OBBRSS, holding the one triangle
g@.beginModel(1, 3)
g@.addSubModel([np.array(v, dtype=np.float64) for v in {{@.vertices}}], [[0, 1, 2]])
g@.endModel()
o@ = fcl.CollisionObject(g@, fcl.Transform())
""",
    "mesh": """\
verts, tris = [np.array(v, dtype=np.float64) for v in {{@.vertices}}], {{@.triangles}}
g@ = fcl.BVHModel()  # OBBRSS, every face
g@.beginModel(len(tris), len(verts))
g@.addSubModel(verts, tris)
g@.endModel()
o@ = fcl.CollisionObject(g@, fcl.Transform())
""",
    # fcl.Box takes full side lengths; the quaternion [w, x, y, z] made unit (Eigen's
    # toRotationMatrix assumes a unit quaternion)
    "box": """\
q@ = np.array({{@.rotation}}, dtype=np.float64)
g@ = fcl.Box(*(2.0 * np.array({{@.half_extents}}, dtype=np.float64)))
o@ = fcl.CollisionObject(g@, fcl.Transform(q@ / math.hypot(*q@), np.array({{@.center}}, dtype=np.float64)))
""",
    # fcl.Capsule(r, lz) lies along its own z, centred: rotated onto end - start and moved
    # to the midpoint, as engine.py's capsule_pose does
    "capsule": """\
s@, e@ = np.array({{@.start}}, dtype=np.float64), np.array({{@.end}}, dtype=np.float64)
lz@ = math.hypot(*(e@ - s@))
u = (e@ - s@) / lz@ if lz@ > 0 else np.array([0.0, 0.0, 1.0])
q = np.array([1.0 + u[2], -u[1], u[0], 0.0] if u[2] >= 0 else [-u[1], 1.0 - u[2], 0.0, u[0]])
g@ = fcl.Capsule({{@.radius}}, lz@)
o@ = fcl.CollisionObject(g@, fcl.Transform(q / math.hypot(*q), 0.5 * s@ + 0.5 * e@))
""",
    "aabb": """\
lo, hi = np.array({{@.min}}, dtype=np.float64), np.array({{@.max}}, dtype=np.float64)
g@ = fcl.Box(*(hi - lo))  # an AABB as an fcl.Box at its centre
o@ = fcl.CollisionObject(g@, fcl.Transform(0.5 * lo + 0.5 * hi))
""",
}

HEAD = """\
# <pins>: crashtest `<query>` <pair>, asked as crashtest's fcl/libccd adapter asks it
import math
import numpy as np
import fcl
"""

# FCL's Contact: normal from the contact's o1 to its o2 (FCL may put the BVHModel first
# whatever the call's order); for the sphere-triangle routine penetration_depth is
# -(r - distance)
COLLIDE = """\
L = lambda v: [float(x) for x in v]
req = fcl.CollisionRequest(enable_contact=True, num_max_contacts=<max_contacts>, gjk_solver_type=fcl.GJKSolverType.GST_LIBCCD)
res = fcl.CollisionResult()
fcl.collide(oa, ob, req, res)
print("is_collision:", res.is_collision)
for c in res.contacts:  # normal: from o1 toward o2
    print("contact: o1 =", "a" if c.o1 is ga else "b", "b1 =", c.b1, "b2 =", c.b2, "pos =", L(c.pos),
          "normal =", L(c.normal), "penetration_depth =", repr(c.penetration_depth))
"""

OVERLAP = """\
def box(lo, hi):  # an AABB as an fcl.Box at its centre
    lo, hi = np.array(lo, dtype=np.float64), np.array(hi, dtype=np.float64)
    return fcl.CollisionObject(fcl.Box(*(hi - lo)), fcl.Transform(0.5 * lo + 0.5 * hi))
res = fcl.CollisionResult()
fcl.collide(box({{a.min}}, {{a.max}}), box({{b.min}}, {{b.max}}),
            fcl.CollisionRequest(gjk_solver_type=fcl.GJKSolverType.GST_LIBCCD), res)
print("is_collision:", res.is_collision)
"""

OVERLAP_SHAPES = """\
res = fcl.CollisionResult()
fcl.collide(oa, ob, fcl.CollisionRequest(gjk_solver_type=fcl.GJKSolverType.GST_LIBCCD), res)
print("is_collision:", res.is_collision)
"""

# toi: conservative advancement over the translation by velocity * t_max; then, at
# t = time_of_contact * t_max, FCL's contact (or, if apart, its distance). The adapter
# runs this in a forked worker so that a crash of FCL is one case's error.
TOI = """\
va, vb, t_max = np.array({{a.velocity}}, dtype=np.float64), np.array({{b.velocity}}, dtype=np.float64), {{t_max}}
pa, pb = oa.getTranslation(), ob.getTranslation()
ccd_req = fcl.ContinuousCollisionRequest(num_max_iterations=10, toc_err=1e-4, ccd_motion_type=fcl.CCDMotionType.CCDM_TRANS,
    gjk_solver_type=fcl.GJKSolverType.GST_INDEP, ccd_solver_type=fcl.CCDSolverType.CCDC_CONSERVATIVE_ADVANCEMENT)
ccd = fcl.ContinuousCollisionResult()
fcl.continuousCollide(oa, fcl.Transform(pa + t_max * va), ob, fcl.Transform(pb + t_max * vb), ccd_req, ccd)
print("is_collide:", ccd.is_collide, "time_of_contact (a fraction of t_max):", repr(ccd.time_of_contact))
if ccd.is_collide:  # both moved to t = time_of_contact * t_max, then FCL's contact there
    t = float(ccd.time_of_contact) * t_max
    oa.setTranslation(pa + t * va); ob.setTranslation(pb + t * vb)
<collide>    if not res.contacts:  # apart at t: FCL's distance (BVH-shape points in their object's frame)
        dres = fcl.DistanceResult()
        fcl.distance(oa, ob, fcl.DistanceRequest(enable_nearest_points=True, gjk_solver_type=fcl.GJKSolverType.GST_INDEP), dres)
        print("distance: o1 =", "a" if dres.o1 is ga else "b", "min_distance =", repr(dres.min_distance),
              "nearest_points =", [L(q) for q in dres.nearest_points])
"""


# --- distance -------------------------------------------------------------------------
# FCL's own fcl::distance<double>(const CollisionObject*, const CollisionObject*, const
# DistanceRequest&, DistanceResult&), called past python-fcl: python-fcl 0.7.0.11 builds
# its request as DistanceRequestd(enable_nearest_points, enable_signed_distance,
# gjk_solver_type) (fcl.pyx, `distance`), but FCL 0.7.0's constructor takes (bool, bool, S
# rel_err, S abs_err, S distance_tolerance, GJKSolverType) (distance_request.h): the solver
# type lands in rel_err (GST_INDEP -> 1.0) and the solver stays GST_LIBCCD. engine.py runs
# this very text (exec) for the fcl/indep engine; the structures are FCL 0.7.0's, field for
# field (distance_request.h, distance_result.h; Eigen's Vector3d is three doubles).
LIBFCL_DISTANCE = """\
import ctypes, glob, os, sys
class DistanceRequest(ctypes.Structure):  # fcl::DistanceRequest<double>
    _fields_ = [("enable_nearest_points", ctypes.c_bool), ("enable_signed_distance", ctypes.c_bool),
                ("rel_err", ctypes.c_double), ("abs_err", ctypes.c_double),
                ("distance_tolerance", ctypes.c_double), ("gjk_solver_type", ctypes.c_int)]
class DistanceResult(ctypes.Structure):  # fcl::DistanceResult<double>
    _fields_ = [("min_distance", ctypes.c_double), ("nearest_points", ctypes.c_double * 6),
                ("o1", ctypes.c_void_p), ("o2", ctypes.c_void_p), ("b1", ctypes.c_ssize_t), ("b2", ctypes.c_ssize_t)]
_libfcl = ctypes.CDLL(glob.glob(os.path.join(os.path.dirname(fcl.__file__), "..", "python_fcl.libs", "libfcl*.so*"))[0])
_fcl_distance = getattr(_libfcl, "_ZN3fcl8distanceIdEET_PKNS_15CollisionObjectIS1_EES5_RKNS_15DistanceRequestIS1_EERNS_14DistanceResultIS1_EE")
_fcl_distance.restype = ctypes.c_double
_fcl_distance.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.POINTER(DistanceRequest), ctypes.POINTER(DistanceResult)]
def cpp_pointer(obj):  # python-fcl's C++ object: Cython's `thisptr`, the first field after the object header
    return ctypes.c_void_p.from_address(id(obj) + object.__basicsize__).value
def libfcl_distance(o1, o2, solver, tolerance):
    req = DistanceRequest(True, True, 0.0, 0.0, tolerance, int(solver))
    res = DistanceResult(sys.float_info.max, (ctypes.c_double * 6)(), None, None, -1, -1)
    _fcl_distance(cpp_pointer(o1), cpp_pointer(o2), ctypes.byref(req), ctypes.byref(res))
    return res
"""

# fcl.Convex's faces from a Hull: FCL's flat list [count, i, j, k, ...]; a flat hull's polygon
# once per side; a segment or a point has none (FCL then searches its vertices one by one)
CONVEX_FACES = """\
def convex_faces(h):
    if h.dim == 2:
        ring = [int(i) for i in h.polygon]
        return 2, [len(ring), *ring, len(ring), *ring[::-1]]
    return len(h.triangles), [int(x) for t in h.triangles for x in (3, *t)]
"""

# the convex shape: the hull's vertices and faces for fcl.Convex, made as engine.py makes
# them (crashtest_engine.convex_hull, whose source is pasted in), at the identity
CONVEX = """\
h@ = convex_hull({{@.points}})
g@ = fcl.Convex([np.array(v, dtype=np.float64) for v in h@.vertices], *convex_faces(h@))
o@ = fcl.CollisionObject(g@, fcl.Transform())
"""

DISTANCE_LIBCCD = """\
# FCL's DistanceResult: min_distance (signed), nearest_points[0] on its o1, [1] on its o2, no normal
L = lambda v: [float(x) for x in v]
req = fcl.DistanceRequest(enable_nearest_points=True, enable_signed_distance=True,
                          gjk_solver_type=fcl.GJKSolverType.GST_LIBCCD)
res = fcl.DistanceResult()
fcl.distance(oa, ob, req, res)
print("min_distance:", repr(res.min_distance), "o1 =", "a" if res.o1 is ga else "b",
      "nearest_points:", [L(q) for q in res.nearest_points])
"""

DISTANCE_INDEP = """\
# FCL's DistanceResult: min_distance (signed), nearest_points[0] on its o1, [1] on its o2, no normal
res = libfcl_distance(oa, ob, fcl.GJKSolverType.GST_INDEP, 1e-6)
print("min_distance:", repr(res.min_distance), "o1 =", "a" if res.o1 == cpp_pointer(ga) else "b",
      "nearest_points:", list(res.nearest_points[:3]), list(res.nearest_points[3:]))
"""


def distance_script(variant, ka, kb):
    import inspect
    import crashtest_engine
    head = (HEAD.replace("<pins>", pinned("python-fcl", "numpy", "scipy"))
            .replace("<query>", "distance").replace("<pair>", f"{ka}-{kb}")
            .replace("fcl/libccd adapter", f"fcl/{variant} adapter"))
    if "convex" in (ka, kb):
        head += ("\n" + inspect.getsource(crashtest_engine.Hull) + "\n\n"
                 + inspect.getsource(crashtest_engine.convex_hull) + "\n\n" + CONVEX_FACES + "\n")
    if variant == "indep":
        head += LIBFCL_DISTANCE
    shapes = "".join(CONVEX.replace("@", r) if k == "convex" else SHAPE[k].replace("@", r)
                     for r, k in (("a", ka), ("b", kb)))
    call = DISTANCE_INDEP if variant == "indep" else DISTANCE_LIBCCD
    if variant == "libccd" and kb == "plane":
        call = "# FCL 0.7.0 dies here (SIGSEGV): no libccd support function for a Halfspace\n" + call
    return head + shapes + call


def indent(text, by="    "):
    return "".join(by + line if line.strip() else line for line in text.splitlines(True))


def script(query, ka, kb, variant="libccd"):
    if query == "distance":
        return distance_script(variant, ka, kb)
    head = (HEAD.replace("<pins>", pinned("python-fcl", "numpy"))
            .replace("<query>", query).replace("<pair>", f"{ka}-{kb}"))
    if query == "overlap" and (ka, kb) == ("aabb", "aabb"):
        return head + OVERLAP
    if query == "overlap":  # a box and a box or an AABB, as for aabb-aabb
        return head + SHAPE[ka].replace("@", "a") + SHAPE[kb].replace("@", "b") + OVERLAP_SHAPES
    shapes = SHAPE[ka].replace("@", "a") + SHAPE[kb].replace("@", "b")
    # one contact, or for a mesh one per face (the adapter takes the deepest, ties to
    # the lowest face index)
    collide = COLLIDE.replace("<max_contacts>", "max(1, len(tris))" if kb == "mesh" else "1")
    if query == "contact":
        return head + shapes + collide
    return head + shapes + TOI.replace("<collide>", indent(collide))


def reproductions(handlers, variant="libccd"):
    """One script for every pair in `handlers` (engine.py's HANDLERS); `variant`, the engine's
    GJK solver (libccd or indep), is the one its distance scripts ask for."""
    return {(q, a, b): script(q, a, b, variant) for q, a, b in handlers}
