#!/usr/bin/env python3
# Simulates an engine speaking another protocol: its hello says crashtest-engine/99.
import os, sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scripted

for batch in scripted.batches("bad-hello", protocol="crashtest-engine/99"):
    scripted.answer_correctly(batch)
