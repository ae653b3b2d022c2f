"""bullet's reproductions: for every pair engine.py answers, a standalone program
that asks Bullet (pybullet) one case the way engine.py does (the same shapes,
bodies, margins and calls) and prints pybullet's raw answer, before engine.py's
convention translation. engine.py passes `reproductions(HANDLERS)` to `serve`,
which puts them in the hello; crashtest fills the placeholders (`{{a.radius}}`,
...) with a finding's shrunk case (docs/PROTOCOL.md, hello, `reproductions`).

Keep them in step with engine.py: a change to `make_*`, `_body`, the margins or a
call there is a change here. One difference is kept on purpose: a program makes a
sphere a body, where engine.py gives getClosestPoints a bare sphere shape (to save
pybullet's dear body building); bare_spheres.py checks, in crashtest's tests, that
the two ways answer the same bit for bit.
"""
from crashtest_engine import pinned

HEAD = """\
# <pins>: crashtest `<query>` <pair>, asked as crashtest's bullet adapter asks it
<imports>import pybullet as p
p.connect(p.DIRECT)
"""

# --- Bullet's bodies, as engine.py's make_* build them (`@` is a or b): static
# (mass 0), identity orientation; collisionMargin 0 on every shape but the sphere,
# whose margin is its radius in Bullet
SHAPE = {
    "sphere": """\
@ = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=p.createCollisionShape(p.GEOM_SPHERE, radius={{@.radius}}),
                      basePosition={{@.center}})
""",
    # btStaticPlaneShape(n, 0), the body moved to the plane's point (d/|n|) n/|n|
    "plane": """\
n = {{@.normal}}
ln = math.hypot(*n)
s = {{@.offset}} / ln
@ = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=p.createCollisionShape(p.GEOM_PLANE, planeNormal=n),
                      basePosition=[n[0] / ln * s, n[1] / ln * s, n[2] / ln * s])
p.changeDynamics(@, -1, collisionMargin=0.0)
""",
    # vertices + indices: a static btBvhTriangleMeshShape
    "triangle": """\
shape = p.createCollisionShape(p.GEOM_MESH, vertices={{@.vertices}}, indices=[0, 1, 2], flags=p.GEOM_FORCE_CONCAVE_TRIMESH)
@ = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition=[0.0, 0.0, 0.0])
p.changeDynamics(@, -1, collisionMargin=0.0)
""",
    "mesh": """\
indices = [i for t in {{@.triangles}} for i in t]
shape = p.createCollisionShape(p.GEOM_MESH, vertices={{@.vertices}}, indices=indices, flags=p.GEOM_FORCE_CONCAVE_TRIMESH)
@ = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition=[0.0, 0.0, 0.0])
p.changeDynamics(@, -1, collisionMargin=0.0)
""",
    # btBoxShape(half extents) at the box's centre
    "aabb": """\
lo, hi = {{@.min}}, {{@.max}}
shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=[0.5 * hi[i] - 0.5 * lo[i] for i in range(3)])
@ = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition=[0.5 * lo[i] + 0.5 * hi[i] for i in range(3)])
p.changeDynamics(@, -1, collisionMargin=0.0)
""",
    # btBoxShape(half extents) at the centre, rotated: the quaternion [w, x, y, z] made
    # unit and written in pybullet's order [x, y, z, w]
    "box": """\
q = [float(x) for x in {{@.rotation}}]
q = [x / math.hypot(*q) for x in q]
shape = p.createCollisionShape(p.GEOM_BOX, halfExtents={{@.half_extents}})
@ = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition={{@.center}},
                      baseOrientation=[q[1], q[2], q[3], q[0]])
p.changeDynamics(@, -1, collisionMargin=0.0)
""",
    # GEOM_MESH with vertices only: a btConvexHullShape of the points (optimizeConvexHull) in a
    # btCompoundShape, at the origin; collisionMargin 0 reaches the hull
    "convex": """\
shape = p.createCollisionShape(p.GEOM_MESH, vertices={{@.points}})
@ = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition=[0.0, 0.0, 0.0])
p.changeDynamics(@, -1, collisionMargin=0.0)
""",
    # btCapsuleShapeZ(r, height) at the midpoint, its z turned onto end - start (its margin
    # is its radius: none is sent)
    "capsule": """\
st, en = {{@.start}}, {{@.end}}
d = [en[i] - st[i] for i in range(3)]
height = math.hypot(*d)
u = [x / height for x in d] if height > 0 else [0.0, 0.0, 1.0]
q = [1.0 + u[2], -u[1], u[0], 0.0] if u[2] >= 0 else [-u[1], 1.0 - u[2], 0.0, u[0]]
q = [x / math.hypot(*q) for x in q]
shape = p.createCollisionShape(p.GEOM_CAPSULE, radius={{@.radius}}, height=height)
@ = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition=[0.5 * st[i] + 0.5 * en[i] for i in range(3)],
                      baseOrientation=[q[1], q[2], q[3], q[0]])
""",
}

# getClosestPoints(A, B, distance): contactNormalOnB points from B toward A,
# contactDistance < 0 is penetration
CLOSEST = """\
points = p.getClosestPoints(a, b, 0.0)
print("points:", len(points))
for q in points:  # contactNormalOnB: from B toward A; contactDistance < 0: penetration
    print("positionOnA", list(q[5]), "positionOnB", list(q[6]), "contactNormalOnB", list(q[7]), "contactDistance", repr(q[8]))
"""

# distance: getClosestPoints with a distance above any the shapes can have (engine.py's
# distance_reach, pasted in, of the case's shapes)
DISTANCE = """\
points = p.getClosestPoints(a, b, distance_reach(case))
print("distance threshold:", distance_reach(case), "points:", len(points))
for q in points:  # contactNormalOnB: from B toward A; contactDistance < 0: penetration
    print("positionOnA", list(q[5]), "positionOnB", list(q[6]), "contactNormalOnB", list(q[7]), "contactDistance", repr(q[8]))
"""
DIST_SHAPE = {
    "sphere": """{"sphere": {"center": {{@.center}}, "radius": {{@.radius}}}}""",
    "box": """{"box": {"center": {{@.center}}, "half_extents": {{@.half_extents}}, "rotation": {{@.rotation}}}}""",
    "capsule": """{"capsule": {"start": {{@.start}}, "end": {{@.end}}, "radius": {{@.radius}}}}""",
    "plane": """{"plane": {"normal": {{@.normal}}, "offset": {{@.offset}}}}""",
    "triangle": """{"triangle": {"vertices": {{@.vertices}}}}""",
    "convex": """{"convex": {"points": {{@.points}}}}""",
}

# rayTest(from, to): the closest hit; objectUniqueId -1 is none. For a triangle mesh (and
# the plane's two triangles) Bullet turns the face normal toward the ray's start.
RAY = """\
obj, link, fraction, position, normal = p.rayTest({{a.start}}, {{a.end}})[0]
print("objectUniqueId", obj, "linkIndex", link, "hitFraction", repr(fraction), "hitPosition", list(position),
      "hitNormal", list(normal))
"""


# getAABB(body): Bullet's AABB of the body's shape at its transform
AABB = """\
lo, hi = p.getAABB(a)
print("getAABB:", list(lo), list(hi))
"""


def script(query, ka, kb, distmax_source=""):
    if query == "bounds":  # a box
        body = SHAPE[ka].replace("@", "a") + AABB
    elif query == "intersect":
        body = SHAPE[kb].replace("@", "b") + RAY
    elif query == "distance":
        body = ("import sys\n" + distmax_source + "\n\n"
                + f'case = {{"a": {DIST_SHAPE[ka].replace("@", "a")}, "b": {DIST_SHAPE[kb].replace("@", "b")}}}\n'
                + SHAPE[ka].replace("@", "a") + SHAPE[kb].replace("@", "b") + DISTANCE)
    else:  # contact; overlap (the adapter: overlap = at least one point)
        body = SHAPE[ka].replace("@", "a") + SHAPE[kb].replace("@", "b") + CLOSEST
    return (HEAD.replace("<pins>", pinned("pybullet")).replace("<query>", query).replace("<pair>", f"{ka}-{kb}" if kb else ka)
            .replace("<imports>", "import math\n" if "math." in body else "")) + body


def reproductions(handlers, distmax_source=""):
    """One script for every pair in `handlers` (engine.py's HANDLERS); `distmax_source`, the
    source of the common module's distance_reach, is pasted into the distance scripts."""
    return {(q, a, b): script(q, a, b, distmax_source) for q, a, b in handlers}
