"""A short seeded run of the file-damage fuzzer (tests/fuzz/file_fuzz.py; `make fuzz` runs a long one):
every damaged, forged or foreign file either loads (and works) or raises OSError; no crash, no hang."""
from __future__ import annotations

import os

from file_fuzz import fuzz


def test_damaged_files_never_crash_hang_or_raise_the_wrong_error(tmp_path):
    n = int(os.environ.get("OCTOREACH_FUZZ_FILE_CASES", "240"))
    results, summary = fuzz(n, seed=12, workdir=tmp_path)
    bad = [(r["category"], r["outcome"]) for r in results if r["outcome"].startswith(("crash", "hang", "wrong"))]
    print(summary)
    assert not bad, bad[:20]
    total = summary["total"]
    assert total["cases"] == n
    assert total.get("oserror", 0) > n // 3  # the damage is mostly caught, not silently accepted
