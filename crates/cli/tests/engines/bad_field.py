#!/usr/bin/env python3
# Simulates an engine whose answer has a misspelt field: overlap answers say "overlapp" (contact answers are correct).
import os, sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scripted


def entry(case):
    if case["query"] == "overlap":
        return {"answer": {"overlapp": scripted.correct(case)["answer"]["overlap"]}}
    return scripted.correct(case)


for batch in scripted.batches("bad-field"):
    scripted.answer(batch, [entry(c) for c in batch["cases"]])
