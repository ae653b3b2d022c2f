#!/usr/bin/env python3
# An engine whose every normal is k times too long, all else right: it passes each message to
# an engine it starts (argv[2:], speaking crashtest-engine/1) and multiplies by k (argv[1]) every
# `normal` in the answers (contact, hit, time of impact), its hello renamed "scaled normals".
import json, subprocess, sys

k = float(sys.argv[1])
inner = subprocess.Popen(sys.argv[2:], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)


def scaled(answer):
    for key in ("contact", "hit", "toi"):
        inside = answer.get(key)
        if isinstance(inside, dict) and "normal" in inside:
            inside["normal"] = [x * k for x in inside["normal"]]
    return answer


for line in sys.stdin:
    if not line.strip():
        continue
    inner.stdin.write(line if line.endswith("\n") else line + "\n")
    inner.stdin.flush()
    if json.loads(line).get("type") == "shutdown":
        break
    reply = json.loads(inner.stdout.readline())
    if reply.get("type") == "hello":
        reply["name"] = "scaled normals"
    for entry in reply.get("answers", []):
        if isinstance(entry.get("answer"), dict):
            scaled(entry["answer"])
    sys.stdout.write(json.dumps(reply) + "\n")
    sys.stdout.flush()
inner.stdin.close()
sys.exit(inner.wait())
