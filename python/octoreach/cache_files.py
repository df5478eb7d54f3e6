"""The files of a map cache folder, below the cache's logic (octoreach.cache): a map's bytes made in a private
folder, the SHA-256 digest of an open entry (read in chunks: memory stays bounded whatever its size), notes
read within bounds, and the per-key lock file (flock; a lock file its holder removed while others waited is
given up for a fresh one, never followed as a link).
"""
from __future__ import annotations

import hashlib
import json
import os
import stat
import tempfile
from pathlib import Path

from ._core import CapabilityMap

_NOTE_BYTES = 1 << 20  # a note is a few hundred bytes; a larger one is not the cache's
_CHUNK = 1 << 20


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


def entry_bytes(m) -> bytes:
    """The bytes of a map as a cache entry (with its joint solutions when it has them), made in a private folder:
    the cache writes them through the one Python writer, so no name planted in a shared folder redirects it."""
    return map_bytes(m, with_solutions=getattr(m, "has_solutions", False))


def digest(data: bytes) -> str:
    """The digest a note records of its entry's bytes: SHA-256, hexadecimal."""
    return hashlib.sha256(data).hexdigest()


def fd_digest(fd: int, keep: bool = False) -> tuple[str, bytes | None]:
    """(digest, bytes or None) of the whole file open at `fd`, read from its start in 1 MiB chunks; its bytes are
    kept only when asked for (what is hashed is what the caller gets)."""
    h = hashlib.sha256()
    parts = []
    pos = 0
    while True:
        chunk = os.pread(fd, _CHUNK, pos)
        if not chunk:
            break
        h.update(chunk)
        pos += len(chunk)
        if keep:
            parts.append(chunk)
    return h.hexdigest(), b"".join(parts) if keep else None


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


def note_disagrees(note: dict | None, found: str) -> str | None:
    """None when a note (read_note) records the digest `found` of its entry's bytes, else what is wrong."""
    if note is None:
        return "has no note of its key"
    if "sha256" not in note:
        return "has a note without its digest"
    if note["sha256"] != found:
        return "is not the entry its note records (its SHA-256 differs: another key's entry or altered bytes)"
    return None


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
