"""A benchmark's run of itself in a child process, under this octoreach or under another build's.

The benchmarks that compare two builds (--reference DIR) time each in its own process, alternating, so both see
the machine in the same state. A child prints its figures as one JSON object; where that object names the
package it imported ("octoreach": the package's directory), the run is checked to have imported the build asked
for, since an editable install's finder or a stale PYTHONPATH would otherwise time the wrong one unnoticed.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

import octoreach


class ChildFailed(RuntimeError):
    """A child run failed, or imported another octoreach than the one asked for (the message says which)."""


def this_build() -> str:
    """The directory that holds the octoreach package this process imported (a PYTHONPATH entry for it)."""
    return os.path.dirname(os.path.dirname(os.path.abspath(octoreach.__file__)))


def run_child(script: str, args: list, pythonpath: str = "") -> dict:
    """`script args` in a child process (pythonpath, one directory or a PYTHONPATH-style list, before the
    inherited PYTHONPATH, when given); the JSON it prints."""
    env = dict(os.environ)
    roots = [os.path.abspath(p) for p in pythonpath.split(os.pathsep) if p]
    if roots:
        env["PYTHONPATH"] = os.pathsep.join(p for p in (*roots, env.get("PYTHONPATH", "")) if p)
    cmd = [sys.executable, os.path.abspath(script), *map(str, args)]
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, check=False)
    where = f" under PYTHONPATH={os.pathsep.join(roots)}" if roots else ""
    if done.returncode != 0:
        raise ChildFailed(f"{os.path.basename(script)} {' '.join(map(str, args))}{where} failed:\n"
                          f"{done.stderr[-2000:]}")
    out = json.loads(done.stdout)
    got = out.get("octoreach") if isinstance(out, dict) else None
    if roots and isinstance(got, str) and os.path.isabs(got) and \
            not any(os.path.abspath(got).startswith(r + os.sep) for r in roots):
        raise ChildFailed(f"{os.path.basename(script)}{where} imported octoreach from {got}, not from there "
                          "(an editable install's finder comes first?)")
    return out
