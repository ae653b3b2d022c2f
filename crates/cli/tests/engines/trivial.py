#!/usr/bin/env python3
# Simulates an engine that costs nothing: every case answered at once (overlap true, contact null, ns 0), to measure protocol overhead.
import os, sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scripted

TRIVIAL = {"overlap": {"answer": {"overlap": True}, "ns": 0}, "contact": {"answer": {"contact": None}, "ns": 0}}

for batch in scripted.batches("trivial"):
    scripted.answer(batch, [TRIVIAL[c["query"]] for c in batch["cases"]])
