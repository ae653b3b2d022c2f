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
# <pins>: crashtest `<query>` <pair>, asked as crashtest's fcl adapter asks it
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


def indent(text, by="    "):
    return "".join(by + line if line.strip() else line for line in text.splitlines(True))


def script(query, ka, kb):
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


def reproductions(handlers):
    """One script for every pair in `handlers` (engine.py's HANDLERS)."""
    return {(q, a, b): script(q, a, b) for q, a, b in handlers}
