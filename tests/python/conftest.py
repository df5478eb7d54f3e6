"""Shared fixtures of the Python tests: robots and chains (pose helpers: pose_helpers.py)."""
from __future__ import annotations

import atexit
import os
import shutil
import tempfile

import pytest

# The CLI looks maps up in the map cache: the tests keep theirs out of the user's cache directory, in a
# folder of their own that goes when the test run ends.
if "OCTOREACH_CACHE_DIR" not in os.environ:
    os.environ["OCTOREACH_CACHE_DIR"] = tempfile.mkdtemp(prefix="octoreach-test-cache-")
    atexit.register(shutil.rmtree, os.environ["OCTOREACH_CACHE_DIR"], ignore_errors=True)

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
