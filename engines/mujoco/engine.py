#!/usr/bin/env python3
"""mujoco: MuJoCo (the `mujoco` Python package) behind crashtest-engine/1.

Every answer is MuJoCo's own: contacts from `mj_collision` on an MjModel built from
MJCF, hits from `mj_ray` (plane, mesh geoms) and `mj_rayFlex` (a one-triangle flex).
The only arithmetic done here is (1) turning the case's shapes into MuJoCo's
representation (a plane's point and orientation, geom positions and sizes) and
(2) the convention translation in ONE place, `translate_contact` / `translate_hit`
below. See README.md.
"""
import math
import os
import sys

# --- protect the protocol: MuJoCo (C code) may print to fd 1 (warnings go through
# printf). Keep a private duplicate of fd 1 for the protocol, point fd 1 at stderr,
# and make sys.stdout write to the duplicate. Done before importing mujoco.
_proto_fd = os.dup(1)
os.dup2(2, 1)
sys.stdout = os.fdopen(_proto_fd, "w", buffering=1 << 16, encoding="utf-8", newline="\n")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from crashtest_engine import Unsupported, package_version, serve, timed  # noqa: E402

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


class Scene:
    def __init__(self, xml):
        self.m = mujoco.MjModel.from_xml_string(xml)
        self.d = mujoco.MjData(self.m)
        # Geom positions are written into model.geom_pos; MuJoCo skips geom_pos for a
        # geom compiled as sharing its body's frame (geom_sameframe), so turn that off.
        self.m.geom_sameframe[:] = int(mujoco.mjtSameFrame.mjSAMEFRAME_NONE)
        self.gid = {mujoco.mj_id2name(self.m, mujoco.mjtObj.mjOBJ_GEOM, i): i for i in range(self.m.ngeom)}


_scenes = {}


def scene(key, xml):
    if key not in _scenes:
        _scenes[key] = Scene(xml)
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


def set_plane(sc, name, p):
    """A plane geom: its z axis is the outward normal (MuJoCo's convention), its
    position a point of the plane. The quaternion is MuJoCo's own mju_quatZ2Vec(n);
    the point is n/|n| * (d/|n|) (the only input conversion done here)."""
    g = sc.gid[name]
    n = [float(x) for x in p["normal"]]
    ln = math.hypot(*n)
    u = [x / ln for x in n]
    s = p["offset"] / ln
    q = np.zeros(4)
    mujoco.mju_quatZ2Vec(q, np.array(n))
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
        sc = scene("sphere-sphere", XML_SPHERE_SPHERE)
        set_sphere(sc, "a", sphere_a)
        set_sphere(sc, "b", b["sphere"])
        world = sc.gid["b"]
    elif kind == "plane":
        sc = scene("plane-sphere", XML_PLANE_SPHERE)
        set_sphere(sc, "a", sphere_a)
        set_plane(sc, "b", b["plane"])
        world = sc.gid["b"]
    else:  # triangle: the vertices of the one flex element (f64, mjData.flexvert_xpos)
        sc = scene("flex-sphere", XML_FLEX_SPHERE)
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


def ray_guard(vec):
    """mj_ray calls mjERROR("vector length is too small") when mju_norm3(vec) < mjMINVAL
    (engine_ray.c, mj_ray), and in the Python package mjERROR ends the process (exit 1)
    instead of raising. The same test, with MuJoCo's own mju_norm3 and mjMINVAL, is made
    here so that the case becomes an error and the session survives."""
    if mujoco.mju_norm3(vec) < mujoco.mjMINVAL:
        raise RuntimeError("MuJoCo's mj_ray aborts the process on this ray (mjERROR 'vector length is "
                           "too small': |end - start| < mjMINVAL = 1e-15); not called")


def intersect_plane(case):
    seg, p = case["a"]["segment"], case["b"]["plane"]
    sc = scene("plane-only", XML_PLANE_ONLY)
    set_plane(sc, "b", p)
    mujoco.mj_kinematics(sc.m, sc.d)
    start = np.array(seg["start"])
    vec = np.array(seg["end"]) - start
    ray_guard(vec)
    normal = np.zeros(3)
    gid = np.zeros(1, np.int32)
    x = timed(mujoco.mj_ray, sc.m, sc.d, start, vec, None, 1, -1, gid, normal)
    return translate_hit(float(x), seg["start"], vec.tolist(), normal)


def intersect_triangle(case):
    seg, tri = case["a"]["segment"], case["b"]["triangle"]
    sc = scene("flex-sphere", XML_FLEX_SPHERE)  # the same one-triangle flex
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
    ("intersect", "segment", "plane"): intersect_plane,
    ("intersect", "segment", "triangle"): intersect_triangle,
    ("intersect", "segment", "mesh"): intersect_mesh,
}

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
    "stdout": "fd 1 redirected to stderr; the protocol uses a duplicate of the original fd 1",
}

if __name__ == "__main__":
    # mjModel.mesh_vert is float: segment–mesh is answered on f32 vertices.
    sys.exit(serve("mujoco", package_version("mujoco"), 53, HANDLERS, PROVENANCE,
                   pair_precision={("intersect", "segment", "mesh"): 24}))
