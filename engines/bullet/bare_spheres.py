#!/usr/bin/env python3
"""Checks that engine.py's bare spheres answer as bodies do (run by crashtest's tests).

engine.py hands a sphere to getClosestPoints as a bare collision shape and makes only
the other shape a body (closest_points). This asks every pair it answers both ways, on
seeded random cases (apart, touching, penetrating, centre inside, either argument order)
and exact ones (touching exactly, concentric), and exits 1 naming the first case whose
raw pybullet points differ in any bit: the bodies way is engine.make for both shapes,
as reproduce.py's programs build them.
"""
import os
import random
import sys

sys.argv = [sys.argv[0]]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import engine  # noqa: E402  (connects to pybullet in DIRECT mode)

p = engine.p


def with_bodies(case):
    engine._housekeeping()
    a, b = engine.make(case["a"]), engine.make(case["b"])
    try:
        return p.getClosestPoints(a, b, engine.DISTANCE)
    finally:
        p.removeBody(a)
        p.removeBody(b)


def point(rng, scale):
    return [rng.uniform(-scale, scale) for _ in range(3)]


def shapes(rng):
    scale = 10.0 ** rng.randint(-3, 3)
    c = point(rng, scale)
    r = scale * rng.uniform(0.01, 1.0)
    sphere = {"sphere": {"center": c, "radius": r}}
    other_c = [c[i] + rng.uniform(-2, 2) * r for i in range(3)]
    yield {"sphere": {"center": other_c, "radius": scale * rng.uniform(0.01, 1.0)}}
    n = point(rng, 1.0)
    yield {"plane": {"normal": n, "offset": sum(n[i] * c[i] for i in range(3)) + rng.uniform(-1.5, 1.5) * r}}
    tri = [[c[i] + rng.uniform(-3, 3) * r for i in range(3)] for _ in range(3)]
    yield {"triangle": {"vertices": tri}}
    mesh = tri + [[c[i] + rng.uniform(-3, 3) * r for i in range(3)] for _ in range(2)]
    yield {"mesh": {"vertices": mesh, "triangles": [[0, 1, 2], [1, 3, 2], [2, 3, 4]]}}
    yield {"box": {"center": other_c, "half_extents": [scale * rng.uniform(0.0, 1.0) for _ in range(3)],
                   "rotation": [rng.uniform(-1, 1) for _ in range(4)]}}
    yield {"capsule": {"start": other_c, "end": [c[i] + rng.uniform(-3, 3) * r for i in range(3)],
                       "radius": scale * rng.uniform(0.01, 1.0)}}
    yield sphere  # the sphere itself last: the callers pair it with each of the above


def cases():
    rng = random.Random(20261122)
    for _ in range(300):
        *others, sphere = shapes(rng)
        for other in others:
            yield {"a": sphere, "b": other}
            if not {"mesh", "box", "capsule"} & set(other):  # sphere first only: the pairs
                yield {"a": other, "b": sphere}
    # exact: touching a plane, a triangle and a sphere exactly; concentric spheres
    unit = {"sphere": {"center": [0.0, 0.0, 1.0], "radius": 1.0}}
    yield {"a": unit, "b": {"plane": {"normal": [0.0, 0.0, 2.0], "offset": 0.0}}}
    yield {"a": {"plane": {"normal": [0.0, 0.0, 1.0], "offset": 0.0}}, "b": unit}
    yield {"a": unit, "b": {"triangle": {"vertices": [[-1.0, -1.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]]}}}
    yield {"a": unit, "b": {"sphere": {"center": [0.0, 0.0, 3.0], "radius": 1.0}}}
    yield {"a": unit, "b": {"sphere": {"center": [0.0, 0.0, 1.0], "radius": 0.5}}}
    yield {"a": unit, "b": {"box": {"center": [0.0, 0.0, -1.0], "half_extents": [1.0, 1.0, 1.0]}}}
    yield {"a": unit, "b": {"capsule": {"start": [-1.0, 0.0, -0.5], "end": [1.0, 0.0, -0.5], "radius": 0.5}}}


def main():
    n = 0
    for case in cases():
        bare, bodies = engine.closest_points(case), with_bodies(case)
        # every field but the body ids (-1 for a bare shape) and link indices
        strip = [[tuple(q[5]), tuple(q[6]), tuple(q[7]), q[8]] for q in bare]
        want = [[tuple(q[5]), tuple(q[6]), tuple(q[7]), q[8]] for q in bodies]
        if repr(strip) != repr(want):
            print(f"case {n}: {case}\n  bare spheres: {strip}\n  bodies:       {want}", file=sys.stderr)
            return 1
        n += 1
    print(f"{n} cases: bare spheres and bodies give the same points, bit for bit")
    return 0


if __name__ == "__main__":
    sys.exit(main())
