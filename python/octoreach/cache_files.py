"""The files of a map cache folder, below the cache's logic (octoreach.cache): a map's bytes made in a private
folder, entries written through the one Python writer, notes read within bounds, and the per-key lock file
(flock; a lock file its holder removed while others waited is given up for a fresh one, never followed as a
link).
"""
from __future__ import annotations

import json
import os
import stat
import tempfile
from pathlib import Path

from ._core import CapabilityMap
from .atomic_write import write_atomically

_NOTE_BYTES = 1 << 20  # a note is a few hundred bytes; a larger one is not the cache's


def map_bytes(m, with_solutions: bool = False) -> bytes:
    """The file bytes of a map, written by its own save into a private temporary folder (mode 0700: nothing
    another user plants can redirect that write) and read back."""
    with tempfile.TemporaryDirectory(prefix="octoreach-") as d:
        path = os.path.join(d, "map")
        if isinstance(m, CapabilityMap):
            m.save(path, with_solutions=with_solutions)
        else:
            m.save(path)
        with open(path, "rb") as f:
            return f.read()


def save_entry(m, path: str) -> None:
    """A map saved as a cache entry: its bytes made in a private folder, then the one Python writer (an exclusive
    temporary file in the cache folder, renamed), so that no name planted in a shared folder redirects it."""
    write_atomically(path, map_bytes(m, with_solutions=getattr(m, "has_solutions", False)), "map cache entry")


def regular(path: Path) -> bool:
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False


def read_note(path: Path, kind: str, key: str) -> dict | None:
    """The note of an entry when it is a regular file holding a JSON object of that kind and key, else None."""
    from .data_files import read_bytes

    try:
        if not regular(path):
            return None
        note = json.loads(read_bytes(path, "cache note", _NOTE_BYTES))
    except (OSError, ValueError, RecursionError):
        return None
    if not isinstance(note, dict) or note.get("kind") != kind or note.get("key") != key or \
            not isinstance(note.get("fields"), dict):
        return None
    return note


def acquire(path: Path) -> int | None:
    """A descriptor of `path` holding its exclusive flock, or None when it cannot be taken (a link, a special
    file, no permission). A lock file its holder removed while we waited is given up for a fresh one."""
    import fcntl

    for _ in range(100):
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0),
                         0o666)
        except OSError:
            return None
        try:
            st = os.fstat(fd)
            if not stat.S_ISREG(st.st_mode):
                os.close(fd)
                return None
            fcntl.flock(fd, fcntl.LOCK_EX)
            now = os.stat(path, follow_symlinks=False)
            if (now.st_ino, now.st_dev) == (st.st_ino, st.st_dev):
                return fd
        except OSError:
            pass
        os.close(fd)
    return None
