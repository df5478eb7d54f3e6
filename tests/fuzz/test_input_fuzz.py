"""A short seeded run of the input-file fuzzer (tests/fuzz/input_fuzz.py; `make fuzz` runs a long one): every
room, job and polygon file, however broken, is accepted or refused with a clean one-paragraph error; no
traceback, hang, memory blow-up or crash."""
from __future__ import annotations

import os

from input_fuzz import BAD, KINDS, fuzz


def test_broken_input_files_give_clean_errors(tmp_path):
    n = int(os.environ.get("OCTOREACH_FUZZ_INPUT_CASES", "144"))
    results, summary = fuzz(n, seed=11, workdir=tmp_path)
    bad = [(r["category"], r["outcome"]) for r in results if r["outcome"].startswith(BAD)]
    print(summary["total"])
    assert not bad, bad[:20]
    total = summary["total"]
    assert total["cases"] == n
    assert total.get("accepted", 0) >= n // 20 and total.get("clean", 0) > n // 2  # valid files load, broken ones don't
    assert {r["category"].split("/")[0] for r in results} == set(KINDS)
