"""crashtest-engine/1 for Python adapters: the read loop, the hello, per-case
timing and error containment (docs/PROTOCOL.md). An adapter gives its name,
version, precision, provenance and one handler per pair it answers; a handler
takes the case (a dict in the fixture format's vocabulary) and returns the
answer (a dict in the `expect` vocabulary), or raises `Unsupported`.

Timing: a handler that wraps its engine's call in `timed(...)` is charged for
that call alone (the conversion of the case into the engine's types and of its
result back is the adapter's, not the engine's); otherwise the whole handler
is timed.

Reproductions: `serve(..., reproductions={(query, a, b): script})` (b None for
bounds) puts standalone Python programs in the hello (`"reproductions"`, docs/
PROTOCOL.md): each asks the engine one case of its pair through the engine's own
package, exactly as the handler does, and prints the engine's raw answer.
Placeholders such as `{{a.center}}`, `{{b.vertices}}`, `{{t_max}}` become the
case's values as JSON literals when crashtest fills a finding's draft.

Convex hulls: `convex_hull(points)` gives the vertices and faces of a `convex`
shape's hull (Qhull through scipy) for adapters whose engine's convex shape wants
them (FCL's `Convex`, Coal's `Convex`): input preparation, never an answer.
"""
import json
import math
import os
import sys
import time

PROTOCOL = "crashtest-engine/1"


class Unsupported(Exception):
    """The engine cannot answer this case; the message says why."""


_charged = []  # ns of the engine calls made for the current case


def timed(fn, *args, **kwargs):
    """Calls `fn(*args, **kwargs)` and charges its time to the current case."""
    start = time.perf_counter_ns()
    out = fn(*args, **kwargs)
    _charged.append(time.perf_counter_ns() - start)
    return out


def finite(x):
    """Whether every number in `x` is finite."""
    if isinstance(x, float):
        return math.isfinite(x)
    if isinstance(x, dict):
        return all(finite(v) for v in x.values())
    if isinstance(x, (list, tuple)):
        return all(finite(v) for v in x)
    return True


def pair_of(case):
    """The case's (query, kind of a, kind of b or None)."""
    return (case["query"], next(iter(case["a"])), next(iter(case["b"])) if "b" in case else None)


def answer(handlers, case):
    """One case's entry: its answer, `unsupported`, or the error; with its time."""
    _charged.clear()
    start = time.perf_counter_ns()
    try:
        key = pair_of(case)
        if key not in handlers:
            entry = {"unsupported": "not among the engine's capabilities"}
        else:
            ans = handlers[key](case)
            entry = {"answer": ans} if finite(ans) else {"error": "non-finite number in the answer"}
    except Unsupported as why:
        entry = {"unsupported": str(why)}
    except Exception as exc:  # the engine's own failure on this case, shown as it is
        entry = {"error": f"{type(exc).__name__}: {exc}"}
    whole = time.perf_counter_ns() - start
    entry["ns"] = float(sum(_charged)) if _charged else float(whole)
    return entry


def send(msg):
    sys.stdout.write(json.dumps(msg, allow_nan=False, separators=(",", ":")) + "\n")
    sys.stdout.flush()


def run_world(world, msg):
    """One `world` message's reply: the engine's `world(msg)` (a dict with
    `positions`, `velocities` and `settings`), timed, or the error."""
    reply = {"type": "world", "id": int(msg.get("id", 0))}
    _charged.clear()
    start = time.perf_counter_ns()
    try:
        out = world(msg)
        if not finite([out.get("positions"), out.get("velocities")]):
            raise ValueError("non-finite number in the trajectory")
        reply.update(out)
    except Exception as exc:  # the engine's own failure on this world, shown as it is
        reply = {"type": "world", "id": reply["id"], "error": f"{type(exc).__name__}: {exc}"}
    whole = time.perf_counter_ns() - start
    reply["ns"] = float(sum(_charged)) if _charged else float(whole)
    return reply


def serve(name, version, precision, handlers, provenance, pair_precision=None, world=None,
          reproductions=None, prepare=None):
    """Answers crashtest on standard input and output until `shutdown`.
    `pair_precision` maps a pair, (query, a, b), to the bits of mantissa it is
    answered in where that is not `precision` (a mesh stored in f32: 24).
    `world`, when given, steps a `world` message (docs/PROTOCOL.md, "`world`").
    `reproductions` maps a pair (b None for bounds) to a Python script with
    placeholders (the module's docstring), sent in the hello.
    `prepare`, when given, is called with a batch's cases (the JSON objects
    among them) before they are answered one by one: an adapter may start work
    on several at once there, and its handlers then hand back what it found.
    An exception it raises is written to standard error and the batch is
    answered case by case as without it."""
    pair_precision = pair_precision or {}
    repros = [{"query": q, "a": a, **({"b": b} if b else {}), "language": "python", "script": script}
              for (q, a, b), script in (reproductions or {}).items()]
    for line in sys.stdin:
        if not line.strip():
            continue
        try:
            msg = json.loads(line, parse_int=float)  # every input number is an f64
        except ValueError as exc:
            print(f"{name}: not a message: {exc}", file=sys.stderr)
            continue
        kind = msg.get("type") if isinstance(msg, dict) else None
        if kind == "hello":
            caps = [{"query": q, "a": a, **({"b": b} if b else {}),
                     **({"precision": pair_precision[(q, a, b)]} if (q, a, b) in pair_precision else {})}
                    for q, a, b in handlers]
            send({"type": "hello", "protocol": PROTOCOL, "name": name, "version": version,
                  "precision": precision, "capabilities": caps, "provenance": provenance,
                  **({"worlds": True} if world else {}),
                  **({"reproductions": repros} if repros else {})})
        elif kind == "batch":
            if prepare:
                try:
                    prepare([c for c in msg.get("cases", []) if isinstance(c, dict)])
                except Exception as exc:
                    print(f"{name}: preparing batch {msg.get('id')}: {type(exc).__name__}: {exc}", file=sys.stderr)
            answers = []
            for c in msg.get("cases", []):
                answers.append(answer(handlers, c) if isinstance(c, dict) else {"error": "a case is a JSON object"})
            send({"type": "answers", "id": int(msg["id"]), "answers": answers})
        elif kind == "world" and world:
            send(run_world(world, msg))
        elif kind == "world":
            send({"type": "world", "id": int(msg.get("id", 0)), "error": f"{name} does not step worlds"})
        elif kind == "shutdown":
            return 0
        else:
            print(f"{name}: ignoring a message of type {kind!r}", file=sys.stderr)
    return 0


def pinned(*dists):
    """'dist==version, ...' as engines/requirements.txt pins them (the installed
    version where it pins none): the first line of a reproduction."""
    pins = {}
    try:
        with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "requirements.txt")) as f:
            for line in f:
                name, sep, version = line.split("#")[0].strip().partition("==")
                if sep:
                    pins[name.lower()] = version.strip()
    except OSError:
        pass
    return ", ".join(f"{d}=={pins.get(d.lower()) or package_version(d)}" for d in dists)


def package_version(dist):
    """The installed version of distribution `dist`, or 'not installed'."""
    from importlib import metadata
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "not installed"


# --- convex hulls: input preparation for the `convex` shape ------------------------------
HULL_NOTE = ("the case's points made unique (numpy.unique); a solid hull: scipy.spatial.ConvexHull "
             "(Qhull with scipy's default options for 3-D, 'Qt' only) of the points scaled by a power of two to "
             "at most 1 and centred (Qhull dies where its products overflow): its vertices (input points, "
             "never moved) and its triangles, each turned to face out by Qhull's own facet normal; a hull Qhull "
             "finds flat: its polygon (a 2-D ConvexHull of the points in the coordinate plane their "
             "normal is least parallel to) as two fans of triangles, one per side; a segment-like one: "
             "its two extreme points; one point: that point. Points Qhull leaves out lie inside, or "
             "within its roundoff of a facet (Qhull's coplanar points)")


class Hull:
    """A convex hull prepared for an engine that wants vertices and faces: `vertices` (k, 3)
    float64, each one of the case's points as given; `triangles` (m, 3) int64 into them,
    counter-clockwise seen from outside (for `dim` 3; for `dim` 2 each triangle of the
    polygon once per side); `polygon` the flat hull's vertices in order around it (dim 2);
    `dim` 0 (a point), 1 (a segment), 2 (a polygon) or 3 (a solid)."""

    def __init__(self, vertices, triangles, dim, polygon=None):
        self.vertices, self.triangles, self.dim, self.polygon = vertices, triangles, dim, polygon


def convex_hull(points):
    """The hull of a `convex` shape's points, for engines whose convex shape takes vertices
    and faces (HULL_NOTE says how). This is the adapter's input preparation: the engine
    still answers every query on it."""
    import numpy as np
    from scipy.spatial import ConvexHull, QhullError

    pts = np.unique(np.asarray(points, dtype=np.float64).reshape(-1, 3), axis=0)
    none = np.zeros((0, 3), dtype=np.int64)
    if len(pts) == 1:
        return Hull(pts, none, 0)
    # Qhull (and the SVD below) are given the points scaled by a power of two to at most 1
    # in magnitude and moved to their box's centre: Qhull dies (SIGSEGV) where its products
    # of coordinates overflow (points of 1e270 do it), and which points are vertices does not
    # change under scaling and translation. The hull's vertices are the case's own points.
    top = float(np.abs(pts).max())
    q = np.ldexp(pts, -math.frexp(top)[1]) if top > 0 else pts
    q = q - (0.5 * q.min(axis=0) + 0.5 * q.max(axis=0))
    if len(pts) >= 4:
        try:
            h = ConvexHull(q)
        except QhullError:
            h = None
        if h is not None:
            keep = np.asarray(h.vertices)
            index = np.full(len(pts), -1, dtype=np.int64)
            index[keep] = np.arange(len(keep))
            tris = index[np.asarray(h.simplices, dtype=np.int64)]
            w = q[keep]
            e0, e1 = w[tris[:, 1]] - w[tris[:, 0]], w[tris[:, 2]] - w[tris[:, 0]]
            inward = np.einsum("ij,ij->i", np.cross(e0, e1), h.equations[:, :3]) < 0
            tris[inward] = tris[inward][:, [0, 2, 1]]
            return Hull(pts[keep], tris, 3)
    # flat, a segment or fewer than 4 points: the plane the points span, found by the
    # direction of least spread (SVD), then a 2-D hull in the coordinate plane most
    # nearly parallel to it (its vertices are input points; the order around is Qhull's)
    centred = q - q.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    drop = int(np.argmax(np.abs(vt[-1]))) if len(vt) == 3 else None
    if drop is not None and len(pts) >= 3:
        axes = [i for i in range(3) if i != drop]
        try:
            h2 = ConvexHull(q[:, axes])
        except QhullError:
            h2 = None
        if h2 is not None:
            ring = np.asarray(h2.vertices, dtype=np.int64)  # counter-clockwise in the 2-D plane
            v = pts[ring]
            k = len(v)
            fan = np.array([[0, i, i + 1] for i in range(1, k - 1)], dtype=np.int64)
            return Hull(v, np.concatenate([fan, fan[:, [0, 2, 1]]]), 2, polygon=np.arange(k))
    # a segment: its two extreme points along the direction of greatest spread
    t = centred @ vt[0]
    ends = pts[[int(np.argmin(t)), int(np.argmax(t))]]
    return Hull(ends, none, 1)


# The format's distance pairs (docs/FORMAT.md, "Distance"), `a` then `b`.
DISTANCE_PAIRS = [("sphere", "sphere"), ("sphere", "plane"), ("sphere", "triangle"), ("sphere", "box"),
                  ("sphere", "capsule"), ("sphere", "convex"), ("box", "plane"), ("box", "box"),
                  ("box", "triangle"), ("capsule", "capsule"), ("capsule", "plane"), ("capsule", "box"),
                  ("capsule", "triangle"), ("capsule", "convex"), ("convex", "convex"), ("convex", "plane"),
                  ("convex", "box"), ("convex", "triangle")]


def distance_reach(case):
    """8 M + 1 (at most DBL_MAX), with M the largest magnitude among a distance case's
    coordinates, radii, half-extents and plane offsets over |n|: every point of a sphere, box,
    capsule, triangle or hull lies within 2 sqrt(3) M < 3.5 M of the origin (a centre or end
    within sqrt(3) M, plus a radius or a half-diagonal), a plane passes within M of it, so no
    distance between the two shapes reaches 8 M. For engines that search for closest points
    only up to a given distance."""
    m = 0.0
    for shape in (case["a"], case["b"]):
        (kind, s), = shape.items()
        if kind == "plane":
            m = max(m, abs(float(s["offset"])) / math.hypot(*s["normal"]))
            continue
        for key, v in s.items():
            if key in ("points", "vertices"):
                m = max(m, max(abs(float(x)) for q in v for x in q))
            elif key in ("center", "start", "end", "half_extents"):
                m = max(m, max(abs(float(x)) for x in v))
            elif key == "radius":
                m = max(m, abs(float(v)))
    return min(8.0 * m + 1.0, sys.float_info.max)
