"""Steps worlds badly, one fault per bounce world: a reply with too few samples
(e = 0), its own error (e = 0.25), an exit mid-world (e = 0.5: the process is
restarted); every other world gets a well-formed reply whose spheres never move."""
import sys
from scripted import CAPS, answer, correct, messages, send

for msg in messages():
    if msg["type"] == "hello":
        send({"type": "hello", "protocol": "crashtest-engine/1", "name": "world-faults", "version": "1",
              "precision": 53, "capabilities": CAPS, "worlds": True, "provenance": {}})
    elif msg["type"] == "batch":
        answer(msg, [correct(c) for c in msg["cases"]])
    elif msg["type"] == "world":
        spheres = [b for b in msg["bodies"] if "sphere" in b]
        start = [b["sphere"]["center"] for b in spheres]
        reply = {"type": "world", "id": msg["id"], "positions": [start] * (int(msg["steps"]) + 1),
                 "velocities": [[0.0, 0.0, 0.0] for _ in spheres], "settings": {"motion": "none"}}
        if msg["name"] == "bounce, e = 0":
            reply["positions"] = [start]
        elif msg["name"] == "bounce, e = 0.25":
            reply = {"type": "world", "id": msg["id"], "error": "simulated solver failure"}
        elif msg["name"] == "bounce, e = 0.5":
            print("fatal: simulated crash in a world", file=sys.stderr)
            sys.exit(4)
        send(reply)
