#!/usr/bin/env python3
"""ipctk: the IPC Toolkit's narrow-phase CCD methods (the Python package ipctk)
behind crashtest-engine/1, as two engines from one adapter:

    engine.py tight-inclusion   ->  ipctk/tight-inclusion (ipctk.TightInclusionCCD)
    engine.py additive          ->  ipctk/additive        (ipctk.AdditiveCCD)

See README.md for what it answers, the convention table and the divergences
found. Every number in an answer is ipctk's; the adapter only orders the case's
positions into ipctk's arguments and translates ipctk's (hit, toi) into the
format's answer, in ONE place: `arguments` and `to_format` below (the section
marked THE CONVENTION TRANSLATION).

Each case's call runs in a forked worker process with a wall-time budget
(`CASE_BUDGET`): Tight Inclusion's retry for a time of impact below
`SMALL_TOI` runs without an iteration limit (ipctk's tight_inclusion_ccd.cpp),
and where the impact is at t = 0 but ipctk's distance there rounds above 0 it
runs until memory runs out; the worker is then killed and the case fails, and
the next case gets a new worker. A batch is kept within `BATCH_BUDGET`.
"""
import json
import math
import os
import select
import signal
import sys
import time

# --- protect the protocol -------------------------------------------------------
# ipctk logs through spdlog; a native library may write to fd 1. The protocol keeps a
# duplicate of fd 1; fd 1 itself is pointed at stderr before ipctk is imported, so
# nothing but protocol messages reaches crashtest.
_PROTO_FD = os.dup(1)
os.dup2(2, 1)
sys.stdout = os.fdopen(_PROTO_FD, "w", encoding="utf-8", newline="\n")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import crashtest_engine  # noqa: E402
from crashtest_engine import package_version, serve  # noqa: E402
from reproduce import reproductions  # noqa: E402  (this folder's reproduce.py)

import numpy as np  # noqa: E402
import ipctk  # noqa: E402

# --- settings (echoed in the hello's provenance) ----------------------------------
MIN_DISTANCE = 0.0  # the format's contact is distance 0: no minimum separation
# Tight Inclusion: its default tolerance (1e-6); conservative_rescaling 1.0 (its default
# 0.8 makes ipctk ask Tight Inclusion for the time the distance reaches min(1e-4, 0.2 d0)
# instead of 0: README.md, "Settings"); the iteration limit lowered from its default 1e7
# to 1e4 (the budget of the default report: README.md, "Time"). Additive: its default
# conservative_rescaling 0.9; max_iterations lowered from its default 1e7 to 1e4 (the
# budget, the same).
TI_CONSERVATIVE_RESCALING = 1.0
TI_MAX_ITERATIONS = 10_000
ADDITIVE_MAX_ITERATIONS = 10_000
METHODS = {
    "tight-inclusion": lambda: ipctk.TightInclusionCCD(max_iterations=TI_MAX_ITERATIONS,
                                                       conservative_rescaling=TI_CONSERVATIVE_RESCALING),
    "additive": lambda: ipctk.AdditiveCCD(max_iterations=ADDITIVE_MAX_ITERATIONS),
}
CASE_BUDGET = 0.02   # s of the worker's CPU time per case; past it the worker is killed, the case failed
CASE_WALL = 2.0      # s of wall time per case, whatever the CPU time (a machine under load)
BATCH_BUDGET = 45.0  # s of wall time per batch, below crashtest's 60 s (see `wall_budget`)
CASE_FLOOR = 0.005   # s of wall time: the least a case is given when the batch's budget runs short
POLL = 0.01          # s: how often a slow case's CPU time is read
_TICKS = os.sysconf("SC_CLK_TCK")


def additive_default_max_iterations():
    """AdditiveCCD's default max_iterations, from its constructor's signature (ipctk
    exposes no attribute for it, so what was passed cannot be read back either)."""
    import re
    m = re.search(r"max_iterations: [\w.]+ = (\d+)", ipctk.AdditiveCCD.__init__.__doc__ or "")
    return int(m.group(1)) if m else None


def constructor(ccd):
    """The method object's constructor call with every setting (read back from the object
    where ipctk exposes it): the provenance and the reproductions say it."""
    if isinstance(ccd, ipctk.TightInclusionCCD):
        return (f"ipctk.TightInclusionCCD(tolerance={ccd.tolerance!r}, max_iterations={ccd.max_iterations!r}, "
                f"conservative_rescaling={ccd.conservative_rescaling!r})")
    return (f"ipctk.AdditiveCCD(max_iterations={ADDITIVE_MAX_ITERATIONS!r}, "
            f"conservative_rescaling={ccd.conservative_rescaling!r})")


def settings(ccd):
    if isinstance(ccd, ipctk.TightInclusionCCD):
        return (f"{constructor(ccd)} (its defaults: tolerance {ccd.DEFAULT_TOLERANCE!r}, max_iterations "
                f"{ccd.DEFAULT_MAX_ITERATIONS!r}, conservative_rescaling {ccd.DEFAULT_CONSERVATIVE_RESCALING!r}; "
                f"SMALL_TOI {ccd.SMALL_TOI!r})")
    return (f"{constructor(ccd)} (its defaults: max_iterations {additive_default_max_iterations()!r}, from the "
            f"constructor's signature; conservative_rescaling {ccd.DEFAULT_CONSERVATIVE_RESCALING!r})")


def provenance(method, ccd):
    conservative = {
        "tight-inclusion": "Tight Inclusion is conservative: its toi is at or before the first contact. With "
                           "min_distance 0 and conservative_rescaling 1.0, ipctk's TightInclusionCCD asks Tight "
                           "Inclusion (ticcd::vertexFaceCCD / edgeEdgeCCD, minimum separation min(1e-4, (1 - 1.0) * "
                           "d0) = 0) for the earliest time its inclusion function cannot exclude a contact, refined "
                           "until the function's box is within the tolerance min(1e-6, d0/2) in x, y and z (d0 the "
                           "distance at time 0) or max_iterations is reached (then coarser, still conservative); a "
                           "toi below SMALL_TOI is asked again with no_zero_toi and no iteration limit",
        "additive": "Additive CCD steps by conservative_rescaling * distance / (a bound on the relative "
                    "speed) and stops before a step that brings the distance below (1 - conservative_rescaling) "
                    "* d0: its toi is early by design (0.9 * t for a head-on approach)",
    }[method]
    return {
        "ipctk": package_version("ipctk"),
        "numpy": package_version("numpy"),
        "precision": "f64 (Eigen double throughout; Tight Inclusion's own numerical error filters on)",
        "method": settings(ccd),
        "min_distance": repr(MIN_DISTANCE),
        "tmax": "the case's t_max, passed as tmax",
        "toi": conservative,
        "moving_point-moving_triangle": "point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1, t2_t1, "
                                        "min_distance, tmax): a.t0, b.t0[0..2], a.t1, b.t1[0..2]",
        "moving_segment-moving_segment": "edge_edge_ccd(ea0_t0, ea1_t0, eb0_t0, eb1_t0, ea0_t1, ea1_t1, eb0_t1, "
                                         "eb1_t1, min_distance, tmax): a.t0[0..1], b.t0[0..1], a.t1[0..1], b.t1[0..1]",
        "answer": "hit false: null (the toi beside it is not a time: inf for Tight Inclusion, Additive's partial "
                  "sum); hit true: {\"t\": toi}, toi as ipctk gives it (a non-finite toi: the case's error); no "
                  "degenerate flag (ipctk has none)",
        "budget": f"each case in a forked worker process, {CASE_BUDGET:g} s of its CPU time and at most "
                  f"{CASE_WALL:g} s of wall time (less once a batch has spent most of {BATCH_BUDGET:g} s, never below "
                  f"{CASE_FLOOR:g} s): past it the worker is killed and the case is an error; ns is the method's "
                  "own call, timed in the worker",
        "logging": "ipctk.set_logger_level(LoggerLevel.error): its warnings (\"Initial distance 0 <= d_min=0, "
                   "returning toi=0!\") are not written; they change no answer",
        "stdout": "fd 1 redirected to stderr before import; protocol on a duplicate of fd 1",
    }


# --- THE CONVENTION TRANSLATION (the only place) -----------------------------------
# The format: positions move linearly from t0 (time 0) to t1 (time 1); the answer is the
# first time in [0, t_max] at which the point lies on the closed triangle (the closed
# segments share a point), or null. ipctk's methods take the same linear motion over
# [0, 1] as start and end positions, and tmax.
#
# 1. Argument order. point_triangle_ccd(p_t0, t0_t0, t1_t0, t2_t0, p_t1, t0_t1, t1_t1,
#    t2_t1): every position at time 0, then every one at time 1; the point first, then
#    the triangle's vertices in the case's order. edge_edge_ccd(ea0_t0, ea1_t0, eb0_t0,
#    eb1_t0, ea0_t1, ...): a's ends then b's at time 0, then the same at time 1.
# 2. min_distance 0 (MIN_DISTANCE), tmax = the case's t_max.
# 3. (hit, toi): hit false -> null, whatever toi is (Tight Inclusion leaves inf; Additive
#    leaves the sum of its steps when it passed tmax, which can be any number, > tmax or
#    not); hit true -> {"t": toi}, toi unchanged: never clamped to [0, t_max] nor moved
#    later (Tight Inclusion's toi is conservative, at or before the contact; Additive's
#    is early by design: README.md, "Known divergences"). An initial distance 0 is ipctk's
#    (True, 0.0): t = 0, as the format says.
# 4. No degenerate flag: ipctk has none, so none is sent.
# 5. hit with a non-finite toi (Additive on a zero-area triangle: NaN): the case's error,
#    "non-finite toi", naming ipctk's pair (the protocol's form for a NaN or infinity).
def arguments(case):
    """The case's positions in ipctk's order, and which method takes them."""
    (ka, sa), = case["a"].items()
    (kb, sb), = case["b"].items()
    if (ka, kb) == ("moving_point", "moving_triangle"):
        return "point_triangle_ccd", [sa["t0"], *sb["t0"], sa["t1"], *sb["t1"]]
    if (ka, kb) == ("moving_segment", "moving_segment"):
        return "edge_edge_ccd", [*sa["t0"], *sb["t0"], *sa["t1"], *sb["t1"]]
    raise ValueError(f"no ipctk method for {ka}-{kb}")


def to_format(hit, toi):
    if hit and not math.isfinite(toi):  # the protocol's form for a non-finite answer
        raise ValueError(f"non-finite toi: ipctk answered (hit {hit}, toi {toi!r})")
    return {"ccd": {"t": float(toi)} if hit else None}
# --- end of the convention translation ------------------------------------------


# --- the worker: ipctk's calls in a forked child, one case at a time ---------------
def worker_loop(method, rfd, wfd):
    """The worker's life: one call a line on `rfd` ([method name, 8 positions, tmax]),
    one line back on `wfd` ({"hit", "toi", "ns"} or {"exception": [type, text]})."""
    os.close(_PROTO_FD)  # the protocol is the parent's alone
    import resource
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))  # a crash leaves no core file
    ccd = METHODS[method]()
    with os.fdopen(rfd, "rb") as calls:
        for line in calls:
            try:
                name, points, tmax = json.loads(line)
                args = [np.array(p, dtype=np.float64) for p in points]
                fn = getattr(ccd, name)
                start = time.perf_counter_ns()
                hit, toi = fn(*args, MIN_DISTANCE, tmax)
                ns = time.perf_counter_ns() - start
                out = {"hit": bool(hit), "toi": float(toi), "ns": ns}
            except Exception as exc:
                out = {"exception": [type(exc).__name__, str(exc)]}
            os.write(wfd, (json.dumps(out, allow_nan=True) + "\n").encode())


class Worker:
    """One forked worker: its pid, the write end of its call pipe, the read end of its
    answers and what has arrived of a line."""

    def __init__(self, method):
        to_r, to_w = os.pipe()
        from_r, from_w = os.pipe()
        pid = os.fork()
        if pid == 0:  # the worker: never returns
            status = 0
            try:
                os.close(to_w)
                os.close(from_r)
                worker_loop(method, to_r, from_w)
            except BaseException:
                status = 1
            finally:
                os._exit(status)
        os.close(to_r)
        os.close(from_w)
        self.pid, self.to_w, self.fd, self.buf = pid, to_w, from_r, b""

    def cpu(self):
        """The worker's CPU time so far (user + system), in s (/proc/PID/stat, in clock
        ticks: 10 ms here)."""
        with open(f"/proc/{self.pid}/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / _TICKS

    def call(self, line, cpu_budget, wall_budget):
        """Sends one call and waits for its line while the worker has used less than
        `cpu_budget` s of CPU on it and less than `wall_budget` s of wall time have
        passed: ("answer", obj), ("timeout", "CPU" or "wall") or ("gone", wait status)."""
        cpu0 = self.cpu()
        os.write(self.to_w, line)
        deadline = time.monotonic() + wall_budget
        while b"\n" not in self.buf:
            left = deadline - time.monotonic()
            if left <= 0:
                return ("timeout", "wall")
            if not select.select([self.fd], [], [], min(left, POLL))[0]:
                if self.cpu() - cpu0 >= cpu_budget:
                    return ("timeout", "CPU")
                continue
            chunk = os.read(self.fd, 65536)
            if not chunk:
                return ("gone", self.end(kill=False))
            self.buf += chunk
        done, self.buf = self.buf.split(b"\n", 1)
        return ("answer", json.loads(done))

    def end(self, kill):
        """Ends the worker (SIGKILL first when `kill`) and returns its wait status."""
        if kill:
            os.kill(self.pid, signal.SIGKILL)
        os.close(self.to_w)
        os.close(self.fd)
        return os.waitpid(self.pid, 0)[1]


class EngineFailure(Exception):
    """ipctk crashed, or did not answer within the budget."""


_worker = None
_batch = None  # {"start": monotonic s, "left": cases not yet answered}, set by `prepare`


def prepare(cases):
    """The start of a batch (crashtest_engine.serve's `prepare`): its clock and its count,
    for `budget`."""
    global _batch
    _batch = {"start": time.monotonic(), "left": len(cases)}


def wall_budget():
    """The wall time the next case may take: CASE_WALL, unless the batch's slow cases
    have spent so much of BATCH_BUDGET that what is left, less CASE_FLOOR for each case
    after this one, is less; never below CASE_FLOOR. A batch so takes at most about
    BATCH_BUDGET + CASE_FLOOR per case, within crashtest's time limit per batch (60 s by
    default), and one whose cases take µs, as nearly all do, is never cut short. (The
    case's own budget is CPU time, CASE_BUDGET: what the machine's load does not change.)"""
    if _batch is None:
        return CASE_WALL
    spent = time.monotonic() - _batch["start"]
    left = BATCH_BUDGET - spent - CASE_FLOOR * max(0, _batch["left"] - 1)
    return min(CASE_WALL, max(CASE_FLOOR, left))


def run(method, name, points, tmax):
    """One ipctk call in the worker (forked anew after a crash or a timeout): (hit, toi,
    ns) or an exception."""
    global _worker
    if _worker is None:
        _worker = Worker(method)
    line = (json.dumps([name, points, tmax], allow_nan=False) + "\n").encode()
    wall = wall_budget()
    if _batch is not None:
        _batch["left"] -= 1
    out = _worker.call(line, CASE_BUDGET, wall)
    if out[0] == "timeout":
        _worker.end(kill=True)
        _worker = None
        spent = f"{CASE_BUDGET:g} s of CPU time" if out[1] == "CPU" else f"{wall:g} s of wall time"
        raise EngineFailure(f"ipctk {name} did not answer within its budget, {spent} (the worker was "
                            "killed; README.md, \"Time\")")
    if out[0] == "gone":
        _worker = None
        status = out[1]
        if os.WIFSIGNALED(status):
            sig = os.WTERMSIG(status)
            raise EngineFailure(f"ipctk crashed (signal {sig}, {signal.Signals(sig).name}) in {name}")
        raise EngineFailure(f"the ipctk worker exited (status {os.waitstatus_to_exitcode(status)}) in {name}")
    res = out[1]
    if "exception" in res:
        raise type(res["exception"][0], (Exception,), {})(res["exception"][1])
    return res["hit"], res["toi"], res["ns"]


def handler(method):
    def ccd(case):
        name, points = arguments(case)
        hit, toi, ns = run(method, name, points, float(case.get("t_max", 1.0)))
        crashtest_engine._charged.append(float(ns))  # the method's own call, timed in the worker
        return to_format(hit, toi)
    return ccd


def main(argv):
    if len(argv) != 2 or argv[1] not in METHODS:
        print(f"usage: {argv[0]} {{{'|'.join(METHODS)}}}", file=sys.stderr)
        return 2
    method = argv[1]
    ipctk.set_logger_level(ipctk.LoggerLevel.error)
    ccd = METHODS[method]()  # for the provenance; the worker makes its own
    h = handler(method)
    handlers = {("ccd", "moving_point", "moving_triangle"): h,
                ("ccd", "moving_segment", "moving_segment"): h}
    return serve(f"ipctk/{method}", package_version("ipctk"), 53, handlers, provenance(method, ccd),
                 reproductions=reproductions(method, constructor(ccd), handlers), prepare=prepare)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
