#!/usr/bin/env python3
"""python-reference: the lecture's plain formulas behind crashtest-engine/1 (stdlib only)."""
import json, math, platform, sys, time

def add(u, v): return [u[0] + v[0], u[1] + v[1], u[2] + v[2]]
def sub(u, v): return [u[0] - v[0], u[1] - v[1], u[2] - v[2]]
def mul(u, s): return [u[0] * s, u[1] * s, u[2] * s]
def dot(u, v): return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
def cross(u, v): return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
def norm(u): return math.sqrt(dot(u, u))
UP = [0.0, 0.0, 1.0]  # fallback normal wherever a direction is undefined (answered with degenerate: true)

def closest_on_segment(p, a, b):
    ab = sub(b, a); l2 = dot(ab, ab)
    t = 0.0 if l2 == 0 else min(1.0, max(0.0, dot(sub(p, a), ab) / l2))
    return add(a, mul(ab, t))

def closest_on_triangle(p, a, b, c):  # by the regions of its vertices, edges and face
    if norm(cross(sub(b, a), sub(c, a))) == 0:  # zero area: the closest of its edges (well defined)
        return min((closest_on_segment(p, u, v) for u, v in ((a, b), (b, c), (c, a))), key=lambda q: norm(sub(p, q)))
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if d1 <= 0 and d2 <= 0: return a
    bp = sub(p, b); d3, d4 = dot(ab, bp), dot(ac, bp)
    if d3 >= 0 and d4 <= d3: return b
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0: return add(a, mul(ab, d1 / (d1 - d3)))
    cp = sub(p, c); d5, d6 = dot(ab, cp), dot(ac, cp)
    if d6 >= 0 and d5 <= d6: return c
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0: return add(a, mul(ac, d2 / (d2 - d6)))
    va = d3 * d6 - d5 * d4
    if va <= 0 and d4 - d3 >= 0 and d5 - d6 >= 0: return add(b, mul(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))))
    denom = va + vb + vc
    return add(a, add(mul(ab, vb / denom), mul(ac, vc / denom)))

def bary(p, a, b, c):  # signed barycentrics of p's projection onto the plane; None if zero area
    v0, v1, v2 = sub(b, a), sub(c, a), sub(p, a)
    d00, d01, d11, d20, d21 = dot(v0, v0), dot(v0, v1), dot(v1, v1), dot(v2, v0), dot(v2, v1)
    den = d00 * d11 - d01 * d01
    if den == 0 or norm(cross(v0, v1)) == 0: return None
    v = (d11 * d20 - d01 * d21) / den; w = (d00 * d21 - d01 * d20) / den
    return [1.0 - v - w, v, w]

# Contact of sphere `a` against shape `b`: point on b, normal from b toward a, depth >= 0.
def contact(s, b):
    M, r = s["center"], s["radius"]
    if "sphere" in b:
        B = b["sphere"]; w = sub(M, B["center"]); d = norm(w)
        if d > r + B["radius"]: return {"contact": None}
        n = UP if d == 0 else mul(w, 1 / d)  # concentric: fallback normal +z
        out = {"contact": {"point": add(B["center"], mul(n, B["radius"])), "normal": n, "depth": r + B["radius"] - d}}
        return dict(out, degenerate=True) if d == 0 else out
    if "plane" in b:
        P = b["plane"]; ln = norm(P["normal"])
        if ln == 0: return {"contact": None, "degenerate": True}
        n = mul(P["normal"], 1 / ln); s_ = (dot(P["normal"], M) - P["offset"]) / ln
        if s_ > r: return {"contact": None}
        return {"contact": {"point": sub(M, mul(n, s_)), "normal": n, "depth": r - s_}}
    V = b["triangle"]["vertices"]; q = closest_on_triangle(M, *V); w = sub(M, q); d = norm(w)
    if d > r: return {"contact": None}
    if d > 0: return {"contact": {"point": q, "normal": mul(w, 1 / d), "depth": r - d}}
    N = cross(sub(V[1], V[0]), sub(V[2], V[0])); lN = norm(N)  # centre on the triangle: face normal
    return {"contact": {"point": q, "normal": UP if lN == 0 else mul(N, 1 / lN), "depth": r}, "degenerate": True}

# THE CONVENTION TRANSLATION (the only one): this engine computes in the format's own
# conventions, so only the reverse order (plane/triangle first, sphere second) needs one:
# swap a and b, then negate the normal and move the point onto the other shape's deepest
# point, p - n*depth (n the unswapped normal).
def contact_swapped(shape_a, sphere_b):
    ans = contact(sphere_b, shape_a); c = ans["contact"]
    if c is not None:
        ans["contact"] = {"point": sub(c["point"], mul(c["normal"], c["depth"])), "normal": mul(c["normal"], -1.0), "depth": c["depth"]}
    return ans

def intersect(seg, b):
    p0 = seg["start"]; d = sub(seg["end"], p0)
    if "plane" in b: N, off, V = b["plane"]["normal"], b["plane"]["offset"], None
    else: V = b["triangle"]["vertices"]; N = cross(sub(V[1], V[0]), sub(V[2], V[0])); off = dot(N, V[0])
    if norm(N) == 0 or norm(d) == 0: return {"hit": None, "degenerate": True}  # zero-area triangle / zero-length segment
    den = dot(N, d)
    if den == 0: return {"hit": None, "parallel": True}
    t = (off - dot(N, p0)) / den
    if t < 0 or t > 1: return {"hit": None}
    hit = {"t": t, "point": add(p0, mul(d, t)), "normal": mul(N, 1 / norm(N))}
    if V is not None:
        bc = bary(hit["point"], *V)
        if bc is None: return {"hit": None, "degenerate": True}
        if min(bc) < 0: return {"hit": None}
        hit["barycentric"] = bc
    return {"hit": hit}

def toi(a, b, t_max):
    A = a["sphere"]; va = A.get("velocity", [0.0, 0.0, 0.0]); kind = "sphere" if "sphere" in b else "plane"
    B = b[kind]; vb = B.get("velocity", [0.0, 0.0, 0.0]); v = sub(va, vb); r = A["radius"]
    if kind == "sphere":
        w = sub(A["center"], B["center"]); R = r + B["radius"]; C = dot(w, w) - R * R
        if C <= 0: t = 0.0
        else:
            qa, qb = dot(v, v), dot(w, v); disc = qb * qb - qa * C
            if qa == 0 or qb >= 0 or disc < 0: return {"toi": None}
            t = (-qb - math.sqrt(disc)) / qa
        if t > t_max: return {"toi": None}
        ca, cb = add(A["center"], mul(va, t)), add(B["center"], mul(vb, t)); w = sub(ca, cb); d = norm(w)
        n = UP if d == 0 else mul(w, 1 / d)
        out = {"toi": {"t": t, "point": add(cb, mul(n, B["radius"])), "normal": n}}
        return dict(out, degenerate=True) if d == 0 else out
    ln = norm(B["normal"])
    if ln == 0: return {"toi": None, "degenerate": True}
    n = mul(B["normal"], 1 / ln); s0 = (dot(B["normal"], A["center"]) - B["offset"]) / ln
    if s0 <= r: t, s_t = 0.0, s0
    else:
        closing = -dot(n, v)
        if closing <= 0: return {"toi": None}
        t, s_t = (s0 - r) / closing, r
    if t > t_max: return {"toi": None}
    return {"toi": {"t": t, "point": sub(add(A["center"], mul(va, t)), mul(n, s_t)), "normal": n}}

def response(a, b, e):
    A = a["sphere"]; va = A["velocity"]
    if "plane" in b:
        ln = norm(b["plane"]["normal"]); zero = [0.0, 0.0, 0.0]
        if ln == 0: return {"velocity_a": va, "velocity_b": zero, "degenerate": True}
        n = mul(b["plane"]["normal"], 1 / ln); vn = dot(va, n)
        return {"velocity_a": va if vn >= 0 else sub(va, mul(n, (1 + e) * vn)), "velocity_b": zero}
    B = b["sphere"]; vb = B["velocity"]; w = sub(A["center"], B["center"]); d = norm(w)
    if d == 0: return {"velocity_a": va, "velocity_b": vb, "degenerate": True}  # concentric: keep velocities
    n = mul(w, 1 / d); vn = dot(sub(va, vb), n)
    if vn >= 0: return {"velocity_a": va, "velocity_b": vb}
    j = -(1 + e) * vn / (1 / A["mass"] + 1 / B["mass"])
    return {"velocity_a": add(va, mul(n, j / A["mass"])), "velocity_b": sub(vb, mul(n, j / B["mass"]))}

def barycentric(p, V):
    bc = bary(p, *V)
    return {"barycentric": bc} if bc else {"barycentric": [1.0, 0.0, 0.0], "degenerate": True}  # zero area: v0's

def bounds(a):
    P = a["points"]["points"]; c = mul([sum(p[i] for p in P) for i in range(3)], 1 / len(P))
    return {"aabb": {"min": [min(p[i] for p in P) for i in range(3)], "max": [max(p[i] for p in P) for i in range(3)]},
            "sphere": {"center": c, "radius": max(norm(sub(p, c)) for p in P)}}

def overlap(a, b):
    A, B = a["aabb"], b["aabb"]
    return {"overlap": all(A["min"][i] <= B["max"][i] and B["min"][i] <= A["max"][i] for i in range(3))}

HANDLERS = {
    ("contact", "sphere", "sphere"): lambda c: contact(c["a"]["sphere"], c["b"]),
    ("contact", "sphere", "plane"): lambda c: contact(c["a"]["sphere"], c["b"]),
    ("contact", "sphere", "triangle"): lambda c: contact(c["a"]["sphere"], c["b"]),
    ("contact", "plane", "sphere"): lambda c: contact_swapped(c["a"], c["b"]["sphere"]),
    ("contact", "triangle", "sphere"): lambda c: contact_swapped(c["a"], c["b"]["sphere"]),
    ("intersect", "segment", "plane"): lambda c: intersect(c["a"]["segment"], c["b"]),
    ("intersect", "segment", "triangle"): lambda c: intersect(c["a"]["segment"], c["b"]),
    ("barycentric", "point", "triangle"): lambda c: barycentric(c["a"]["point"]["at"], c["b"]["triangle"]["vertices"]),
    ("bounds", "points", None): lambda c: bounds(c["a"]),
    ("overlap", "aabb", "aabb"): lambda c: overlap(c["a"], c["b"]),
    ("toi", "sphere", "sphere"): lambda c: toi(c["a"], c["b"], c["t_max"]),
    ("toi", "sphere", "plane"): lambda c: toi(c["a"], c["b"], c["t_max"]),
    ("response", "sphere", "sphere"): lambda c: response(c["a"], c["b"], c["restitution"]),
    ("response", "sphere", "plane"): lambda c: response(c["a"], c["b"], c["restitution"]),
}

def finite(x):
    if isinstance(x, float): return math.isfinite(x)
    if isinstance(x, dict): return all(finite(v) for v in x.values())
    if isinstance(x, list): return all(finite(v) for v in x)
    return True

def answer(case):
    start = time.perf_counter_ns()
    try:
        key = (case["query"], next(iter(case["a"])), next(iter(case["b"])) if "b" in case else None)
        if key not in HANDLERS: entry = {"unsupported": "not among python-reference's capabilities"}
        else:
            ans = HANDLERS[key](case)
            entry = {"answer": ans} if finite(ans) else {"error": "non-finite number in the answer"}
    except Exception as exc:
        entry = {"error": f"{type(exc).__name__}: {exc}"}
    entry["ns"] = time.perf_counter_ns() - start
    return entry

def send(msg):
    sys.stdout.write(json.dumps(msg, allow_nan=False, separators=(",", ":")) + "\n"); sys.stdout.flush()

def main():
    for line in sys.stdin:
        if not line.strip(): continue
        msg = json.loads(line, parse_int=float)  # every input number is an f64
        if msg.get("type") == "hello":
            caps = [{"query": q, "a": a, **({"b": b} if b else {})} for q, a, b in HANDLERS]
            send({"type": "hello", "protocol": "crashtest-engine/1", "name": "python-reference", "version": "1",
                  "precision": 53, "capabilities": caps, "provenance": {"python": platform.python_version()}})
        elif msg.get("type") == "batch":
            send({"type": "answers", "id": int(msg["id"]), "answers": [answer(c) for c in msg["cases"]]})
        elif msg.get("type") == "shutdown": return 0
        else: print(f"python-reference: ignoring a message of type {msg.get('type')!r}", file=sys.stderr)
    return 0

if __name__ == "__main__":
    sys.exit(main())
