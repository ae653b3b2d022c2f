"""mujoco's reproductions: for every pair engine.py answers, a standalone program
that asks MuJoCo one case the way engine.py does (the same MJCF, the same model
fields written, the same calls) and prints MuJoCo's raw answer, before engine.py's
convention translation. engine.py passes `reproductions(HANDLERS, MODELS, _GEOM,
MESH_INERTIA)` to `serve`, which puts them in the hello; crashtest fills the placeholders
(`{{a.radius}}`, ...) with a finding's shrunk case (docs/PROTOCOL.md, hello,
`reproductions`). The MJCF of the fixed models comes from engine.py itself (MODELS),
so the scripts compile exactly the adapter's models.

Keep them in step with engine.py: a change to `Scene`, `set_sphere`, `set_plane`,
`set_box`, a per-case model or a call there is a change here.
"""
from crashtest_engine import pinned

HEAD = """\
# <pins>: crashtest `<query>` <pair>, asked as crashtest's mujoco adapter asks it
"""

# A fixed model, as engine.py's Scene compiles it (geom_pos is written below, so
# MuJoCo must not treat a geom as sharing its body's frame)
SCENE = '''\
m = mujoco.MjModel.from_xml_string("""<xml>""")
d = mujoco.MjData(m)
m.geom_sameframe[:] = int(mujoco.mjtSameFrame.mjSAMEFRAME_NONE)  # geom_pos is written below
'''

# set_sphere: position, radius, and the bounding data the compiler gives a sphere
SPHERE = """\
g, r = m.geom("<geom>").id, {{@.radius}}
m.geom_pos[g], m.geom_size[g], m.geom_rbound[g], m.geom_aabb[g] = {{@.center}}, [r, 0.0, 0.0], r, [0.0, 0.0, 0.0, r, r, r]
"""

# set_plane: the geom's z axis is the unit normal (mju_quatZ2Vec), its position a point
# of the plane
PLANE = """\
n = {{@.normal}}
ln = math.hypot(*n)
u, s = [x / ln for x in n], {{@.offset}} / ln
q = np.zeros(4)
mujoco.mju_quatZ2Vec(q, np.array(u))
g = m.geom("<geom>").id
m.geom_pos[g], m.geom_quat[g] = [u[0] * s, u[1] * s, u[2] * s], q
"""

# a model per case with the mesh (vertices written as repr(float), as engine.py does)
MESH_MODEL = """\
f = lambda xs: " ".join(repr(float(x)) for x in xs)
V, F = {{b.vertices}}, {{b.triangles}}
xml = ('<mujoco><asset><mesh name="m" inertia="<inertia>" vertex="' + f(x for v in V for x in v)
       + '" face="' + " ".join(str(int(i)) for t in F for i in t) + '"/></asset><worldbody>'
       '<geom name="b" type="mesh" mesh="m" contype="<ct>" conaffinity="<ct>" <attrs>/>'<sphere>
       '</worldbody></mujoco>')
m = mujoco.MjModel.from_xml_string(xml)
d = mujoco.MjData(m)
"""
MESH_SPHERE = """
       '<body name="a" pos="' + f({{a.center}}) + '"><freejoint/><geom name="a" type="sphere" size="'
       + f([{{a.radius}}]) + '" contype="1" conaffinity="1" <attrs>/></body>'"""

# MuJoCo's contacts: frame[:3] = the unit normal from geom[0] toward geom[1] (for a
# flex, geom[1] = -1 and flex[1] = the flex); dist = signed distance (< 0: penetration);
# pos = the midpoint between the two surfaces
CONTACTS = """\
mujoco.mj_kinematics(m, d)
<flex>mujoco.mj_collision(m, d)
print("geoms:", [m.geom(i).name for i in range(m.ngeom)], "ncon:", d.ncon)
for i in range(d.ncon):  # frame[:3]: normal from geom[0] toward geom[1]; dist < 0: penetration; pos: midway
    c = d.contact[i]
    print(f"contact {i}: geom {c.geom.tolist()} flex {c.flex.tolist()} pos {c.pos.tolist()} "
          f"normal {c.frame[:3].tolist()} dist {float(c.dist)!r}")
"""

# mj_ray / mj_rayFlex: pnt = start, vec = end - start; x = the hit's distance along vec in
# units of |vec| (-1: none); normal = the surface normal at the hit
RAY = """\
mujoco.mj_kinematics(m, d)
<flex>start = np.array({{a.start}})
vec = np.array({{a.end}}) - start
normal, <id> = np.zeros(3), np.zeros(1, np.int32)
x = <call>
print("x:", float(x), "(hit point start + x*vec; -1: no hit)", "<id>:", int(<id>[0]), "normal:", normal.tolist())
"""
RAY_GEOM = ("mujoco.mj_ray(m, d, start, vec, None, 1, -1, geomid, normal)  # geomgroup NULL, flg_static 1, bodyexclude -1\n"
            "# (the adapter does not call mj_ray when |vec| < mjMINVAL: MuJoCo's mjERROR would end its process)")
RAY_FLEX = ("mujoco.mj_rayFlex(m, d, 0, False, False, True, False, 0, start, vec, vertid, normal)"
            "  # layer 0, faces only, flex 0")

BOXES = """\
for name, lo, hi in (("a", {{a.min}}, {{a.max}}), ("b", {{b.min}}, {{b.max}})):  # set_box: centre, half extents
    c, h = [0.5 * lo[i] + 0.5 * hi[i] for i in range(3)], [0.5 * hi[i] - 0.5 * lo[i] for i in range(3)]
    g = m.geom(name).id
    m.geom_pos[g], m.geom_size[g] = c, h
    m.geom_rbound[g], m.geom_aabb[g] = math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]), [0.0, 0.0, 0.0] + h
"""


# set_obox: centre, half extents, the quaternion [w, x, y, z] made unit, and the bounding
# data the compiler gives a box
OBOX = """\
g, h, q = m.geom("<geom>").id, [float(x) for x in {{@.half_extents}}], [float(x) for x in {{@.rotation}}]
m.geom_pos[g], m.geom_quat[g], m.geom_size[g] = {{@.center}}, [x / math.hypot(*q) for x in q], h
m.geom_rbound[g], m.geom_aabb[g] = math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]), [0.0, 0.0, 0.0] + h
"""

# set_capsule: the midpoint, size [r, half length], the geom's z onto the axis by MuJoCo's
# mju_quatZ2Vec, and the bounding data the compiler gives a capsule
CAPSULE = """\
g, st, en, r = m.geom("<geom>").id, {{@.start}}, {{@.end}}, {{@.radius}}
half = [0.5 * en[i] - 0.5 * st[i] for i in range(3)]
hl = math.hypot(*half)
q = np.zeros(4)
mujoco.mju_quatZ2Vec(q, np.array([x / hl for x in half]))
m.geom_pos[g], m.geom_quat[g], m.geom_size[g] = [0.5 * st[i] + 0.5 * en[i] for i in range(3)], q, [r, hl, 0.0]
m.geom_rbound[g], m.geom_aabb[g] = r + hl, [0.0, 0.0, 0.0, r, r, r + hl]
"""

SETTER = {"sphere": SPHERE, "box": OBOX, "capsule": CAPSULE, "plane": PLANE}
SCENE_OF = {("sphere", "box"): "sphere-box", ("box", "plane"): "plane-box", ("sphere", "capsule"): "sphere-capsule",
            ("capsule", "capsule"): "capsule-capsule", ("capsule", "plane"): "plane-capsule",
            ("box", "box"): "box-box", ("capsule", "box"): "capsule-box"}
FLEX_SCENE_OF = {"box": "flex-box", "capsule": "flex-capsule"}


def script(query, ka, kb, models, geom_attrs, inertia):
    text = body(query, ka, kb, models, geom_attrs, inertia)
    head = (HEAD.replace("<pins>", pinned("mujoco", *(["numpy"] if "np." in text else [])))
            .replace("<query>", query).replace("<pair>", f"{ka}-{kb}"))
    return head + imports(text)


def body(query, ka, kb, models, geom_attrs, inertia):
    """The script after its first line."""

    def scene(name):
        return SCENE.replace("<xml>", models[name])

    def contacts(flex=False):
        return CONTACTS.replace("<flex>", "mujoco.mj_flex(m, d)\n" if flex else "")

    def mesh_model(ct, sphere):
        return (MESH_MODEL.replace("<sphere>", MESH_SPHERE if sphere else "").replace("<inertia>", inertia)
                .replace("<ct>", ct).replace("<attrs>", geom_attrs))

    def ray(call, ident, flex=False):
        return (RAY.replace("<flex>", "mujoco.mj_flex(m, d)\n" if flex else "")
                .replace("<call>", call).replace("<id>", ident))

    if query == "contact" and (ka, kb) in SCENE_OF:
        # the case's a is the model's geom "a" (in a free body), its b the geom "b" (world);
        # the adapter takes the deepest contact (the least dist)
        return (scene(SCENE_OF[(ka, kb)]) + SETTER[ka].replace("@", "a").replace("<geom>", "a")
                + SETTER[kb].replace("@", "b").replace("<geom>", "b") + contacts()
                + "# the adapter takes the contact with the least dist (the first of equals)\n")
    if query == "contact" and kb == "triangle" and ka in FLEX_SCENE_OF:
        # the case's a is the model's geom "a" (in a free body), its triangle b the flex's one
        # element; the adapter takes the deepest contact (the least dist)
        return (scene(FLEX_SCENE_OF[ka]) + SETTER[ka].replace("@", "a").replace("<geom>", "a")
                + "m.flex_vert[:] = {{b.vertices}}  # the one-triangle flex's vertices\n" + contacts(True)
                + "# the adapter takes the contact with the least dist (the first of equals)\n")
    if query == "intersect" and kb == "box":
        return scene("box-only") + OBOX.replace("@", "b").replace("<geom>", "b") + ray(RAY_GEOM, "geomid")
    if query == "overlap" and ka == "box":
        setter_b = (OBOX.replace("@", "b").replace("<geom>", "b") if kb == "box" else
                    BOXES.replace('(("a", {{a.min}}, {{a.max}}), ("b", {{b.min}}, {{b.max}}))',
                                 '(("b", {{b.min}}, {{b.max}}),)'))
        return (scene("box-box") + OBOX.replace("@", "a").replace("<geom>", "a") + setter_b + contacts()
                + "# the adapter's overlap: at least one contact with dist <= 0\n")
    if query == "contact":
        # the sphere is the model's geom "a" (in a free body), the other shape is "b" (or
        # the flex) in the world body; in a reversed pair the case's a is the model's "b"
        sphere, other, kind = ("a", "b", kb) if ka == "sphere" else ("b", "a", ka)
        note = ("" if ka == "sphere" else
                f"# the case's b (the sphere) is the model's geom \"a\"; the case's a (the {ka}) is "
                + ("the flex\n" if ka == "triangle" else "the model's geom \"b\"\n"))
        if kind == "mesh":  # compiled as engine.py's Scene compiles it
            return mesh_model("1", True) + SCENE.splitlines(True)[-1] + contacts()
        setter_a = SPHERE.replace("@", sphere).replace("<geom>", "a")
        if kind == "sphere":
            return scene("sphere-sphere") + setter_a + SPHERE.replace("@", "b").replace("<geom>", "b") + contacts()
        if kind == "plane":
            return (scene("plane-sphere") + note + setter_a
                    + PLANE.replace("@", other).replace("<geom>", "b") + contacts())
        return (scene("flex-sphere") + note + setter_a
                + f"m.flex_vert[:] = {{{{{other}.vertices}}}}  # the one-triangle flex's vertices\n" + contacts(True))
    if query == "intersect":
        if kb == "plane":
            return (scene("plane-only") + PLANE.replace("@", "b").replace("<geom>", "b")
                    + ray(RAY_GEOM, "geomid"))
        if kb == "triangle":
            return (scene("flex-sphere") + "m.flex_vert[:] = {{b.vertices}}  # the one-triangle flex's vertices\n"
                    + ray(RAY_FLEX, "vertid", flex=True))
        return mesh_model("0", False) + ray(RAY_GEOM, "geomid")
    # overlap aabb-aabb
    return scene("box-box") + BOXES + contacts() + "# the adapter's overlap: at least one contact with dist <= 0\n"


def imports(body):
    """The imports `body` needs."""
    return (("import math\n" if "math." in body else "") + ("import numpy as np\n" if "np." in body else "")
            + "import mujoco\n" + body)


# --- distance: the case's two shapes as geoms "a" and "b" of one model's world body, as
# engine.py's dist_geom_xml writes them (the compiler places them), then mj_geomDistance
# with the shared distmax (distance_reach, pasted in) ---------------------------------------
DIST_SHAPE = {
    "sphere": """{"sphere": {"center": {{@.center}}, "radius": {{@.radius}}}}""",
    "box": """{"box": {"center": {{@.center}}, "half_extents": {{@.half_extents}}, "rotation": {{@.rotation}}}}""",
    "capsule": """{"capsule": {"start": {{@.start}}, "end": {{@.end}}, "radius": {{@.radius}}}}""",
    "plane": """{"plane": {"normal": {{@.normal}}, "offset": {{@.offset}}}}""",
    "convex": """{"convex": {"points": {{@.points}}}}""",
}
DIST_GEOM = """\
def geom(name, shape):  # (asset, geom) MJCF, as engine.py's dist_geom_xml writes them
    (kind, s), = shape.items()
    g = f'name="{name}" contype="0" conaffinity="0" <attrs>'
    if kind == "sphere":
        return "", f'<geom {g} type="sphere" size="{f([s["radius"]])}" pos="{f(s["center"])}"/>'
    if kind == "box":
        return "", f'<geom {g} type="box" size="{f(s["half_extents"])}" pos="{f(s["center"])}" quat="{f(s["rotation"])}"/>'
    if kind == "capsule":
        return "", f'<geom {g} type="capsule" size="{f([s["radius"]])}" fromto="{f(s["start"] + s["end"])}"/>'
    if kind == "plane":  # MuJoCo's plane: the half-space z <= 0 of its frame
        n = s["normal"]
        ln = math.hypot(*n)
        k = s["offset"] / ln
        return "", f'<geom {g} type="plane" size="0 0 1" zaxis="{f(n)}" pos="{f([x / ln * k for x in n])}"/>'
    return (f'<mesh name="m{name}" inertia="<inertia>" vertex="{f(x for p in s["points"] for x in p)}"/>',
            f'<geom {g} type="mesh" mesh="m{name}"/>')
"""
DISTANCE = """\
f = lambda xs: " ".join(repr(float(x)) for x in xs)
case = {"a": <a>, "b": <b>}
<geom>
(asset_a, geom_a), (asset_b, geom_b) = geom("a", case["a"]), geom("b", case["b"])
m = mujoco.MjModel.from_xml_string(f"<mujoco><asset>{asset_a}{asset_b}</asset><worldbody>{geom_a}{geom_b}</worldbody></mujoco>")
d = mujoco.MjData(m)
mujoco.mj_kinematics(m, d)

<distmax>
fromto = np.zeros(6)
dist = mujoco.mj_geomDistance(m, d, m.geom("a").id, m.geom("b").id, distance_reach(case), fromto)
print("distmax:", distance_reach(case), "dist:", repr(float(dist)), "from (on a):", fromto[:3].tolist(),
      "to (on b):", fromto[3:].tolist())
"""


def distance_script(ka, kb, geom_attrs, inertia, distmax_source):
    head = (HEAD.replace("<pins>", pinned("mujoco", "numpy")).replace("<query>", "distance")
            .replace("<pair>", f"{ka}-{kb}") + "import math\nimport sys\nimport numpy as np\nimport mujoco\n")
    return head + (DISTANCE.replace("<a>", DIST_SHAPE[ka].replace("@", "a"))
                   .replace("<b>", DIST_SHAPE[kb].replace("@", "b"))
                   .replace("<geom>", DIST_GEOM.replace("<attrs>", geom_attrs).replace("<inertia>", inertia))
                   .replace("<distmax>", distmax_source))


def reproductions(handlers, models, geom_attrs, inertia, distance=None):
    """One script for every pair in `handlers` (engine.py's HANDLERS). `models`: the
    MJCF of engine.py's fixed models by scene name; `geom_attrs`: the margin and gap
    attributes of every geom; `inertia`: a mesh's inertia mode; `distance`: (a distance
    case's mesh inertia, the source of the shared distance_reach (common/crashtest_engine.py))."""
    if distance is None:
        return {(q, a, b): script(q, a, b, models, geom_attrs, inertia) for q, a, b in handlers}
    dist_inertia, distmax_source = distance
    return {(q, a, b): distance_script(a, b, geom_attrs, dist_inertia, distmax_source) if q == "distance"
            else script(q, a, b, models, geom_attrs, inertia) for q, a, b in handlers}
