"""What the scripted fault engines of this folder share (not a script: they import it).

The hello (CAPS: overlap aabb-aabb and contact sphere-sphere), correct answers to those
two queries, and the read loop of the protocol `crashtest-engine/1` (docs/PROTOCOL.md):
each script keeps only its own misbehaviour.
"""
import json, math, sys

CAPS = [{"query": "overlap", "a": "aabb", "b": "aabb"}, {"query": "contact", "a": "sphere", "b": "sphere"}]


def send(msg):
    sys.stdout.write(json.dumps(msg) + "\n")
    sys.stdout.flush()


def hello(name, protocol="crashtest-engine/1"):
    send({"type": "hello", "protocol": protocol, "name": name, "version": "1",
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


def batches(name, protocol="crashtest-engine/1"):
    """The main loop: answers each hello with `name`'s hello (saying `protocol`), yields each batch."""
    for msg in messages():
        if msg["type"] == "hello":
            hello(name, protocol)
        elif msg["type"] == "batch":
            yield msg


def answer(batch, entries):
    send({"type": "answers", "id": batch["id"], "answers": entries})


def answer_correctly(batch):
    answer(batch, [correct(c) for c in batch["cases"]])
