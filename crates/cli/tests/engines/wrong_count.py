#!/usr/bin/env python3
# Simulates an engine that answers one case fewer than the batch holds.
import os, sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scripted

for batch in scripted.batches("wrong-count"):
    scripted.answer(batch, [scripted.correct(c) for c in batch["cases"][1:]])
