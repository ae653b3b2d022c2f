#!/usr/bin/env python3
# Simulates an engine whose reply is not JSON: every batch is answered with a truncated line.
import os, sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scripted

for batch in scripted.batches("malformed"):
    sys.stdout.write('{"type":"answers","id":%d,"answers":[\n' % batch["id"])
    sys.stdout.flush()
