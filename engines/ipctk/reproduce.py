"""ipctk's reproductions: for every pair engine.py answers, a standalone program
that asks ipctk one case the way engine.py does (the same method object, the
same argument order, min_distance and tmax) and prints ipctk's raw answer, the
(hit, toi) pair, before engine.py's convention translation. engine.py passes
`reproductions(method, ctor, handlers)` to `serve`, which puts them in the hello;
crashtest fills the placeholders (`{{a.t0}}`, `{{b.t1}}`, `{{t_max}}`) with a
finding's shrunk case (docs/PROTOCOL.md, hello, `reproductions`).

Keep them in step with engine.py: a change to a setting or a call there is a
change here. The script makes the call in its own process (the adapter's worker
and its time budget are not reproduced): where ipctk runs long, so does the
script, and that is the reproduction.
"""
from crashtest_engine import pinned

HEAD = """\
# <pins>: crashtest `ccd` <pair>, asked as crashtest's ipctk/<method> adapter asks it
import numpy as np
import ipctk

V = lambda p: np.array(p, dtype=np.float64)
ccd = <ctor>
print(ccd.__class__.__name__, {k: getattr(ccd, k) for k in <attrs>})
"""

ATTRS = {
    "tight-inclusion": '("tolerance", "max_iterations", "conservative_rescaling")',
    "additive": '("conservative_rescaling",)',  # max_iterations: no attribute in ipctk's Python API
}

POINT_TRIANGLE = """\
p_t0, p_t1 = V({{a.t0}}), V({{a.t1}})      # the moving point at time 0 and 1
tri_t0 = [V(v) for v in {{b.t0}}]          # the triangle's vertices at time 0
tri_t1 = [V(v) for v in {{b.t1}}]          # ... and at time 1
# (hit, toi): toi is the time of impact when hit; when not, it is not a time
hit, toi = ccd.point_triangle_ccd(p_t0, *tri_t0, p_t1, *tri_t1, min_distance=0.0, tmax={{t_max}})
print("hit:", hit, "toi:", repr(toi))
"""

EDGE_EDGE = """\
ea_t0, ea_t1 = [V(v) for v in {{a.t0}}], [V(v) for v in {{a.t1}}]   # segment a's ends at time 0, 1
eb_t0, eb_t1 = [V(v) for v in {{b.t0}}], [V(v) for v in {{b.t1}}]   # segment b's ends at time 0, 1
# (hit, toi): toi is the time of impact when hit; when not, it is not a time
hit, toi = ccd.edge_edge_ccd(*ea_t0, *eb_t0, *ea_t1, *eb_t1, min_distance=0.0, tmax={{t_max}})
print("hit:", hit, "toi:", repr(toi))
"""


def script(method, ctor, ka, kb):
    head = (HEAD.replace("<pins>", pinned("ipctk", "numpy")).replace("<pair>", f"{ka}-{kb}")
            .replace("<method>", method).replace("<ctor>", ctor).replace("<attrs>", ATTRS[method]))
    return head + (POINT_TRIANGLE if ka == "moving_point" else EDGE_EDGE)


def reproductions(method, ctor, handlers):
    """One script for every pair in `handlers` (engine.py's handlers); `ctor` is the
    method object's constructor call with every setting the adapter's object has."""
    return {(q, a, b): script(method, ctor, a, b) for q, a, b in handlers}
