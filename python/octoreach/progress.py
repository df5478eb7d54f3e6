"""A small terminal progress bar for long C++ builds (no extra dependency)."""
from __future__ import annotations

import sys
import time


class ProgressBar:
    """Callable (done, total) -> True that draws a bar on stderr; pass it as `progress=`."""

    def __init__(self, label: str, enabled: bool = True, stream=None, min_interval: float = 0.1):
        self.label = label
        self.enabled = enabled
        self.stream = stream or sys.stderr
        self.min_interval = min_interval
        self._start = time.perf_counter()
        self._last = 0.0
        self._finished = False

    def __call__(self, done: int, total: int) -> bool:
        if not self.enabled or self._finished:
            return True
        now = time.perf_counter()
        if done < total and now - self._last < self.min_interval:
            return True
        self._last = now
        frac = done / total if total else 1.0
        width = 30
        filled = int(round(width * frac))
        elapsed = now - self._start
        eta = elapsed / frac - elapsed if frac > 0 else float("nan")
        bar = "#" * filled + "-" * (width - filled)
        self.stream.write(f"\r{self.label} [{bar}] {100 * frac:5.1f}% {elapsed:6.1f}s eta {eta:5.1f}s")
        if done >= total:
            self.stream.write("\n")
            self._finished = True
        self.stream.flush()
        return True


def make_progress(progress, label: str):
    """Turns the `progress` argument of a build (True, False, None or a callable) into a callback or None."""
    if progress is True:
        return ProgressBar(label)
    if progress in (False, None):
        return None
    if callable(progress):
        return progress
    raise TypeError(f"progress must be True, False or a callable (done, total), got {progress!r}")
