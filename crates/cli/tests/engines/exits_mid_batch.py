#!/usr/bin/env python3
# Simulates an engine that crashes: answers its first batch, then exits with status 3 mid-batch on its second.
import os, sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scripted

for n, batch in enumerate(scripted.batches("exits-mid-batch"), 1):
    if n == 2:
        sys.stderr.write("fatal: simulated crash\n")
        sys.stderr.flush()
        sys.exit(3)
    scripted.answer_correctly(batch)
