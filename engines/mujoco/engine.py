#!/usr/bin/env python3
"""mujoco: MuJoCo (the `mujoco` Python package) behind crashtest-engine/1.

Every answer is MuJoCo's own: contacts from `mj_collision` on an MjModel built from
MJCF, hits from `mj_ray` (plane, mesh geoms) and `mj_rayFlex` (a one-triangle flex).
The only arithmetic done here is (1) turning the case's shapes into MuJoCo's
representation (a plane's point and orientation, geom positions and sizes) and
(2) the convention translation in ONE place, `translate_contact` / `translate_hit`
below, and `to_format_distance` for distances from `mj_geomDistance` (section
"DISTANCE"). See README.md.
"""
import inspect
import math
import os
import re
import sys

# --- protect the protocol: MuJoCo (C code) may print to fd 1 (warnings go through
# printf). Keep a private duplicate of fd 1 for the protocol, point fd 1 at stderr,
# and make sys.stdout write to the duplicate. Done before importing mujoco.
_proto_fd = os.dup(1)
os.dup2(2, 1)
sys.stdout = os.fdopen(_proto_fd, "w", buffering=1 << 16, encoding="utf-8", newline="\n")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from crashtest_engine import DISTANCE_PAIRS as ALL_DISTANCE_PAIRS, Unsupported, distance_reach, package_version, serve, timed  # noqa: E402
from reproduce import reproductions  # noqa: E402  (this folder's reproduce.py)

import numpy as np  # noqa: E402
import mujoco  # noqa: E402

# MuJoCo appends its errors and warnings to MUJOCO_LOG.TXT in the working
# directory; work in a private temporary one so that a run leaves nothing in the
# user's folder (cases arrive inline: no path is read relative to it).
import atexit  # noqa: E402
import shutil  # noqa: E402
import tempfile  # noqa: E402
_workdir = tempfile.mkdtemp(prefix="crashtest-mujoco-")
os.chdir(_workdir)
atexit.register(shutil.rmtree, _workdir, True)

MARGIN = 0.0  # geom/flex margin, set explicitly on every geom and flex
GAP = 0.0  # geom/flex gap, set explicitly on every geom and flex
FLEX_RADIUS = 0.0  # a triangle is a dim-2 flex element of radius 0

# ---------------------------------------------------------------- models (built once)
# The shape `b` lives in the world body; the sphere `a` (or the sphere of a reversed
# pair) lives in a body with a free joint, so that MuJoCo's collision filter (which skips
# pairs of dof-less bodies) lets them collide. World-body geoms are paired with every
# collidable body directly (mj_broadphase's "always colliding" path, no SAP), and each
# geom pair then passes MuJoCo's bounding-sphere filter (geom_rbound) before the
# narrow phase.
_GEOM = f'margin="{MARGIN!r}" gap="{GAP!r}"'
XML_SPHERE_SPHERE = f"""<mujoco><worldbody>
  <geom name="b" type="sphere" size="1" {_GEOM}/>
  <body name="a"><freejoint/><geom name="a" type="sphere" size="1" {_GEOM}/></body>
</worldbody></mujoco>"""
XML_PLANE_SPHERE = f"""<mujoco><worldbody>
  <geom name="b" type="plane" size="0 0 1" {_GEOM}/>
  <body name="a"><freejoint/><geom name="a" type="sphere" size="1" {_GEOM}/></body>
</worldbody></mujoco>"""
XML_FLEX_SPHERE = f"""<mujoco><worldbody>
  <body name="a"><freejoint/><geom name="a" type="sphere" size="1" {_GEOM}/></body>
</worldbody><deformable>
  <flex name="tri" dim="2" body="world world world" vertex="0 0 0  1 0 0  0 1 0" element="0 1 2"
        radius="{FLEX_RADIUS!r}"><contact margin="{MARGIN!r}" gap="{GAP!r}"/></flex>
</deformable></mujoco>"""
XML_PLANE_ONLY = f"""<mujoco><worldbody>
  <geom name="b" type="plane" size="0 0 1" {_GEOM}/>
</worldbody></mujoco>"""
MESH_INERTIA = "shell"  # a flat or open mesh has no volume; "shell" lets it compile
# aabb-aabb overlap: two box geoms, b in the world body, a in a free body (identity
# orientation: no quat, the free joint at qpos0), both collidable (contype = conaffinity
# = 1, MuJoCo's default); mj_collision -> mjc_BoxBox (engine_collision_box.c).
XML_BOX_BOX = f"""<mujoco><worldbody>
  <geom name="b" type="box" size="1 1 1" contype="1" conaffinity="1" {_GEOM}/>
  <body name="a"><freejoint/><geom name="a" type="box" size="1 1 1" contype="1" conaffinity="1" {_GEOM}/></body>
</worldbody></mujoco>"""

# Boxes and capsules (contact, segment-box): b a geom of the world body, a (the sphere, the
# box or the capsule of the case's a) a geom of a free body, both collidable (MuJoCo's
# default contype = conaffinity = 1). Sizes and poses are written per case (set_obox,
# set_capsule, set_sphere, set_plane); those in the MJCF only let it compile.
def _xml_pair(b, a):
    return (f'<mujoco><worldbody>\n  <geom name="b" {b} {_GEOM}/>\n'
            f'  <body name="a"><freejoint/><geom name="a" {a} {_GEOM}/></body>\n</worldbody></mujoco>')


_SPHERE, _BOX, _CAPSULE, _PLANE = ('type="sphere" size="1"', 'type="box" size="1 1 1"',
                                   'type="capsule" size="1 1"', 'type="plane" size="0 0 1"')
XML_SPHERE_BOX = _xml_pair(_BOX, _SPHERE)
XML_PLANE_BOX = _xml_pair(_PLANE, _BOX)
XML_SPHERE_CAPSULE = _xml_pair(_CAPSULE, _SPHERE)
XML_CAPSULE_CAPSULE = _xml_pair(_CAPSULE, _CAPSULE)
XML_PLANE_CAPSULE = _xml_pair(_PLANE, _CAPSULE)
XML_CAPSULE_BOX = _xml_pair(_BOX, _CAPSULE)
# box-triangle, capsule-triangle: the triangle is the one-element dim-2 flex of
# sphere-triangle (vertices written per case into flex_vert), the box or the capsule a geom
# of a free body. mj_collideGeomElem (engine_collision_driver.c) runs MuJoCo's dedicated
# mjraw_BoxTriangle / mjraw_CapsuleTriangle (engine_collision_primitive.c) on it.
def _xml_flex(a):
    return (f'<mujoco><worldbody>\n  <body name="a"><freejoint/><geom name="a" {a} {_GEOM}/></body>\n'
            f'</worldbody><deformable>\n  <flex name="tri" dim="2" body="world world world" '
            f'vertex="0 0 0  1 0 0  0 1 0" element="0 1 2"\n        radius="{FLEX_RADIUS!r}">'
            f'<contact margin="{MARGIN!r}" gap="{GAP!r}"/></flex>\n</deformable></mujoco>')


XML_FLEX_BOX = _xml_flex(_BOX)
XML_FLEX_CAPSULE = _xml_flex(_CAPSULE)
# segment-box: the box alone, not collidable (mj_ray needs no collision)
XML_BOX_ONLY = f"""<mujoco><worldbody>
  <geom name="b" {_BOX} contype="0" conaffinity="0" {_GEOM}/>
</worldbody></mujoco>"""
# segment-capsule: the capsule alone, likewise
XML_CAPSULE_ONLY = f"""<mujoco><worldbody>
  <geom name="b" {_CAPSULE} contype="0" conaffinity="0" {_GEOM}/>
</worldbody></mujoco>"""


# the fixed models by scene name (also the MJCF of the hello's reproductions)
MODELS = {"sphere-sphere": XML_SPHERE_SPHERE, "plane-sphere": XML_PLANE_SPHERE, "flex-sphere": XML_FLEX_SPHERE,
          "plane-only": XML_PLANE_ONLY, "box-box": XML_BOX_BOX, "sphere-box": XML_SPHERE_BOX,
          "plane-box": XML_PLANE_BOX, "sphere-capsule": XML_SPHERE_CAPSULE, "capsule-capsule": XML_CAPSULE_CAPSULE,
          "plane-capsule": XML_PLANE_CAPSULE, "box-only": XML_BOX_ONLY, "capsule-only": XML_CAPSULE_ONLY, "capsule-box": XML_CAPSULE_BOX,
          "flex-box": XML_FLEX_BOX, "flex-capsule": XML_FLEX_CAPSULE}


class Scene:
    def __init__(self, xml):
        self.m = mujoco.MjModel.from_xml_string(xml)
        self.d = mujoco.MjData(self.m)
        # Geom positions are written into model.geom_pos; MuJoCo skips geom_pos for a
        # geom compiled as sharing its body's frame (geom_sameframe), so turn that off.
        self.m.geom_sameframe[:] = int(mujoco.mjtSameFrame.mjSAMEFRAME_NONE)
        self.gid = {mujoco.mj_id2name(self.m, mujoco.mjtObj.mjOBJ_GEOM, i): i for i in range(self.m.ngeom)}


_scenes = {}


def scene(key):
    if key not in _scenes:
        _scenes[key] = Scene(MODELS[key])
    return _scenes[key]


def set_sphere(sc, name, s):
    """Places a sphere geom: position, radius, and MuJoCo's bounding data for a sphere
    (geom_rbound = r and geom_aabb = [0,0,0, r,r,r], as the compiler sets them)."""
    g = sc.gid[name]
    r = s["radius"]
    sc.m.geom_pos[g] = s["center"]
    sc.m.geom_size[g] = [r, 0.0, 0.0]
    sc.m.geom_rbound[g] = r
    sc.m.geom_aabb[g] = [0.0, 0.0, 0.0, r, r, r]


def set_box(sc, name, box):
    """Places a box geom from an aabb: geom_pos = the centre, geom_size = the half
    extents (MuJoCo's box: size = half-sizes), identity orientation (written: the model is
    shared with box-box, whose boxes are rotated); and the bounding
    data MuJoCo's compiler gives a box (user_objects.cc, mjCGeom::GetRBound:
    geom_rbound = sqrt(hx*hx + hy*hy + hz*hz); geom_aabb = [0,0,0, hx,hy,hz]).
    Input conversion: centre = min/2 + max/2, half = max/2 - min/2 (never overflows;
    each rounded once, so a box is represented to within rounding of its corners).
    MuJoCo's compiler refuses a box with a half-size <= 0 (checksize: "size %d must be
    positive in geom"), so a zero extent is `unsupported` with that reason."""
    g = sc.gid[name]
    lo = [float(x) for x in box["min"]]
    hi = [float(x) for x in box["max"]]
    c = [0.5 * lo[i] + 0.5 * hi[i] for i in range(3)]
    h = [0.5 * hi[i] - 0.5 * lo[i] for i in range(3)]
    for i in range(3):
        if not h[i] > 0:
            raise Unsupported(f"MuJoCo cannot represent a box with a zero extent (axis {i}: half-size {h[i]!r}): "
                              f"its compiler refuses it ('size {i} must be positive in geom', checksize in user_objects.cc)")
    sc.m.geom_pos[g] = c
    sc.m.geom_quat[g] = [1.0, 0.0, 0.0, 0.0]  # identity: the model is shared with rotated boxes (set_obox)
    sc.m.geom_size[g] = h
    sc.m.geom_rbound[g] = math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2])
    sc.m.geom_aabb[g] = [0.0, 0.0, 0.0, h[0], h[1], h[2]]


def set_obox(sc, name, box):
    """Places a box geom from a `box` shape: geom_pos = the centre, geom_size = the half
    extents (MuJoCo's box: size = half-sizes), geom_quat = the case's quaternion [w, x, y,
    z] (MuJoCo's order) divided by its length (math.hypot: MuJoCo composes geom_quat
    assuming a unit quaternion); and the bounding data of set_box. A zero half-extent
    (a flat box) is `unsupported`: MuJoCo's compiler refuses a box size <= 0."""
    g = sc.gid[name]
    h = [float(x) for x in box["half_extents"]]
    for i in range(3):
        if not h[i] > 0:
            raise Unsupported(f"MuJoCo cannot represent a box with a zero extent (axis {i}: half-size {h[i]!r}): "
                              f"its compiler refuses it ('size {i} must be positive in geom', checksize in user_objects.cc)")
    q = [float(x) for x in box.get("rotation", [1.0, 0.0, 0.0, 0.0])]
    lq = math.hypot(*q)
    sc.m.geom_pos[g] = box["center"]
    sc.m.geom_quat[g] = [x / lq for x in q]
    sc.m.geom_size[g] = h
    sc.m.geom_rbound[g] = math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2])
    sc.m.geom_aabb[g] = [0.0, 0.0, 0.0, h[0], h[1], h[2]]


def set_capsule(sc, name, c):
    """THE CAPSULE PLACEMENT (the only one). MuJoCo's capsule geom is the segment from
    (0, 0, -size[1]) to (0, 0, size[1]) of the geom's frame, swept by size[0]. The case's
    capsule: geom_pos = start/2 + end/2; size = [r, hl] with hl = |end/2 - start/2|
    (math.hypot of the halves: never overflows); geom_quat = MuJoCo's own
    mju_quatZ2Vec of the unit axis (end/2 - start/2)/hl, as the compiler's `fromto` does;
    geom_rbound = r + hl and geom_aabb = [0,0,0, r,r,r+hl], as the compiler sets them. A
    zero-length axis is `unsupported`: the compiler refuses it ('size 1 must be positive
    in geom'; with fromto, 'fromto points too close in geom')."""
    g = sc.gid[name]
    st, en = [float(x) for x in c["start"]], [float(x) for x in c["end"]]
    half = [0.5 * en[i] - 0.5 * st[i] for i in range(3)]
    hl = math.hypot(*half)
    if not hl > 0:
        raise Unsupported("MuJoCo cannot represent a capsule with a zero-length axis: its compiler refuses it "
                          "('size 1 must be positive in geom'; 'fromto points too close in geom')")
    r = float(c["radius"])
    q = np.zeros(4)
    mujoco.mju_quatZ2Vec(q, np.array([x / hl for x in half]))
    sc.m.geom_pos[g] = [0.5 * st[i] + 0.5 * en[i] for i in range(3)]
    sc.m.geom_quat[g] = q
    sc.m.geom_size[g] = [r, hl, 0.0]
    sc.m.geom_rbound[g] = r + hl
    sc.m.geom_aabb[g] = [0.0, 0.0, 0.0, r, r, r + hl]


def set_plane(sc, name, p):
    """A plane geom: its z axis is the outward normal (MuJoCo's convention), its
    position a point of the plane. The normal is made unit here (math.hypot: no
    overflow or underflow at any finite length) and given to MuJoCo's own
    mju_quatZ2Vec, which takes a direction (a raw normal shorter than mjMINVAL or
    whose square overflows would be read as no direction); the point is
    u * (d/|n|). These are the only input conversions done here."""
    g = sc.gid[name]
    n = [float(x) for x in p["normal"]]
    ln = math.hypot(*n)
    u = [x / ln for x in n]
    s = p["offset"] / ln
    q = np.zeros(4)
    mujoco.mju_quatZ2Vec(q, np.array(u))
    sc.m.geom_pos[g] = [u[0] * s, u[1] * s, u[2] * s]
    sc.m.geom_quat[g] = q


def collide(sc):
    """MuJoCo's collision pipeline: kinematics (and flex vertex positions) untimed,
    then mj_collision, timed. Returns the contacts."""
    mujoco.mj_kinematics(sc.m, sc.d)
    if sc.m.nflex:
        mujoco.mj_flex(sc.m, sc.d)
    timed(mujoco.mj_collision, sc.m, sc.d)
    return [sc.d.contact[i] for i in range(sc.d.ncon)]


# ================================================================ THE CONVENTION TRANSLATION
# The only place where MuJoCo's conventions become the format's (README, "Conventions").
# MuJoCo contact (engine_collision_primitive.c, engine_collision_driver.c):
#   frame[0:3] = unit normal pointing from geom1 toward geom2 (contact.geom[0] -> geom[1];
#                for a flex, geom[1] = -1 and flex[1] = the flex);
#   dist       = signed distance, negative in penetration (depth = -dist);
#   pos        = the midpoint between the two surfaces: geom1's surface point is
#                pos - n*dist/2, geom2's is pos + n*dist/2.
# The format: normal from b toward a, point on b's surface, depth >= 0.
# The same for every pair, the four polytope pairs included: box-box (mjc_BoxBox) and
# capsule-box (mjc_CapsuleBox, geom1 the capsule: lower type), read by con.geom; box- and
# capsule-triangle through the flex (mj_collideGeomElem: geom[0] = the geom = a, flex[1] =
# the flex = b, normal from the geom toward the element; mjraw_BoxTriangle's contacts put
# pos = vertex - n*dist/2 or, for a box corner, mjraw_SphereTriangle's midpoint;
# mjraw_CapsuleTriangle's the midpoint between the surfaces): b is geom2 there. Checked on
# the campaign's cases where MuJoCo's depth is right: the translated point lies on the
# referee's region in every one (box-box 274, capsule-box 47, box-triangle 30,
# capsule-triangle 54).
def translate_contact(con, b_is_geom1):
    n = [float(x) for x in con.frame[:3]]
    dist = float(con.dist)
    pos = [float(x) for x in con.pos]
    h = dist / 2.0
    if b_is_geom1:   # b = geom1: its normal toward geom2 = a; its surface point pos - n*dist/2
        normal = n
        point = [pos[i] - n[i] * h for i in range(3)]
    else:            # b = geom2: normal from b toward a is -n; b's surface point pos + n*dist/2
        normal = [-x for x in n]
        point = [pos[i] + n[i] * h for i in range(3)]
    return {"point": point, "normal": normal, "depth": -dist}


# MuJoCo rays (engine_ray.c): mj_ray / mj_rayFlex cast pnt + x*vec, x >= 0, and return
# the smallest x (in units of |vec|) or -1; `normal` is the surface normal at the hit
# (a plane's z axis, a triangle's (v0-v2)x(v1-v2) normalized = the format's face normal).
# A segment is the ray with pnt = start, vec = end - start, cut at x <= 1; its hit point
# is MuJoCo's own pnt + x*vec.
def translate_hit(x, start, vec, normal):
    if x < 0 or x > 1:
        return {"hit": None}
    return {"hit": {"t": x, "point": [start[i] + x * vec[i] for i in range(3)],
                    "normal": [float(v) for v in normal]}}
# ================================================================ end of the translation


def one_contact(cons):
    if not cons:
        return None
    if len(cons) > 1:
        raise RuntimeError(f"MuJoCo returned {len(cons)} contacts for one pair")
    return cons[0]


def contact_sphere_shape(sphere_a, b, reversed_pair):
    """Contact of the sphere (in the free body) against b (in the world). When
    reversed_pair, the case is (b, sphere): the roles of a and b are the case's."""
    kind = next(iter(b))
    if kind == "sphere":
        sc = scene("sphere-sphere")
        set_sphere(sc, "a", sphere_a)
        set_sphere(sc, "b", b["sphere"])
        world = sc.gid["b"]
    elif kind == "plane":
        sc = scene("plane-sphere")
        set_sphere(sc, "a", sphere_a)
        set_plane(sc, "b", b["plane"])
        world = sc.gid["b"]
    else:  # triangle: the vertices of the one flex element (f64, mjData.flexvert_xpos)
        sc = scene("flex-sphere")
        set_sphere(sc, "a", sphere_a)
        sc.m.flex_vert[:] = b["triangle"]["vertices"]
        world = None
    con = one_contact(collide(sc))
    if con is None:
        return {"contact": None}
    if world is None:
        world_is_geom1 = False  # geom-flex contacts: geom[0] = the geom, flex[1] = the flex
        assert con.flex[1] == 0 and con.geom[1] == -1
    else:
        world_is_geom1 = int(con.geom[0]) == world
    # the world shape is the case's b, unless the pair is reversed (then b is the sphere)
    b_is_geom1 = world_is_geom1 if not reversed_pair else not world_is_geom1
    return {"contact": translate_contact(con, b_is_geom1)}


def deepest(cons):
    """MuJoCo's deepest contact (the least dist; on a tie the first in its order). A box on
    a plane gets up to 4 contacts (its corners below the plane, or the clipped face),
    parallel capsules 2: every one is a point of the contact region, the deepest taken."""
    return min(cons, key=lambda c: float(c.dist)) if cons else None


SETTERS = {"sphere": set_sphere, "box": set_obox, "capsule": set_capsule, "plane": set_plane}
SCENE_OF = {("sphere", "box"): "sphere-box", ("box", "plane"): "plane-box", ("sphere", "capsule"): "sphere-capsule",
            ("capsule", "capsule"): "capsule-capsule", ("capsule", "plane"): "plane-capsule",
            ("box", "box"): "box-box", ("capsule", "box"): "capsule-box"}
FLEX_SCENE_OF = {"box": "flex-box", "capsule": "flex-capsule"}


def contact_shapes(case):
    """The box and capsule pairs: a is the model's geom "a" (in a free body), b its geom "b"
    (in the world body); mj_kinematics, then mj_collision (timed): mjc_SphereBox /
    mjc_PlaneBox / mjc_SphereCapsule / mjc_CapsuleCapsule / mjc_PlaneCapsule, whichever
    MuJoCo's collision table holds (geom1 is the geom of the lower type: plane < sphere <
    capsule < box). The deepest contact, translated."""
    (ka, sa), = case["a"].items()
    (kb, sb), = case["b"].items()
    sc = scene(SCENE_OF[(ka, kb)])
    SETTERS[ka](sc, "a", sa)
    SETTERS[kb](sc, "b", sb)
    con = deepest(collide(sc))
    if con is None:
        return {"contact": None}
    return {"contact": translate_contact(con, int(con.geom[0]) == sc.gid["b"])}


def contact_shape_triangle(case):
    """box-triangle and capsule-triangle: a is the geom "a" (in a free body), the triangle b
    the one element of the flex (vertices in flex_vert, f64, as for sphere-triangle);
    mj_kinematics and mj_flex, then mj_collision (timed) -> mj_collideGeomElem ->
    mjraw_BoxTriangle / mjraw_CapsuleTriangle (MuJoCo's own routines for a box or a
    capsule against a 2-D flex element; see README, "boxes and capsules", for what they
    test). Geom-flex contacts put the geom first (geom[0] = a, flex[1] = the flex): b is
    geom2. The deepest contact, translated."""
    (ka, sa), = case["a"].items()
    sc = scene(FLEX_SCENE_OF[ka])
    SETTERS[ka](sc, "a", sa)
    sc.m.flex_vert[:] = case["b"]["triangle"]["vertices"]
    con = deepest(collide(sc))
    if con is None:
        return {"contact": None}
    assert con.flex[1] == 0 and con.geom[1] == -1 and con.geom[0] == sc.gid["a"]
    return {"contact": translate_contact(con, False)}


def contact_sphere_mesh(case):
    """Sphere a (in a free body) against mesh b (a mesh geom of the world body), both
    collidable (contype = conaffinity = 1, MuJoCo's default), margin 0, gap 0; a model
    compiled per case (not timed), then mj_collision (timed).

    CONVENTION (README): MuJoCo collides a mesh geom as the CONVEX HULL of its vertices
    (the compiler builds it with qhull; the narrow phase is its convex-convex routine on
    the hull, to its ccd tolerance), a solid. The format's mesh is a soup of two-sided
    faces. So:
      - a non-convex mesh: MuJoCo's contact is with the hull, not with the nearest face;
      - a vertex no face uses still spans the hull;
      - a centre inside the hull: MuJoCo pushes the sphere out of the solid (depth
        r + distance to the hull's surface, normal outward), where the format's face
        contact is r - distance with the normal from the face toward the centre;
      - a mesh with fewer than 4 vertices, or all coplanar, has no hull: the compiler
        refuses it ("at least 4 vertices required" / "has coplanar vertices, cannot
        compute convex hull") -> `unsupported`, with MuJoCo's message; any other
        compiler refusal is shown as the engine's error.
    Vertices are stored as f32 (mjModel.mesh_vert), re-expressed in the mesh's inertial
    frame (the geom's pos/quat carry it back): the hello gives this pair precision 24."""
    sph, mesh = case["a"]["sphere"], case["b"]["mesh"]
    verts, faces = mesh["vertices"], mesh["triangles"]
    if len(verts) < 4:
        # user_mesh.cc, CheckInitialMesh: "at least 4 vertices required"
        raise Unsupported("MuJoCo refuses a mesh with fewer than 4 vertices (compiler: 'at least 4 vertices required')")
    c = sph["center"]
    xml = (f'<mujoco><asset><mesh name="m" inertia="{MESH_INERTIA}" vertex="'
           + " ".join(fmt(x) for v in verts for x in v) + '" face="'
           + " ".join(str(int(i)) for f in faces for i in f) + '"/></asset><worldbody>'
           f'<geom name="b" type="mesh" mesh="m" contype="1" conaffinity="1" {_GEOM}/>'
           f'<body name="a" pos="{fmt(c[0])} {fmt(c[1])} {fmt(c[2])}"><freejoint/>'
           f'<geom name="a" type="sphere" size="{fmt(sph["radius"])}" contype="1" conaffinity="1" {_GEOM}/></body>'
           '</worldbody></mujoco>')
    try:
        sc = Scene(xml)
    except ValueError as exc:
        if "coplanar" in str(exc):  # the compiler has no convex hull for a flat mesh
            raise Unsupported("MuJoCo collides a mesh as its convex hull and refuses a flat one: "
                              + " ".join(str(exc).split()))
        raise
    con = one_contact(collide(sc))
    if con is None:
        return {"contact": None}
    b_is_geom1 = int(con.geom[0]) == sc.gid["b"]
    return {"contact": translate_contact(con, b_is_geom1)}


def overlap_aabb(case):
    """aabb-aabb overlap through MuJoCo's box-box collision: b a box geom of the world
    body, a a box geom of a free body (identity orientation), margin 0, gap 0;
    mj_kinematics, then mj_collision (timed) -> bounding-sphere filter (geom_rbound) ->
    mjc_BoxBox. THE RULE: overlap = at least one contact with dist <= 0. Touching boxes
    get contacts with dist = 0 (face, edge, or corner contact) when they pass the
    bounding-sphere filter; mjc_BoxBox's separation tests carry a slack (septol =
    1e-13 x the summed half-sizes), and its edge-edge path can return a contact with
    0 < dist <= septol: such a contact is not an overlap."""
    sc = scene("box-box")
    set_box(sc, "a", case["a"]["aabb"])
    set_box(sc, "b", case["b"]["aabb"])
    cons = collide(sc)
    return {"overlap": any(float(c.dist) <= 0.0 for c in cons)}


def overlap_box(case):
    """box-box and box-aabb overlap: as aabb-aabb (the same model, the same rule: at least
    one contact with dist <= 0), a box placed by set_obox (its rotation), an AABB by set_box."""
    sc = scene("box-box")
    set_obox(sc, "a", case["a"]["box"])
    (kb, sb), = case["b"].items()
    (set_obox if kb == "box" else set_box)(sc, "b", sb)
    cons = collide(sc)
    return {"overlap": any(float(c.dist) <= 0.0 for c in cons)}


def ray_guard(vec):
    """mj_ray calls mjERROR("vector length is too small") when mju_norm3(vec) < mjMINVAL
    (engine_ray.c, mj_ray), and in the Python package mjERROR ends the process (exit 1)
    instead of raising. The same test, with MuJoCo's own mju_norm3 and mjMINVAL, is made
    here so that the case becomes an error and the session survives."""
    if mujoco.mju_norm3(vec) < mujoco.mjMINVAL:
        raise RuntimeError("MuJoCo's mj_ray aborts the process on this ray (mjERROR 'vector length is "
                           "too small': |end - start| < mjMINVAL = 1e-15); not called")


def ray_on(sc, seg):
    """mj_ray of the segment on the scene's model (pnt = start, vec = end - start, geomgroup
    NULL, flg_static 1, bodyexclude -1), translated."""
    mujoco.mj_kinematics(sc.m, sc.d)
    start = np.array(seg["start"])
    vec = np.array(seg["end"]) - start
    ray_guard(vec)
    normal = np.zeros(3)
    gid = np.zeros(1, np.int32)
    x = timed(mujoco.mj_ray, sc.m, sc.d, start, vec, None, 1, -1, gid, normal)
    return translate_hit(float(x), seg["start"], vec.tolist(), normal)


def intersect_plane(case):
    seg, p = case["a"]["segment"], case["b"]["plane"]
    sc = scene("plane-only")
    set_plane(sc, "b", p)
    return ray_on(sc, seg)


def intersect_box(case):
    """segment-box: mj_ray on the box alone (set_obox), as segment-plane: MuJoCo's ray_box."""
    seg, bx = case["a"]["segment"], case["b"]["box"]
    sc = scene("box-only")
    set_obox(sc, "b", bx)
    return ray_on(sc, seg)


def intersect_capsule(case):
    """segment-capsule: mj_ray on the capsule alone (set_capsule), as segment-box: MuJoCo's ray_capsule."""
    seg, cap = case["a"]["segment"], case["b"]["capsule"]
    sc = scene("capsule-only")
    set_capsule(sc, "b", cap)
    return ray_on(sc, seg)


def intersect_triangle(case):
    seg, tri = case["a"]["segment"], case["b"]["triangle"]
    sc = scene("flex-sphere")  # the same one-triangle flex
    sc.m.flex_vert[:] = tri["vertices"]
    mujoco.mj_kinematics(sc.m, sc.d)
    mujoco.mj_flex(sc.m, sc.d)
    start = np.array(seg["start"])
    vec = np.array(seg["end"]) - start
    normal = np.zeros(3)
    vid = np.zeros(1, np.int32)
    # flex_layer 0; faces only (flg_vert, flg_edge, flg_skin off: with radius 0 they are
    # zero-radius spheres/capsules); flex id 0
    x = timed(mujoco.mj_rayFlex, sc.m, sc.d, 0, False, False, True, False, 0, start, vec, vid, normal)
    return translate_hit(float(x), seg["start"], vec.tolist(), normal)


def fmt(x):
    return repr(float(x))


def intersect_mesh(case):
    seg, mesh = case["a"]["segment"], case["b"]["mesh"]
    verts, faces = mesh["vertices"], mesh["triangles"]
    if len(verts) < 4:
        # MuJoCo's compiler refuses any mesh of fewer than 4 vertices (user_mesh.cc,
        # CheckInitialMesh: "at least 4 vertices required")
        raise Unsupported("MuJoCo refuses a mesh with fewer than 4 vertices (compiler: 'at least 4 vertices required')")
    xml = (f'<mujoco><asset><mesh name="m" inertia="{MESH_INERTIA}" vertex="'
           + " ".join(fmt(c) for v in verts for c in v) + '" face="'
           + " ".join(str(int(i)) for f in faces for i in f) + '"/></asset><worldbody>'
           f'<geom name="b" type="mesh" mesh="m" contype="0" conaffinity="0" {_GEOM}/>'
           '</worldbody></mujoco>')
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    mujoco.mj_kinematics(m, d)
    start = np.array(seg["start"])
    vec = np.array(seg["end"]) - start
    ray_guard(vec)
    normal = np.zeros(3)
    gid = np.zeros(1, np.int32)
    x = timed(mujoco.mj_ray, m, d, start, vec, None, 1, -1, gid, normal)
    return translate_hit(float(x), seg["start"], vec.tolist(), normal)


HANDLERS = {
    ("contact", "sphere", "sphere"): lambda c: contact_sphere_shape(c["a"]["sphere"], c["b"], False),
    ("contact", "sphere", "plane"): lambda c: contact_sphere_shape(c["a"]["sphere"], c["b"], False),
    ("contact", "plane", "sphere"): lambda c: contact_sphere_shape(c["b"]["sphere"], c["a"], True),
    ("contact", "sphere", "triangle"): lambda c: contact_sphere_shape(c["a"]["sphere"], c["b"], False),
    ("contact", "triangle", "sphere"): lambda c: contact_sphere_shape(c["b"]["sphere"], c["a"], True),
    ("contact", "sphere", "mesh"): contact_sphere_mesh,
    ("intersect", "segment", "plane"): intersect_plane,
    ("intersect", "segment", "triangle"): intersect_triangle,
    ("intersect", "segment", "mesh"): intersect_mesh,
    ("overlap", "aabb", "aabb"): overlap_aabb,
    ("contact", "sphere", "box"): contact_shapes,
    ("contact", "box", "plane"): contact_shapes,
    ("contact", "sphere", "capsule"): contact_shapes,
    ("contact", "capsule", "capsule"): contact_shapes,
    ("contact", "capsule", "plane"): contact_shapes,
    ("contact", "box", "box"): contact_shapes,
    ("contact", "capsule", "box"): contact_shapes,
    ("contact", "box", "triangle"): contact_shape_triangle,
    ("contact", "capsule", "triangle"): contact_shape_triangle,
    ("intersect", "segment", "box"): intersect_box,
    ("intersect", "segment", "capsule"): intersect_capsule,
    ("overlap", "box", "box"): overlap_box,
    ("overlap", "box", "aabb"): overlap_box,
}

# ================================================================ WORLDS (dynamics)
# A `world` message (docs/PROTOCOL.md, "Worlds") becomes one MJCF model: each sphere a
# body with a free joint and one sphere geom of the given mass (solid ball: MuJoCo's
# compiler computes the inertia 2/5 m r^2 from the geom), each plane and box a geom of
# the world body (static). Every geom: condim 1 (frictionless normal contact only),
# margin 0, gap 0, and the contact parameters of `contact_params` below. The model is
# compiled per world; stepping is mj_step with the integrator below.
WORLD_INTEGRATOR = "Euler"  # MuJoCo's default: semi-implicit (symplectic) Euler,
#                             v += a*dt then q += v_new*dt; nothing for implicitfast to
#                             add here (no joint damping, no actuators), and RK4 would
#                             re-evaluate the contacts inside one step.
WORLD_IMPEDANCE = 0.9999  # solimp d0 = d_width = mjMAXIMP: a constant impedance d


# ---------------------------------------------------------------- THE RESTITUTION MAPPING
# The only place where a coefficient of restitution e becomes MuJoCo's contact
# parameters (README, "Worlds (dynamics)").
#
# MuJoCo's soft contact (engine_core_constraint.c, mj_makeImpedance and the efc_aref
# line): the constraint asks for the reference acceleration
#     aref = -B*v - K*imp*r        (r = contact distance, < 0 in penetration; v = its rate)
# and the solver gives the normal acceleration a = (1-imp)*a0 + imp*aref while the
# contact pushes (force >= 0; a0 = the unconstrained acceleration). solref in the
# DIRECT form (-k, -b) gives K = k/d_width^2, B = b/d_width; with a constant impedance
# (solimp[0] = solimp[1] = d) this is exactly
#     a = -b*v - k*r  (+ (1-d)*a0, 1e-4 of gravity with d = 0.9999)
# i.e. a linear spring-damper per unit of effective mass: x'' + 2*zeta*w*x' + w^2*x = 0
# with k = w^2, b = 2*zeta*w. Its restitution (half a damped period, force not
# clamped) is e = exp(-zeta*pi/sqrt(1-zeta^2)), so
#     zeta = -ln(e) / sqrt(pi^2 + ln(e)^2)     (zeta = 1 for e = 0, zeta = 0 for e = 1).
# The stiffness is the one MuJoCo's "timeconst" form gives for a critically damped
# contact at its smallest safe time constant: timeconst = 2*dt (MuJoCo clamps a
# positive timeconst to >= 2*timestep, "refsafe"), w = 1/timeconst. For e = 0 this is
# exactly solref = (2*dt, 1).
# Why the direct form: the (timeconst, dampratio) form sets K = 1/(timeconst*zeta)^2,
# so the stiffness grows without bound as zeta -> 0 (w*dt = 0.5/zeta: explicit
# integration unstable for zeta < 0.25, i.e. e > 0.44 at timeconst = 2*dt), and
# dampratio 0 is refused (a positive timeconst with a non-positive dampratio is a
# "mixed solref format" that MuJoCo replaces with its default). (-k, 0) is accepted.
def contact_params(e, dt):
    """(solref, solimp, note) for restitution e at time step dt."""
    e = min(1.0, max(0.0, float(e)))
    if e <= 0.0:
        zeta = 1.0
    else:
        le = math.log(e)
        zeta = -le / math.sqrt(math.pi ** 2 + le * le)
    timeconst = 2.0 * dt
    w = 1.0 / timeconst
    k, b = w * w, 2.0 * zeta * w
    solref = [-k, -b]
    d = WORLD_IMPEDANCE
    solimp = [d, d, 0.001, 0.5, 2.0]  # width/midpoint/power unused when d0 = d_width
    note = (f"direct solref = (-k, -b) = ({-k!r}, {-b!r}): k = w^2, b = 2*zeta*w, w = 1/timeconst, "
            f"timeconst = 2*dt = {timeconst!r}, zeta = -ln e/sqrt(pi^2+ln^2 e) = {zeta!r} (e = {e!r})")
    return solref, solimp, note
# ---------------------------------------------------------------- end of the mapping


def _v(xs):
    return " ".join(repr(float(x)) for x in xs)


def world_model(msg):
    """The MJCF of a world message, and the settings it applies."""
    dt = float(msg["dt"])
    bodies = msg["bodies"]
    es = sorted({float(b.get("restitution", 0.0)) for b in bodies})
    if len(es) > 1:
        raise ValueError(f"bodies have different restitutions {es}; one per world is expected")
    e = es[0] if es else 0.0
    solref, solimp, note = contact_params(e, dt)
    geom = (f'condim="1" margin="{MARGIN!r}" gap="{GAP!r}" solref="{_v(solref)}" '
            f'solimp="{_v(solimp)}" friction="0 0 0"')
    parts, spheres = [], []
    for i, body in enumerate(bodies):
        kind = next(k for k in ("sphere", "plane", "box") if k in body)
        if kind == "sphere":
            s = body["sphere"]
            parts.append(f'<body name="s{i}" pos="{_v(s["center"])}"><freejoint name="j{i}"/>'
                         f'<geom type="sphere" size="{float(s["radius"])!r}" mass="{float(body["mass"])!r}" {geom}/></body>')
            spheres.append((i, body))
        elif kind == "plane":
            p = body["plane"]
            n = np.array([float(x) for x in p["normal"]])
            ln = float(np.linalg.norm(n))
            q = np.zeros(4)
            mujoco.mju_quatZ2Vec(q, n)
            pos = n / ln * (float(p["offset"]) / ln)
            parts.append(f'<geom type="plane" size="0 0 1" pos="{_v(pos)}" quat="{_v(q)}" {geom}/>')
        else:
            bx = body["box"]
            parts.append(f'<geom type="box" size="{_v(bx["half_extents"])}" pos="{_v(bx["center"])}" {geom}/>')
    xml = (f'<mujoco><option timestep="{dt!r}" gravity="{_v(msg.get("gravity", [0, 0, 0]))}" '
           f'integrator="{WORLD_INTEGRATOR}" density="0" viscosity="0"/>'
           '<worldbody>' + "".join(parts) + '</worldbody></mujoco>')
    settings = {
        "integrator": f"{WORLD_INTEGRATOR} (MuJoCo's semi-implicit Euler), mj_step",
        "timestep": repr(dt),
        "solref": f"{_v(solref)} (direct form: -stiffness, -damping)",
        "solimp": _v(solimp),
        "restitution mapping": note,
        "condim": "1 (frictionless), friction 0",
        "margin / gap": f"{MARGIN!r} / {GAP!r}",
        "ccd": "not available (ignored): MuJoCo has no continuous collision for geoms "
               "(nativeccd/multiccd are its convex-convex narrow phase, not sweeping)"
               + (f" (asked: {msg.get('ccd')})" if "ccd" in msg else ""),
        "solver": "Newton (default), iterations 100, tolerance 1e-8, cone pyramidal (irrelevant with condim 1)",
        "damping / sleep": "no joint damping, density 0, viscosity 0; sleep off (default)",
        "plane": 'geom type="plane" size="0 0 1" (infinite half-space), quat = mju_quatZ2Vec(normal)',
        "box": "fixed box geom in the world body",
        "model": "MJCF compiled per world (not timed); only the mj_step calls are timed",
    }
    return xml, spheres, settings


def step_world(msg):
    xml, spheres, settings = world_model(msg)
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    adr = []
    for i, body in spheres:
        j = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, f"j{i}")
        qa, va = int(m.jnt_qposadr[j]), int(m.jnt_dofadr[j])
        d.qvel[va:va + 3] = [float(x) for x in body.get("velocity", [0, 0, 0])]  # world frame
        adr.append((qa, va))
    steps = int(msg["steps"])
    positions = [[d.qpos[qa:qa + 3].tolist() for qa, _ in adr]]
    for _ in range(steps):
        timed(mujoco.mj_step, m, d)  # only the engine's step is charged
        positions.append([d.qpos[qa:qa + 3].tolist() for qa, _ in adr])
    # MuJoCo does not raise on a diverging simulation: mj_checkPos/Vel/Acc warn and RESET
    # mjData to the model's initial state (autoreset, on by default). Such a trajectory is
    # not the engine's physics; say so as the world's error instead of returning it.
    bad = {int(mujoco.mjtWarning.mjWARN_BADQPOS): "BADQPOS", int(mujoco.mjtWarning.mjWARN_BADQVEL): "BADQVEL",
           int(mujoco.mjtWarning.mjWARN_BADQACC): "BADQACC"}
    hit = [f"{name} x{int(d.warning[w].number)} (last info: index {int(d.warning[w].lastinfo)})"
           for w, name in bad.items() if d.warning[w].number > 0]
    if hit:
        raise RuntimeError("MuJoCo found the simulation unstable and reset it: " + ", ".join(hit))
    other = [f"{mujoco.mjtWarning(w).name} x{int(d.warning[w].number)}" for w in range(int(mujoco.mjtWarning.mjNWARNING))
             if w not in bad and d.warning[w].number > 0]
    if other:
        settings["warnings"] = ", ".join(other)
    # a free joint's qvel: linear velocity in the world frame, then angular in the body frame
    velocities = [d.qvel[va:va + 3].tolist() for _, va in adr]
    return {"positions": positions, "velocities": velocities, "settings": settings}
# ================================================================ end of worlds


PROVENANCE = {
    "mujoco (package)": package_version("mujoco"),
    "mujoco (library)": mujoco.mj_versionString(),
    "mjtNum": "f64 (mesh vertices are stored as f32: mjModel.mesh_vert is float)",
    "geom margin": repr(MARGIN),
    "geom gap": repr(GAP),
    "flex margin / gap / radius": f"{MARGIN!r} / {GAP!r} / {FLEX_RADIUS!r}",
    "contact": "mj_kinematics (+ mj_flex) then mj_collision; default mjOption (no override, MULTICCD off)",
    "plane": 'geom type="plane" size="0 0 1" (size 0: infinite for rays), quat = mju_quatZ2Vec(normal)',
    "triangle": "a dim-2 flex of one element, vertices in the world body, radius 0 (sphere-triangle: mjraw_SphereTriangle; ray: mj_rayFlex faces only)",
    "mesh": f'mesh geom, inertia="{MESH_INERTIA}", contype=0 conaffinity=0 (no hull needed); ray: mj_ray(geomgroup=NULL, flg_static=1, bodyexclude=-1)',
    "sphere-mesh": f'model per case: mesh geom (inertia="{MESH_INERTIA}", contype=conaffinity=1: collided as its '
                   'CONVEX HULL) in the world body, sphere geom in a free body at the centre; margin 0, gap 0; '
                   'mj_collision (convex-convex narrow phase, default mjOption ccd settings)',
    "aabb-aabb": "two box geoms (size = half extents = max/2 - min/2, pos = centre = min/2 + max/2, identity "
                 "orientation; b in the world body, a in a free body), rbound/aabb as the compiler sets them, margin 0, "
                 "gap 0; mj_kinematics then mj_collision (bounding-sphere filter, mjc_BoxBox); overlap = any contact "
                 "with dist <= 0; a zero extent: unsupported (the compiler refuses size <= 0)",
    "box": "box geom: geom_pos = centre, geom_size = half extents, geom_quat = q/|q| ([w, x, y, z]), rbound/aabb "
           "as the compiler sets them; a zero half-extent: unsupported (the compiler refuses size <= 0)",
    "capsule": "capsule geom: geom_pos = start/2 + end/2, size = [r, |end/2 - start/2|], geom_quat = "
               "mju_quatZ2Vec(axis), rbound = r + half length; a zero-length axis: unsupported (the compiler refuses it)",
    "box and capsule contacts": "a in a free body, b in the world body; mj_collision; the contact with the least dist "
                                "(box-box: mjc_BoxBox; capsule-box: mjc_CapsuleBox)",
    "box-triangle, capsule-triangle": "a (box or capsule geom) in a free body, the triangle the one-element dim-2 flex "
                                      "(radius 0, margin 0, gap 0) -> mj_collideGeomElem -> mjraw_BoxTriangle / "
                                      "mjraw_CapsuleTriangle; the contact with the least dist",
    "segment-box": "mj_ray on a model holding only the box (contype 0, conaffinity 0)",
    "segment-capsule": "mj_ray on a model holding only the capsule (contype 0, conaffinity 0): ray_capsule",
    "stdout": "fd 1 redirected to stderr; the protocol uses a duplicate of the original fd 1",
}

# ================================================================ DISTANCE
# mj_geomDistance(m, d, geom1, geom2, distmax, fromto) (engine_support.c): the smallest
# signed distance of two geoms, through the geom pair's collision function called with
# margin = distmax (or, for mjc_Convex and mjc_BoxBox while nativeccd is on, MuJoCo's
# own GJK/EPA, mjc_ccd with dist_cutoff = distmax); fromto = the point on geom1 and the
# point on geom2. A distance of distmax or more is not answered (distmax comes back, fromto
# zero), so distmax is chosen per case above any distance its shapes can have (DISTMAX).
#
# The models: every distance case of a batch becomes two geoms "a<i>" and "b<i>" of the world
# body of ONE model (contype = conaffinity = 0: nothing collides; mj_geomDistance does not
# ask), compiled once per batch by MuJoCo's compiler, which places every geom itself: a sphere
# (size r, pos), a box (size = half extents, pos, quat = the case's [w, x, y, z], which the
# compiler normalizes), a capsule (fromto = start and end, size r), a plane (a plane geom,
# size "0 0 1": infinite, zaxis = the case's normal, pos = the point n (d/|n|)/|n|: MuJoCo's
# plane is the half-space z <= 0 of its frame) and a convex shape (a mesh asset of the case's
# points, which the compiler wraps in their convex hull with qhull, inertia "shell"). Mesh
# vertices are f32 (mjModel.mesh_vert), re-expressed in the mesh's inertial frame: the convex
# pairs are answered at precision 24. A shape the compiler refuses (a zero half-extent,
# equal capsule ends, a hull that is flat, a segment or under 4 points) is `unsupported`
# with its message.
#
# MuJoCo has no triangle geom (a triangle is a flex element, and mj_geomDistance takes geoms
# only; a mesh of 3 vertices is refused: "at least 4 vertices required"): the triangle
# pairs are not answered.
DISTANCE_PAIRS = [(a, b) for a, b in ALL_DISTANCE_PAIRS if "triangle" not in (a, b)]
DIST_INERTIA = "shell"  # the mesh's inertia: "shell" compiles thin hulls "convex" may refuse


def _f(xs):
    return " ".join(repr(float(x)) for x in xs)


def dist_geom_xml(name, shape):
    """The MJCF of one shape as a geom (and a mesh asset for a convex shape), or raises
    Unsupported for what MuJoCo's compiler refuses."""
    (kind, s), = shape.items()
    g = f'name="{name}" contype="0" conaffinity="0" {_GEOM}'
    if kind == "sphere":
        return "", f'<geom {g} type="sphere" size="{_f([s["radius"]])}" pos="{_f(s["center"])}"/>'
    if kind == "box":
        h = [float(x) for x in s["half_extents"]]
        if not all(x > 0 for x in h):
            raise Unsupported("MuJoCo cannot represent a box with a zero extent: its compiler refuses it "
                              "('size must be positive in geom', checksize in user_objects.cc)")
        q = s.get("rotation", [1.0, 0.0, 0.0, 0.0])
        return "", f'<geom {g} type="box" size="{_f(h)}" pos="{_f(s["center"])}" quat="{_f(q)}"/>'
    if kind == "capsule":
        if list(s["start"]) == list(s["end"]):
            raise Unsupported("MuJoCo cannot represent a capsule with a zero-length axis: its compiler refuses "
                              "it ('fromto points too close in geom')")
        return "", f'<geom {g} type="capsule" size="{_f([s["radius"]])}" fromto="{_f(list(s["start"]) + list(s["end"]))}"/>'
    if kind == "plane":
        n = [float(x) for x in s["normal"]]
        ln = math.hypot(*n)
        k = float(s["offset"]) / ln
        return "", f'<geom {g} type="plane" size="0 0 1" zaxis="{_f(n)}" pos="{_f([x / ln * k for x in n])}"/>'
    if kind == "convex":
        if maybe_flat(s["points"]):
            # MuJoCo's own word on it: the mesh alone, compiled
            refusal = mesh_refusal(s["points"])
            if refusal:
                raise Unsupported("MuJoCo collides a mesh as its convex hull and refuses this one: " + refusal)
        asset = f'<mesh name="m{name}" inertia="{DIST_INERTIA}" vertex="{_f(x for p in s["points"] for x in p)}"/>'
        return asset, f'<geom {g} type="mesh" mesh="m{name}"/>'
    raise Unsupported(f"no MuJoCo geom for {kind}")


def maybe_flat(points):
    """Whether MuJoCo's compiler might refuse a mesh of these points (fewer than 4, or
    nearly coplanar, collinear or coincident: the least singular value of the centred
    points under 1e-6 of the largest, or not finite; or all within 1e-9 of the first:
    its tests are against mjMINVAL = 1e-15, absolute, user_mesh.cc MakeGraph), all taken
    on the points rounded to f32 as MuJoCo stores them (far from the origin they collapse),
    so that it is compiled alone first (`mesh_refusal`) and a refusal stays that case's; a
    refusal this misses is caught when the batch compiles (`prepare_distance`)."""
    with np.errstate(all="ignore"):
        p = np.unique(np.asarray(points, dtype=np.float64).astype(np.float32), axis=0).astype(np.float64)
    if len(p) < 4:
        return True
    with np.errstate(all="ignore"):
        sv = np.linalg.svd(p - p.mean(axis=0), compute_uv=False)
        spread = np.abs(p - p[0]).max()
    return not (sv[-1] > 1e-6 * sv[0]) or not spread > 1e-9


def mesh_refusal(points):
    """MuJoCo's compiler's message refusing a mesh of these points, or None if it takes it."""
    if len(points) < 4:
        return "its compiler needs at least 4 vertices ('at least 4 vertices required')"
    try:
        mujoco.MjModel.from_xml_string(f'<mujoco><asset><mesh name="m" inertia="{DIST_INERTIA}" vertex="'
                                       f'{_f(x for p in points for x in p)}"/></asset><worldbody>'
                                       '<geom type="mesh" mesh="m"/></worldbody></mujoco>')
    except ValueError as exc:
        return " ".join(str(exc).split())
    return None


_dist_ready = {}  # id(case) -> ("ok", model, data, geom a, geom b, distmax) or ("unsupported", reason)


def prepare_distance(cases):
    """One model for a batch's distance cases (crashtest_engine.serve's `prepare`): each
    case's two geoms, compiled together; a case whose shape the compiler refuses is taken out
    (by the element its message names) and the rest compiled again."""
    _dist_ready.clear()
    parts = {}
    for i, c in enumerate(cases):
        try:
            if c.get("query") != "distance" or HANDLERS.get((c["query"], next(iter(c["a"])), next(iter(c["b"])))) is not distance:
                continue
            pa, pb = dist_geom_xml(f"a{i}", c["a"]), dist_geom_xml(f"b{i}", c["b"])
            parts[i] = (pa, pb)
        except Unsupported as why:
            _dist_ready[id(c)] = ("unsupported", str(why))
        except Exception:
            pass  # a malformed case: answered (with its error) one by one
    while parts:
        xml = ("<mujoco><asset>" + "".join(pa[0] + pb[0] for pa, pb in parts.values()) + "</asset><worldbody>"
               + "".join(pa[1] + pb[1] for pa, pb in parts.values()) + "</worldbody></mujoco>")
        try:
            m = mujoco.MjModel.from_xml_string(xml)
        except ValueError as exc:
            text = " ".join(str(exc).split())
            named = re.search(r"Element name '(m?)([ab])(\d+)'", text)
            i = int(named.group(3)) if named else None
            if i in parts:
                _dist_ready[id(cases[i])] = ("unsupported", "MuJoCo's compiler refuses this shape: " + text)
                del parts[i]
                continue
            # the message names no case (its XML reader refuses a number, say): each case's
            # model alone tells which it refuses
            before = len(parts)
            for i in list(parts):
                pa, pb = parts[i]
                try:
                    mujoco.MjModel.from_xml_string(f"<mujoco><asset>{pa[0]}{pb[0]}</asset><worldbody>{pa[1]}{pb[1]}"
                                                   "</worldbody></mujoco>")
                except ValueError as one:
                    _dist_ready[id(cases[i])] = ("unsupported", "MuJoCo refuses this case's model: "
                                                 + " ".join(str(one).split()))
                    del parts[i]
            if len(parts) == before:
                raise  # no case's own: every case answered one by one
            continue
        d = mujoco.MjData(m)
        mujoco.mj_kinematics(m, d)
        for i in parts:
            c = cases[i]
            _dist_ready[id(c)] = ("ok", m, d, m.geom(f"a{i}").id, m.geom(f"b{i}").id, distance_reach(c))
        return


# THE DISTANCE TRANSLATION (the only one). mj_geomDistance returns the signed distance
# (negative in penetration: the collision functions' contact dist, or mjc_ccd's -depth) and
# fromto = [point on geom1, point on geom2] (engine_support.c: for a flipped pair the sign
# puts the points back in the caller's order; mj_geomDistanceCCD copies status.x1 of geom1
# and x2 of geom2). geom1 = a, geom2 = b: point_a = fromto[0:3], point_b = fromto[3:6].
# MuJoCo gives no normal: it is (point_a - point_b)/|...| for d > 0, (point_b -
# point_a)/|...| for d < 0 (the format's EPA convention), the zero vector where the two
# points coincide or d = 0 (touching: the points are one point, and any difference
# between them is rounding; no direction is given). A distance of distmax or more is no
# answer.
def to_format_distance(dist, fromto, distmax):
    dist = float(dist)
    if not dist < distmax:
        raise RuntimeError(f"mj_geomDistance found no distance below distmax = {distmax!r} (answered {dist!r}, "
                           f"fromto {[float(x) for x in fromto]})")
    pa, pb = [float(x) for x in fromto[:3]], [float(x) for x in fromto[3:]]
    diff = [pa[i] - pb[i] for i in range(3)]
    length = math.hypot(*diff)
    sign = 1.0 if dist > 0 else -1.0
    n = [sign * x / length + 0.0 for x in diff] if length > 0 and dist != 0 else [0.0, 0.0, 0.0]
    return {"distance": dist, "point_a": pa, "point_b": pb, "normal": n}


def distance(case):
    entry = _dist_ready.pop(id(case), None)
    if entry is None:  # not prepared with a batch: a model of its own
        prepare_distance([case])
        entry = _dist_ready.pop(id(case))
    if entry[0] == "unsupported":
        raise Unsupported(entry[1])
    _, m, d, ga, gb, distmax = entry
    fromto = np.zeros(6)
    dist = timed(mujoco.mj_geomDistance, m, d, ga, gb, distmax, fromto)
    return to_format_distance(dist, fromto, distmax)


for _a, _b in DISTANCE_PAIRS:
    HANDLERS[("distance", _a, _b)] = distance
PROVENANCE.update({
    "distance": "mj_geomDistance(m, d, geom a, geom b, distmax, fromto) on one model per batch (every case's two "
                "geoms in the world body, contype 0, conaffinity 0, margin 0, gap 0), after mj_kinematics; "
                "default mjOption: nativeccd on (mjc_Convex and mjc_BoxBox pairs go to mjc_ccd), "
                f"ccd_tolerance {mujoco.MjOption().ccd_tolerance!r}, ccd_iterations {mujoco.MjOption().ccd_iterations}",
    "distance distmax": "per case, 8 M + 1 (at most DBL_MAX), M the largest magnitude of the case's coordinates, "
                        "radii, half-extents and plane offsets over |n|: above any distance of the two shapes",
    "distance shapes": "sphere: size r, pos; box: size = half extents, pos, quat = the case's [w, x, y, z] "
                       "(normalized by the compiler); capsule: fromto = start end, size r; plane: plane geom size "
                       "'0 0 1', zaxis = n, pos = n (d/|n|)/|n|; convex: mesh asset of the points (the compiler's "
                       f'qhull hull, inertia "{DIST_INERTIA}", f32 vertices)',
    "distance normal": "none from MuJoCo: (p_a - p_b)/|p_a - p_b| of fromto (d > 0), (p_b - p_a)/|...| (d < 0), "
                       "the zero vector where they coincide or d = 0",
    "distance triangle": "not answered: no triangle geom (mj_geomDistance takes geoms; a 3-vertex mesh is refused)",
})


def prepare(cases):
    prepare_distance(cases)


if __name__ == "__main__":
    # mjModel.mesh_vert is float: segment–mesh and sphere–mesh are answered on f32 vertices.
    convex_pairs = {("distance", a, b): 24 for a, b in DISTANCE_PAIRS if "convex" in (a, b)}
    sys.exit(serve("mujoco", package_version("mujoco"), 53, HANDLERS, PROVENANCE,
                   pair_precision={("intersect", "segment", "mesh"): 24, ("contact", "sphere", "mesh"): 24,
                                   **convex_pairs},
                   world=step_world, prepare=prepare,
                   reproductions=reproductions(HANDLERS, MODELS, _GEOM, MESH_INERTIA,
                                               (DIST_INERTIA, inspect.getsource(distance_reach)))))
