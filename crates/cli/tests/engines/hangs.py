#!/usr/bin/env python3
# Simulates an engine that hangs: never answers a batch holding a case whose name contains "hang".
import os, sys, time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scripted

for batch in scripted.batches("hangs"):
    if any("hang" in c["name"] for c in batch["cases"]):
        time.sleep(3600)
    scripted.answer_correctly(batch)
