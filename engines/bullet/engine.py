#!/usr/bin/env python3
"""bullet: Bullet Physics (pybullet 3.2.7) behind crashtest-engine/1.

Every answer is pybullet's own: getClosestPoints (btCollisionWorld::contactPairTest)
for `contact`, `overlap` and `distance` (asked up to a distance above the case's own),
rayTest (btCollisionWorld::rayTest, ClosestRayResultCallback) for `intersect`. The conventions Bullet uses are translated in ONE place, the section
"CONVENTION TRANSLATION" below; README.md has the table and the sources.
`world` messages are stepped by step_world (section "WORLDS"): Bullet rigid bodies,
stepSimulation; the restitution translation (sqrt(e) per body) is its one convention.
"""
import inspect
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
from crashtest_engine import DISTANCE_PAIRS, Unsupported, distance_reach, package_version, serve, timed  # noqa: E402
from reproduce import reproductions  # noqa: E402  (this folder's reproduce.py)

import pybullet as p  # noqa: E402  (prints its build time to fd 1 = standard error)

CLIENT = p.connect(p.DIRECT)

# --- Engine settings (echoed in the hello's provenance) -----------------------------
MARGIN = 0.0           # collisionMargin set with changeDynamics on every non-sphere body
DISTANCE = 0.0         # getClosestPoints' distance: points with contactDistance <= 0 only
RESET_EVERY = 256      # bodies and bare spheres created before p.resetSimulation() frees the leaked shapes

# pybullet cannot free a collision shape once a body has used it (removeCollisionShape
# answers "Don't remove collision shape: it is used" even after removeBody, and for an
# unused shape it frees the handle but not the shape: "TODO: dealloc"), so the world is
# reset now and then, outside the timed calls. resetSimulation() keeps
# gContactBreakingThreshold and the other settings used here.
_created = 0


def _housekeeping():
    global _created
    if _created >= RESET_EVERY:
        p.resetSimulation()
        _created = 0


def _body(shape, position, orientation=(0.0, 0.0, 0.0, 1.0)):
    """A static (mass 0) body of `shape` at `position`, with `orientation` (pybullet's
    quaternion order, [x, y, z, w]; the identity unless given)."""
    global _created
    _created += 1
    return p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=shape, basePosition=position,
                             baseOrientation=list(orientation))


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


def _xyzw(q):
    """The format's quaternion [w, x, y, z] (any non-zero length) divided by its length
    (math.hypot) and written in pybullet's order [x, y, z, w]."""
    n = math.hypot(*q)
    return [q[1] / n, q[2] / n, q[3] / n, q[0] / n]


def make_obox(b):
    # GEOM_BOX is btBoxShape(half extents) centred on the body, here at the box's centre
    # with its rotation; margin 0 as for the AABB's box (a zero half-extent is given as is)
    body = _body(p.createCollisionShape(p.GEOM_BOX, halfExtents=[float(h) for h in b["half_extents"]]),
                 b["center"], _xyzw(b.get("rotation", [1.0, 0.0, 0.0, 0.0])))
    _zero_margin(body)
    return body


def capsule_pose(c):
    """THE CAPSULE PLACEMENT (the only one). pybullet's GEOM_CAPSULE is btCapsuleShapeZ(r,
    height): the segment from (0, 0, -height/2) to (0, 0, height/2) of the body's frame
    swept by r (checked: a sphere beside the capsule meets its side, one beyond +z its
    end; Bullet's C++ btCapsuleShape lies along y, pybullet builds the Z one). The case's
    capsule: height = |end - start| (math.hypot), the body at start/2 + end/2, rotated by
    the quaternion taking z to u = (end - start)/height — [1 + u_z, -u_y, u_x, 0] for
    u_z >= 0, [-u_y, 1 - u_z, 0, u_x] (a half turn about x, then -z onto u) for u_z < 0,
    made unit — the identity for equal ends. Returns (height, position, [x, y, z, w])."""
    st, en = [float(x) for x in c["start"]], [float(x) for x in c["end"]]
    d = [en[i] - st[i] for i in range(3)]
    height = math.hypot(*d)
    if not math.isfinite(height):
        raise Unsupported("pybullet's capsule takes the length |end - start|, which overflows f64 here")
    mid = [0.5 * st[i] + 0.5 * en[i] for i in range(3)]
    if not height > 0:
        return 0.0, mid, [0.0, 0.0, 0.0, 1.0]
    u = [x / height for x in d]
    q = [1.0 + u[2], -u[1], u[0], 0.0] if u[2] >= 0 else [-u[1], 1.0 - u[2], 0.0, u[0]]
    return height, mid, _xyzw(q)


def make_capsule(c):
    # btCapsuleShapeZ: its margin is its radius (btCapsuleShape::setMargin does nothing:
    # "their entire radius == margin"), so no collisionMargin is sent, as for the sphere
    height, mid, orn = capsule_pose(c)
    return _body(p.createCollisionShape(p.GEOM_CAPSULE, radius=c["radius"], height=height), mid, orn)


def make_convex(c):
    # GEOM_MESH with vertices and no indices: a btConvexHullShape of the points (pybullet adds
    # each point, then optimizeConvexHull(): btConvexHullComputer's hull vertices replace them;
    # PhysicsServerCommandProcessor.cpp, createCollisionShape), the child of a btCompoundShape;
    # collisionMargin 0 reaches the child (changeDynamics sets every child's margin)
    body = _body(p.createCollisionShape(p.GEOM_MESH, vertices=[[float(x) for x in v] for v in c["points"]]),
                 [0.0, 0.0, 0.0])
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
    if kind == "box":
        return make_obox(s)
    if kind == "capsule":
        return make_capsule(s)
    if kind == "convex":
        return make_convex(s)
    raise Unsupported(f"no Bullet shape for {kind}")


def _cross(u, v):
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


# ======================= CONVENTION TRANSLATION (the only one) =======================
# getClosestPoints(A, B) returns points (.., positionOnA, positionOnB, contactNormalOnB,
# contactDistance, ..): the normal points from B toward A, positionOnB lies on B's
# surface, contactDistance < 0 is penetration. pybullet reorders Bullet's manifold into
# (A, B) itself (isSwapped in PhysicsServerCommandProcessor.cpp), so for every order:
#   point = positionOnB, normal = contactNormalOnB, depth = -contactDistance.
# Several points: the one with the smallest contactDistance. Seen for sphere-mesh, where
# btConvexConcaveCollisionAlgorithm runs btSphereTriangleCollisionAlgorithm on every face
# whose AABB meets the sphere's and reports one point per touching face; the smallest
# contactDistance is the face nearest the centre (depth = r - distance). On a tie the
# first of them in Bullet's order (its BVH traversal, not the face index) is taken.
# box-box, capsule-box, box-triangle, capsule-triangle: the same rule. getClosestPoints is
# contactPairTest with BT_CLOSEST_POINT_ALGORITHMS, and btDefaultCollisionConfiguration::
# getClosestPointsAlgorithmCreateFunc has no box-box entry: box-box and capsule-box run
# btConvexConvexAlgorithm (GJK, EPA when penetrating; NOT btBoxBoxDetector, which only the
# contact dispatch uses), the triangle pairs btConvexConcaveCollisionAlgorithm -> the same
# convex-convex algorithm against each btTriangleShape (margin 0, the mesh's). Bullet's
# manifold result writes positionOnB on B and the normal on B for these as for the others
# (checked on the campaign: of the cases whose depth Bullet gets right, the point lies on
# the referee's region in all but 2 - box-box 268 of 269, capsule-box 61 of 62, box- and
# capsule-triangle 247 and 155 of as many - the 2 near-ties answered along another
# direction).
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
# Bullet gives it (facing the segment's start). A box is convex: Bullet's convex cast
# (btGjkConvexCast, kF_UseGjkConvexCastRaytest) gives the surface normal where the ray
# enters, outward, and it is left as given; a capsule (make_capsule's body) is cast the
# same way. No barycentric, no face index, no
# `parallel`: pybullet reports none of them.
def hit_from_ray(result, face_normal):
    obj, _link, frac, pos, nrm = result
    if obj < 0:
        return {"hit": None}
    n = list(nrm)
    if face_normal is not None and sum(n[i] * face_normal[i] for i in range(3)) < 0:
        n = [-n[0], -n[1], -n[2]]
    return {"hit": {"t": frac, "point": list(pos), "normal": n}}
# distance: getClosestPoints(A, B, distance = DISTMAX) answers every point with
# contactDistance <= DISTMAX, so DISTMAX is chosen per case above any distance its shapes can
# have (distance_reach). Of Bullet's points the one with the least contactDistance (as for
# contact): distance = contactDistance (signed: < 0 in penetration), point_a = positionOnA,
# point_b = positionOnB, normal = contactNormalOnB (from B toward A; Bullet's manifold point
# has positionOnA = positionOnB + contactNormalOnB * contactDistance,
# btManifoldResult::addContactPoint), for every pair and order as for contact.
def distance_from_points(points, distmax):
    if not points:
        raise RuntimeError(f"getClosestPoints found no point within distance = {distmax!r}")
    pt = min(points, key=lambda q: q[8])
    return {"distance": pt[8], "point_a": list(pt[5]), "point_b": list(pt[6]), "normal": list(pt[7])}
# =====================================================================================


def distance(case):
    distmax = distance_reach(case)
    return distance_from_points(closest_points(case, distmax), distmax)



def _bare_sphere(shape):
    """A sphere's collision shape and centre, for getClosestPoints' bare-shape arguments
    (no body); None for any other shape. Counted with the bodies: it lives until the
    next reset."""
    global _created
    kind, s = next(iter(shape.items()))
    if kind != "sphere":
        return None
    _created += 1
    return p.createCollisionShape(p.GEOM_SPHERE, radius=s["radius"]), s["center"]


def closest_points(case, distance=DISTANCE):
    """Bullet's closest points of the case's two shapes (getClosestPoints, distance 0).

    Building a body is pybullet's dearest call (createMultiBody serializes the new body
    for its client), far dearer than the query, so a sphere goes as a bare
    collision shape at its centre (collisionShapeA/B and its position: the same
    btSphereShape, in a btCollisionObject at that place, given to the same
    contactPairTest) and only the other shape is made a body (removed after the call).
    pybullet decides whether Bullet reported the pair swapped by comparing the first
    object's body id with bodyA's, and a bare shape's id is -1: with a body on the other
    side the test still tells them apart. Two spheres both go bare:
    btSphereSphereCollisionAlgorithm never swaps them. AABBs, boxes and capsules are bodies."""
    _housekeeping()
    sa, sb = _bare_sphere(case["a"]), _bare_sphere(case["b"])
    if sa and sb:
        return timed(p.getClosestPoints, -1, -1, distance, collisionShapeA=sa[0], collisionShapeB=sb[0],
                     collisionShapePositionA=sa[1], collisionShapePositionB=sb[1])
    a = -1 if sa else make(case["a"])
    b = -1 if sb else make(case["b"])
    bare = {}
    if sa:
        bare.update(collisionShapeA=sa[0], collisionShapePositionA=sa[1])
    if sb:
        bare.update(collisionShapeB=sb[0], collisionShapePositionB=sb[1])
    try:
        return timed(p.getClosestPoints, a, b, distance, **bare)
    finally:
        for body in (a, b):
            if body >= 0:
                p.removeBody(body)


def contact(case):
    return contact_from_points(closest_points(case))


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
    return {"overlap": len(closest_points(case)) > 0}


def bounds_box(case):
    # getAABB of the box's body (margin 0): btBoxShape::getAabb at the body's transform,
    # Bullet's own AABB of the rotated box (btTransformAabb: centre +- |R| h). pybullet
    # exposes no bounding sphere, so only `aabb` is answered.
    _housekeeping()
    body = make(case["a"])
    try:
        lo, hi = timed(p.getAABB, body)
    finally:
        p.removeBody(body)
    return {"aabb": {"min": [float(x) for x in lo], "max": [float(x) for x in hi]}}


# ======================= WORLDS (rigid-body dynamics) =======================
# One `world` message (docs/PROTOCOL.md, "Worlds"): Bullet's own btDiscreteDynamicsWorld
# step (pybullet's btMultiBodyDynamicsWorld, whose rigid bodies go through
# btDiscreteDynamicsWorld and btSequentialImpulseConstraintSolver), one set of settings
# for every world. All bodies are btRigidBody (createMultiBody(useMaximalCoordinates=1)):
# pybullet's changeDynamics applies ccdSweptSphereRadius, and the sleeping switch
# (forceActivationState), only to btRigidBody, not to a btMultiBody base.
W_SOLVER_ITERATIONS = 50          # pybullet's default, set explicitly
W_SUBSTEPS = 0                    # stepSimulation(dt, 0): one internal step of exactly dt
W_BREAKING_THRESHOLD = 0.02       # gContactBreakingThreshold, Bullet's default, set explicitly
W_RESTITUTION_THRESHOLD = 0.0     # m_restitutionVelocityThreshold (Bullet default 0.2)
W_SPLIT_IMPULSE = 1               # Bullet's default (m_splitImpulse = true), set explicitly
W_SPLIT_THRESHOLD = 0.0           # m_splitImpulsePenetrationThreshold (Bullet default -0.04): every penetration split
W_CONTACT_ERP = 0.08              # m_erp2, pybullet's default, set explicitly
W_CONTACT_SLOP = 0.00001          # m_linearSlop, pybullet's default, set explicitly
W_ALLOWED_CCD_PENETRATION = 0.04  # btDispatcherInfo::m_allowedCcdPenetration, Bullet's default


# ---- CONVENTION TRANSLATION (worlds): restitution -----------------------------------
# Bullet combines the restitution of two colliding objects by multiplication
# (btManifoldResult::calculateCombinedRestitution: body0->getRestitution() *
# body1->getRestitution()). Each body therefore gets sqrt(e_i): the contact's restitution
# is sqrt(e_i * e_j), the geometric mean, which is e for every pair (sphere-plane,
# sphere-box, sphere-sphere) when the world's bodies share e, as crashtest's worlds do.
# (Giving static bodies 1 and spheres e would make sphere-sphere contacts e^2.)
def bullet_restitution(e):
    return math.sqrt(e)


def _world_body(shape, mass, position):
    return p.createMultiBody(baseMass=mass, baseCollisionShapeIndex=shape, basePosition=position,
                             useMaximalCoordinates=1)


def _world_dynamics(body, e, ccd_radius):
    p.changeDynamics(body, -1, restitution=bullet_restitution(e), lateralFriction=0.0,
                     spinningFriction=0.0, rollingFriction=0.0, linearDamping=0.0,
                     angularDamping=0.0, activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING,
                     ccdSweptSphereRadius=ccd_radius)


def world_settings(ccd):
    return {
        "bullet": "pybullet " + package_version("pybullet") + " (Bullet 3, f64), p.DIRECT",
        "world": "resetSimulation per world; btMultiBodyDynamicsWorld with btRigidBody bodies "
                 "(createMultiBody(useMaximalCoordinates=1)), btMultiBodyConstraintSolver "
                 "(sequential impulse for rigid contacts)",
        "time_step": "setTimeStep(dt); numSubSteps=0 -> stepSimulation(dt, 0): one internal step of dt, "
                     "no interpolation",
        "solver_iterations": str(W_SOLVER_ITERATIONS),
        "solver_residual_threshold": "1e-7 (pybullet default)",
        "split_impulse": f"{W_SPLIT_IMPULSE} (penetration threshold {W_SPLIT_THRESHOLD})",
        "contact_erp": f"{W_CONTACT_ERP} (m_erp2, position recovery)",
        "contact_slop": f"{W_CONTACT_SLOP} (m_linearSlop)",
        "warm_starting": "on, factor 0.1 (pybullet default)",
        "restitution_velocity_threshold": f"{W_RESTITUTION_THRESHOLD} (Bullet default 0.2)",
        "restitution_mapping": "each body restitution sqrt(e); Bullet multiplies the two "
                               "(btManifoldResult::calculateCombinedRestitution) -> contact restitution e",
        "friction": "lateral, spinning, rolling 0 on every body (combined by product -> 0)",
        "damping": "linear 0, angular 0 on every sphere and static body",
        "sleeping": "disabled (activationState DISABLE_SLEEPING -> DISABLE_DEACTIVATION)",
        "margins": "plane and box collisionMargin 0; sphere margin = its radius (btSphereShape, by definition)",
        "contact_breaking_threshold": f"{W_BREAKING_THRESHOLD} (Bullet default; contacts are created up to "
                                      "this gap and act as speculative contacts: separation/dt is allowed)",
        "ccd": ("on: ccdSweptSphereRadius = radius, ccdMotionThreshold = radius/2 (pybullet sets it), "
                f"allowedCcdPenetration {W_ALLOWED_CCD_PENETRATION}; Bullet clamps the motion at the swept "
                "sphere's first hit (integrateTransforms) and adds a predictive contact with restitution 0")
               if ccd else "off: ccdSweptSphereRadius 0 (ccdMotionThreshold 0)",
        "spheres": "GEOM_SPHERE, mass m, inertia of a solid ball (Bullet computes 2/5 m r^2)",
        "plane": "GEOM_PLANE btStaticPlaneShape(n, 0) at (d/|n|) n/|n|, mass 0 (static)",
        "box": "GEOM_BOX btBoxShape(half extents) at the centre, mass 0 (static)",
    }


def step_world(msg):
    global _created
    p.resetSimulation()
    _created = 0
    dt = float(msg["dt"])
    steps = int(msg["steps"])
    ccd = bool(msg.get("ccd", False))
    p.setGravity(*[float(g) for g in msg["gravity"]])
    p.setTimeStep(dt)
    p.setPhysicsEngineParameter(fixedTimeStep=dt, numSubSteps=W_SUBSTEPS,
                                numSolverIterations=W_SOLVER_ITERATIONS,
                                contactBreakingThreshold=W_BREAKING_THRESHOLD,
                                restitutionVelocityThreshold=W_RESTITUTION_THRESHOLD,
                                useSplitImpulse=W_SPLIT_IMPULSE,
                                splitImpulsePenetrationThreshold=W_SPLIT_THRESHOLD,
                                contactERP=W_CONTACT_ERP, contactSlop=W_CONTACT_SLOP,
                                allowedCcdPenetration=W_ALLOWED_CCD_PENETRATION)
    spheres = []
    for b in msg["bodies"]:
        e = float(b.get("restitution", 0.0))
        if not 0.0 <= e <= 1.0:
            raise ValueError(f"restitution {e} outside [0, 1]")
        if "sphere" in b:
            s = b["sphere"]
            r = float(s["radius"])
            body = _world_body(p.createCollisionShape(p.GEOM_SPHERE, radius=r), float(b["mass"]), s["center"])
            _world_dynamics(body, e, r if ccd else 0.0)
            p.resetBaseVelocity(body, linearVelocity=b.get("velocity", [0.0, 0.0, 0.0]), angularVelocity=[0.0, 0.0, 0.0])
            spheres.append(body)
        elif "plane" in b:
            n = b["plane"]["normal"]
            ln = math.hypot(*n)
            k = b["plane"]["offset"] / ln
            body = _world_body(p.createCollisionShape(p.GEOM_PLANE, planeNormal=n), 0.0,
                               [n[0] / ln * k, n[1] / ln * k, n[2] / ln * k])
            _world_dynamics(body, e, 0.0)
            p.changeDynamics(body, -1, collisionMargin=MARGIN)
        elif "box" in b:
            bx = b["box"]
            body = _world_body(p.createCollisionShape(p.GEOM_BOX, halfExtents=bx["half_extents"]), 0.0, bx["center"])
            _world_dynamics(body, e, 0.0)
            p.changeDynamics(body, -1, collisionMargin=MARGIN)
        else:
            raise Unsupported(f"no Bullet body for {next(iter(b))}")

    def centres():
        return [list(p.getBasePositionAndOrientation(s)[0]) for s in spheres]

    positions = [centres()]
    for _ in range(steps):
        timed(p.stepSimulation)   # only Bullet's step is charged, not the position reads
        positions.append(centres())
    velocities = [list(p.getBaseVelocity(s)[0]) for s in spheres]
    p.resetSimulation()           # leave an empty world for the collision queries
    return {"positions": positions, "velocities": velocities, "settings": world_settings(ccd)}
# =====================================================================================


HANDLERS = {
    ("contact", "sphere", "sphere"): contact,
    ("contact", "sphere", "plane"): contact,
    ("contact", "plane", "sphere"): contact,
    ("contact", "sphere", "triangle"): contact,
    ("contact", "triangle", "sphere"): contact,
    ("contact", "sphere", "mesh"): contact,
    ("intersect", "segment", "plane"): intersect,
    ("intersect", "segment", "triangle"): intersect,
    ("intersect", "segment", "mesh"): intersect,
    ("overlap", "aabb", "aabb"): overlap,
    ("contact", "sphere", "box"): contact,
    ("contact", "box", "plane"): contact,
    ("contact", "sphere", "capsule"): contact,
    ("contact", "capsule", "capsule"): contact,
    ("contact", "capsule", "plane"): contact,
    ("contact", "box", "box"): contact,
    ("contact", "box", "triangle"): contact,
    ("contact", "capsule", "box"): contact,
    ("contact", "capsule", "triangle"): contact,
    ("intersect", "segment", "box"): intersect,
    ("intersect", "segment", "capsule"): intersect,
    ("overlap", "box", "box"): overlap,
    ("overlap", "box", "aabb"): overlap,
    ("bounds", "box", None): bounds_box,
}

for _a, _b in DISTANCE_PAIRS:
    HANDLERS[("distance", _a, _b)] = distance

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
    "mesh_shape": "GEOM_MESH vertices+indices, GEOM_FORCE_CONCAVE_TRIMESH -> static btBvhTriangleMeshShape "
                  "(concave: every face, two-sided); sphere-mesh contact: getClosestPoints, the point "
                  "with the smallest contactDistance",
    "plane_shape": "GEOM_PLANE -> btStaticPlaneShape(n, 0), body at (d/|n|) n/|n|",
    "box_shape": "GEOM_BOX -> btBoxShape(half extents), body at the centre with orientation [x, y, z, w] "
                 "= the case's [w, x, y, z] made unit, collisionMargin 0 (contact, overlap and segment-box alike)",
    "capsule_shape": "GEOM_CAPSULE -> btCapsuleShapeZ(r, height = |end - start|), body at start/2 + end/2 "
                     "rotated z -> end - start; its margin is its radius (none sent)",
    "box_capsule_contacts": "getClosestPoints(bodyA, bodyB or a bare sphere, distance=0), the point with the "
                            "smallest contactDistance; segment-box, segment-capsule: rayTest",
    "distance_query": "getClosestPoints(A, B, distance = DISTMAX) (a sphere as a bare shape, as for contact), the "
                      "point with the least contactDistance; DISTMAX per case 8 M + 1 (at most DBL_MAX), M the largest "
                      "magnitude of the case's coordinates, radii, half-extents and plane offsets over |n|",
    "convex_shape": "GEOM_MESH vertices only -> btConvexHullShape of the points, optimizeConvexHull() "
                    "(btConvexHullComputer), in a btCompoundShape; collisionMargin 0 (changeDynamics, every child)",
    "polytope_contacts": "box-box and capsule-box: btConvexConvexAlgorithm (GJK + EPA; the closest-points dispatch "
                         "has no btBoxBoxCollisionAlgorithm); box-triangle and capsule-triangle: "
                         "btConvexConcaveCollisionAlgorithm -> convex-convex against the btTriangleShape",
}

if __name__ == "__main__":
    sys.exit(serve("bullet", package_version("pybullet"), 53, HANDLERS, PROVENANCE, world=step_world,
                   reproductions=reproductions(HANDLERS, inspect.getsource(distance_reach))))
