#!/usr/bin/env python3
# Simulates an engine that crashes: answers its first batch, then exits with status 3 mid-batch on its second.
import json, math, sys, time

CAPS = [{"query": "overlap", "a": "aabb", "b": "aabb"}, {"query": "contact", "a": "sphere", "b": "sphere"}]


def send(msg):
    sys.stdout.write(json.dumps(msg) + "\n")
    sys.stdout.flush()


def hello(protocol="crashtest-engine/1"):
    send({"type": "hello", "protocol": protocol, "name": "exits-mid-batch", "version": "1",
          "precision": 53, "capabilities": CAPS})


def correct(case):
    """A correct entry for an overlap aabb-aabb or contact sphere-sphere case."""
    a, b = case["a"], case["b"]
    if case["query"] == "overlap":
        A, B = a["aabb"], b["aabb"]
        return {"answer": {"overlap": all(A["min"][i] <= B["max"][i] and B["min"][i] <= A["max"][i] for i in range(3))}}
    A, B = a["sphere"], b["sphere"]
    w = [A["center"][i] - B["center"][i] for i in range(3)]
    d = math.sqrt(sum(x * x for x in w))
    if d > A["radius"] + B["radius"]:
        return {"answer": {"contact": None}}
    n = [0.0, 0.0, 1.0] if d == 0 else [x / d for x in w]  # concentric: fallback normal +z
    point = [B["center"][i] + B["radius"] * n[i] for i in range(3)]
    answer = {"contact": {"point": point, "normal": n, "depth": A["radius"] + B["radius"] - d}}
    return {"answer": dict(answer, degenerate=True) if d == 0 else answer}


def messages():
    """The messages crashtest sends, until shutdown or end of input (then exit 0)."""
    for line in sys.stdin:
        if not line.strip():
            continue
        msg = json.loads(line)
        if msg.get("type") == "shutdown":
            sys.exit(0)
        yield msg
    sys.exit(0)


batches = 0
for msg in messages():
    if msg["type"] == "hello":
        hello()
    elif msg["type"] == "batch":
        batches += 1
        if batches == 2:
            sys.stderr.write("fatal: simulated crash\n")
            sys.stderr.flush()
            sys.exit(3)
        send({"type": "answers", "id": msg["id"], "answers": [correct(c) for c in msg["cases"]]})
