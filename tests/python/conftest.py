"""Shared fixtures of the Python tests: robots and chains (pose helpers: pose_helpers.py)."""
from __future__ import annotations

import os
import tempfile

import pytest

# The CLI looks maps up in the map cache: the tests keep theirs out of the user's cache directory.
os.environ.setdefault("OCTOREACH_CACHE_DIR", tempfile.mkdtemp(prefix="octoreach-test-cache-"))

from octoreach import robots


@pytest.fixture
def arm():
    """A fresh test arm (tests may extend its allowed-collision matrix)."""
    return robots.test_arm()


@pytest.fixture
def arm_chain(arm):
    return arm.chain("base_link", "tool0")


def _load_pr2():
    try:
        return robots.pr2()
    except FileNotFoundError as e:  # example-robot-data is an optional extra ("robots")
        pytest.skip(f"PR2 model unavailable: {e}")


@pytest.fixture(scope="session")
def pr2():
    """One PR2 for read-only tests; tests that change the robot load their own with `fresh_pr2`."""
    return _load_pr2()


@pytest.fixture
def fresh_pr2():
    return _load_pr2
