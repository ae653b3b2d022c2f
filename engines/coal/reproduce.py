"""coal's reproductions: for every pair engine.py answers, a standalone program
that asks Coal one case the way engine.py does (the same shapes, request and
calls) and prints the engine's raw answer, before engine.py's convention
translation. engine.py passes `reproductions(HANDLERS)` to `serve`, which puts
them in the hello; crashtest fills the placeholders (`{{a.radius}}`, ...) with a
finding's shrunk case (docs/PROTOCOL.md, hello, `reproductions`).

Keep them in step with engine.py: a change to `coal_shape`, `mesh_model`, the
request or a call there is a change here.
"""
from crashtest_engine import pinned

HEAD = """\
# <pins>: crashtest `<query>` <pair>, asked as crashtest's <engine> adapter asks it
import math
import numpy as np
import coal
"""

# --- Coal's geometry and placement, as engine.py's coal_shape does (`@` is a or b) ---
SHAPE = {
    "sphere": """\
g@, t@ = coal.Sphere({{@.radius}}), coal.Transform3s()
t@.setTranslation(np.array({{@.center}}, dtype=np.float64))
""",
    "plane": """\
g@, t@ = coal.Halfspace(np.array({{@.normal}}, dtype=np.float64), {{@.offset}}), coal.Transform3s()  # solid n.x <= d
""",
    "triangle": """\
v = [np.array(p, dtype=np.float64) for p in {{@.vertices}}]
g@, t@ = coal.TriangleP(v[0], v[1], v[2]), coal.Transform3s()
""",
    # coal.Box takes full side lengths; coal.Quaternion(w, x, y, z), made unit first
    "box": """\
q = [float(x) for x in {{@.rotation}}]
q = [x / math.hypot(*q) for x in q]
g@ = coal.Box(*(2.0 * np.array({{@.half_extents}}, dtype=np.float64)))
t@ = coal.Transform3s(coal.Quaternion(*q), np.array({{@.center}}, dtype=np.float64))
""",
    # coal.Capsule(r, lz) lies along its own z, centred (halfLength = lz/2): rotated onto
    # end - start and moved to the midpoint, as engine.py's capsule_pose does
    "capsule": """\
s, e = np.array({{@.start}}, dtype=np.float64), np.array({{@.end}}, dtype=np.float64)
lz = math.hypot(*(e - s))
u = (e - s) / lz if lz > 0 else np.array([0.0, 0.0, 1.0])
q = [1.0 + u[2], -u[1], u[0], 0.0] if u[2] >= 0 else [-u[1], 1.0 - u[2], 0.0, u[0]]
q = [float(x) / math.hypot(*q) for x in q]
g@, t@ = coal.Capsule({{@.radius}}, lz), coal.Transform3s(coal.Quaternion(*q), 0.5 * s + 0.5 * e)
""",
    "aabb": """\
lo, hi = np.array({{@.min}}, dtype=np.float64), np.array({{@.max}}, dtype=np.float64)
g@, t@ = coal.Box(*(hi - lo)), coal.Transform3s()  # an AABB as a Box at its centre
t@.setTranslation(0.5 * lo + 0.5 * hi)
""",
}

# a BVHModelOBBRSS of a mesh's vertices and faces, or (bounds of points) of vertices only
MODEL = """\
verts = np.array({{@.<field>}}, dtype=np.float64).reshape(-1, 3)
<tris>g@ = coal.BVHModelOBBRSS()
g@.beginModel(<faces>, len(verts))
g@.addVertices(verts)
<add>print("endModel:", g@.endModel())
"""


def model(role, field, mesh):
    return (MODEL.replace("<field>", field)
            .replace("<tris>", "tris = np.array({{@.triangles}}, dtype=np.int64).reshape(-1, 3)\n" if mesh else "")
            .replace("<faces>", "len(tris)" if mesh else "0")
            .replace("<add>", "g@.addTriangles(tris)\n" if mesh else "")
            .replace("@", role))


# Coal's Contact: normal from o1 (= a) toward o2 (= b); nearest points on o1 and o2;
# penetration_depth is the SIGNED distance (negative when overlapping)
CONTACT = """\
L = lambda v: [float(x) for x in v]
req = coal.CollisionRequest()
req.security_margin, req.num_max_contacts, req.enable_contact = 0.0, <max_contacts>, True
res = coal.CollisionResult()
coal.collide(ga, ta, gb, tb, req, res)
print("isCollision:", res.isCollision())
for i in range(res.numContacts()):
    c = res.getContact(i)  # normal from a toward b; penetration_depth = signed distance
    print(f"contact {i}: normal {L(c.normal)} nearest_point1 {L(c.getNearestPoint1())} "
          f"nearest_point2 {L(c.getNearestPoint2())} penetration_depth {c.penetration_depth!r} b1 {c.b1} b2 {c.b2}")
"""

OVERLAP = """\
box_a = coal.AABB(np.array({{a.min}}, dtype=np.float64), np.array({{a.max}}, dtype=np.float64))
box_b = coal.AABB(np.array({{b.min}}, dtype=np.float64), np.array({{b.max}}, dtype=np.float64))
print("overlap:", box_a.overlap(box_b))
"""

OVERLAP_SHAPES = """\
req = coal.CollisionRequest()
req.security_margin, req.num_max_contacts, req.enable_contact = 0.0, 1, False
res = coal.CollisionResult()
coal.collide(ga, ta, gb, tb, req, res)
print("isCollision:", res.isCollision())
"""

BOUNDS_BOX = """\
L = lambda v: [float(x) for x in v]
obj = coal.CollisionObject(ga, ta)
obj.computeAABB()
print("getAABB: min_", L(obj.getAABB().min_), "max_", L(obj.getAABB().max_))
ga.computeLocalAABB()
print("aabb_center (local):", L(ga.aabb_center), "in world:", L(ta.transform(ga.aabb_center)),
      "aabb_radius:", repr(ga.aabb_radius))
"""

BOUNDS = """\
L = lambda v: [float(x) for x in v]
ga.computeLocalAABB()
print("aabb_local: min_", L(ga.aabb_local.min_), "max_", L(ga.aabb_local.max_))
print("aabb_center:", L(ga.aabb_center), "aabb_radius:", repr(ga.aabb_radius))
"""


# --- distance: coal.distance (the triangle pairs: coal.collide with security_margin =
# DBL_MAX), the request's GJK variant the engine's, every other setting Coal's default ---
# the convex shape: coal.Convex of the hull's vertices and triangles, made as engine.py makes
# them (crashtest_engine.convex_hull, whose source is pasted in), at the identity
CONVEX = """\
h@ = convex_hull({{@.points}})
pts, tris = coal.StdVec_Vec3s(), coal.StdVec_Triangle()
for v in h@.vertices:
    pts.append(np.array(v, dtype=np.float64))
for t in h@.triangles:
    tris.append(coal.Triangle(int(t[0]), int(t[1]), int(t[2])))
g@, t@ = coal.Convex(pts, tris), coal.Transform3s()
"""

# Coal's DistanceResult: min_distance signed; nearest point 1 on a, 2 on b; normal from a
# toward b, = (p2 - p1) / min_distance
DISTANCE = """\
L = lambda v: [float(x) for x in v]
req = coal.DistanceRequest()
req.enable_signed_distance = True
req.gjk_variant = coal.GJKVariant.<variant>
res = coal.DistanceResult()
coal.distance(ga, ta, gb, tb, req, res)
print(f"min_distance {res.min_distance!r} normal {L(res.normal)} nearest_point1 {L(res.getNearestPoint1())} "
      f"nearest_point2 {L(res.getNearestPoint2())}")
"""

# Coal's distance has no TriangleP: collide with security_margin = DBL_MAX runs the same
# shape-shape distance and reports it as a Contact (penetration_depth = signed distance)
DISTANCE_TRIANGLE = """\
import sys
L = lambda v: [float(x) for x in v]
req = coal.CollisionRequest()
req.enable_contact, req.num_max_contacts, req.security_margin = True, 1, sys.float_info.max
req.gjk_variant = coal.GJKVariant.<variant>
res = coal.CollisionResult()
coal.collide(ga, ta, gb, tb, req, res)
for i in range(res.numContacts()):
    c = res.getContact(i)
    print(f"contact {i}: penetration_depth (signed distance) {c.penetration_depth!r} normal {L(c.normal)} "
          f"nearest_point1 {L(c.getNearestPoint1())} nearest_point2 {L(c.getNearestPoint2())}")
"""


def distance_script(ka, kb, variant):
    import inspect
    import crashtest_engine
    engine = {"DefaultGJK": "coal", "NesterovAcceleration": "coal/nesterov", "PolyakAcceleration": "coal/polyak"}[variant]
    head = (HEAD.replace("<pins>", pinned("coal", "libcoal", "numpy", "scipy")).replace("<engine>", engine)
            .replace("<query>", "distance").replace("<pair>", f"{ka}-{kb}"))
    if "convex" in (ka, kb):
        head += ("\n" + inspect.getsource(crashtest_engine.Hull) + "\n\n"
                 + inspect.getsource(crashtest_engine.convex_hull) + "\n\n")
    shapes = "".join(CONVEX.replace("@", r) if k == "convex" else SHAPE[k].replace("@", r)
                     for r, k in (("a", ka), ("b", kb)))
    return head + shapes + (DISTANCE_TRIANGLE if kb == "triangle" else DISTANCE).replace("<variant>", variant)


def script(query, ka, kb, variant="DefaultGJK"):
    if query == "distance":
        return distance_script(ka, kb, variant)
    head = (HEAD.replace("<pins>", pinned("coal", "libcoal", "numpy")).replace("<engine>", "coal")
            .replace("<query>", query).replace("<pair>", f"{ka}-{kb}" if kb else ka))
    if query == "overlap" and (ka, kb) == ("aabb", "aabb"):
        return head + OVERLAP
    if query == "overlap":  # box-box, box-aabb: the shapes collided without contacts
        return head + SHAPE[ka].replace("@", "a") + SHAPE[kb].replace("@", "b") + OVERLAP_SHAPES
    if query == "bounds" and ka == "box":
        return head + SHAPE["box"].replace("@", "a") + BOUNDS_BOX
    if query == "bounds":
        return head + model("a", "points" if ka == "points" else "vertices", ka == "mesh") + BOUNDS
    shapes = "".join(model(r, "vertices", True) + f"t{r} = coal.Transform3s()\n" if k == "mesh"
                     else SHAPE[k].replace("@", r)
                     for r, k in (("a", ka), ("b", kb)))
    # one contact, or for a mesh one per face (the adapter takes the deepest, ties to
    # the lowest face index)
    return head + shapes + CONTACT.replace("<max_contacts>", "max(1, len(tris))" if kb == "mesh" else "1")


def reproductions(handlers, variant="DefaultGJK"):
    """One script for every pair in `handlers` (engine.py's HANDLERS); `variant`, the engine's
    coal.GJKVariant, is the one its distance scripts ask for."""
    return {(q, a, b): script(q, a, b, variant) for q, a, b in handlers}
