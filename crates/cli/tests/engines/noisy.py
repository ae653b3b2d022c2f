#!/usr/bin/env python3
# Simulates an engine that writes a lot to standard error (1000 lines per batch) but answers correctly.
import os, sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scripted

for batch in scripted.batches("noisy"):
    for i in range(1000):
        sys.stderr.write("noise: batch %d, line %d of 1000\n" % (batch["id"], i + 1))
    sys.stderr.flush()
    scripted.answer_correctly(batch)
