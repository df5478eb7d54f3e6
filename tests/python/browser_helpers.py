"""Helpers of the viewer tests in a headless browser: a free port, and the page's pixels once they change."""
from __future__ import annotations

import socket
import time

import numpy as np


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def changed(browser, before: np.ndarray, timeout: float = 10.0) -> np.ndarray:
    """The page's pixels once they differ from `before` (and have settled)."""
    t_end = time.time() + timeout
    while time.time() < t_end:
        time.sleep(0.2)
        px = browser.pixels()
        if np.abs(px.astype(int) - before).mean() > 0.01:
            time.sleep(0.3)
            return browser.pixels()
    raise AssertionError("the page did not change")
