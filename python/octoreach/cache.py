"""The map cache: a map is identified by a content key and looked up before it is built.

The key of a capability map is a SHA-256 of what decides its bytes: the robot's model hash (URDF and
allowed-collision matrix), the arm (base link, tip link, approach axis), every CapabilityMapOptions
field but ``threads`` (which never changes a map), the map file format version and the library version.
Same key, same bytes: builds are deterministic and map files hold no timing.

The cache directory is ``cache_dir=`` when given, else ``$OCTOREACH_CACHE_DIR``, else
``$XDG_CACHE_HOME/octoreach/maps`` (``~/.cache/octoreach/maps``). Entries are ``<kind>-<key>.<ext>`` with
a ``.json`` note beside (robot, arm, options; what ``octoreach cache list`` prints) and a marker file
``.octoreach-cache`` in the folder. Several processes may share a directory: a builder holds an exclusive
lock on ``<key>.lock`` (others wait, then load its entry; the builder removes the lock file when done), and
every file is written to a temporary file created exclusively and renamed into place, so a reader sees a
whole entry or none and a name planted in the folder cannot redirect a write.

An entry is used only when it is a regular file (not a symbolic link), loads (map files carry a CRC-32),
holds the very bytes its note records (the note names the entry's kind and key and holds the SHA-256 of its
bytes; it is written before the entry, so a reader never meets an entry before its note) and agrees with its
key: the map's header names the key's robot model, arm and every build option it records, and a capability
map's stored joint solutions reach their voxels (``octoreach.cache_check``). Any other entry is reported,
deleted and rebuilt, never used. The digest catches what a header cannot: an entry copied from another key
whose header reads the same (a surface map built with other obstacles around its surface, a capability map
of options its header does not record) and any byte changed in a header or payload. What no check here
catches is a writer of the folder who plants a self-consistent map and rewrites its note to match: a shared
cache is as trustworthy as everyone who can write to its folder. A directory that cannot be written, or an
entry that cannot be stored (a full disk): maps are built anyway and returned, with a warning.
``clear()`` deletes only what the cache wrote: files with its own names in a folder that has its marker.
"""
from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import re
import stat
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from . import cache_check, map_files
from .cache_files import acquire, digest, entry_bytes, fd_digest, note_disagrees, read_note, regular
from ._core import Arm, CapabilityMap, CapabilityMapOptions, Robot, __version__, map_format_version
from .atomic_write import check_target, write_atomically

ENV_DIR = "OCTOREACH_CACHE_DIR"
MARKER = ".octoreach-cache"
_EXT = map_files.kinds()  # {kind: file extension} of every map kind (the C++ registry)
# What the cache writes: entries and notes, locks, and the temporary files of both (<name>.tmp.<anything>).
_OWN = re.compile(r"((%s)-[0-9a-f]{40}(%s|\.json)|[0-9a-f]{40}\.lock)(\.tmp\..+)?" % (
    "|".join(map(re.escape, _EXT)), "|".join(map(re.escape, _EXT.values()))))
_warned: set[str] = set()  # directories already warned about


def default_dir() -> Path:
    """$OCTOREACH_CACHE_DIR, else $XDG_CACHE_HOME/octoreach/maps, else ~/.cache/octoreach/maps."""
    if os.environ.get(ENV_DIR):
        return Path(os.environ[ENV_DIR])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "octoreach" / "maps"


def _plain(value):
    """A JSON-able, exact form of an option value (floats by repr through json, arrays as lists)."""
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in sorted(value.items())}
    if isinstance(value, (np.floating, np.integer, np.bool_)):
        return value.item()
    return value


def options_fields(options) -> dict:
    """Every public field of a bound options object (CapabilityMapOptions, SurfaceMapOptions), as plain values."""
    out = {}
    for name in dir(options):
        if name.startswith("_"):
            continue
        value = getattr(options, name)
        if callable(value):
            continue
        out[name] = _plain(value)
    return out


def capability_options(options=None, **kwargs) -> CapabilityMapOptions:
    """A fresh CapabilityMapOptions: the C++ defaults, the fields of `options`, then the keywords."""
    o = CapabilityMapOptions()
    items = list(options_fields(options).items()) if options is not None else []
    for name, value in items + list(kwargs.items()):
        if name.startswith("_") or not hasattr(o, name) or callable(getattr(o, name)):
            raise TypeError(f"unknown capability map option {name!r}")
        try:
            setattr(o, name, value)
        except TypeError:
            raise TypeError(f"capability map option {name!r} must be of the type of its default "
                            f"({type(getattr(o, name)).__name__}), got {type(value).__name__}") from None
    return o


def arm_fields(arm: Arm) -> dict:
    return {"base_link": arm.base_link, "tip_link": arm.tip_link, "approach_axis": _plain(np.asarray(arm.approach_axis))}


def capability_key_fields(robot: Robot, arm: Arm, options: CapabilityMapOptions) -> dict:
    """What decides a capability map's bytes (the options' approach axis is the arm's, threads never matter)."""
    fields = options_fields(options)
    for ignored in ("threads", "approach_axis"):
        fields.pop(ignored, None)
    if not fields.get("poles"):  # off: the keys of maps without poles stay what they were
        fields.pop("poles", None)
    return {"kind": "capability", "robot": robot.name, "model_hash": int(robot.model_hash), "arm": arm_fields(arm),
            "options": fields}


def key_of(fields: dict) -> str:
    """The content key of a map: SHA-256 of its key fields, the file format version and the library version."""
    text = json.dumps({"fields": _plain(fields), "format": map_format_version(), "octoreach": __version__},
                      sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:40]


class MapCache:
    """A cache directory of maps by content key (see the module docstring). ``hits``, ``builds``,
    ``rebuilt_damaged`` (entries that did not load or were not regular files) and ``rebuilt_mismatched``
    (entries that disagreed with their key) count what happened in this object's life."""

    def __init__(self, directory: str | os.PathLike | None = None):
        self.directory = Path(directory) if directory is not None else default_dir()
        self.hits = 0
        self.builds = 0
        self.rebuilt_damaged = 0
        self.rebuilt_mismatched = 0

    def __repr__(self) -> str:
        return f"<octoreach.MapCache {str(self.directory)!r}>"

    # ------------------------------------------------------------------ entries
    def path(self, kind: str, key: str) -> Path:
        return self.directory / f"{kind}-{key}{_EXT[kind]}"

    def _warn_once(self, problem: str) -> None:
        where = str(self.directory)
        if where not in _warned:
            _warned.add(where)
            warnings.warn(f"map cache {where!r} {problem}: building without the cache", RuntimeWarning, stacklevel=4)

    def writable(self) -> bool:
        """True when entries can be stored (the directory exists or can be made, takes files and holds the
        cache's marker); else warns once."""
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            probe = tempfile.NamedTemporaryFile(dir=self.directory, prefix=".probe.", delete=True)
            probe.close()
            if not os.path.lexists(self.directory / MARKER):
                write_atomically(self.directory / MARKER, "octoreach map cache: `octoreach cache clear` deletes the "
                                 "files named <kind>-<key>.<ext> and <key>.lock here, nothing else\n", "cache marker")
            return True
        except OSError as e:
            self._warn_once(f"is not writable ({e.strerror or e})")
            return False

    @contextlib.contextmanager
    def _lock(self, key: str):
        """Exclusive lock of one key across processes (flock on <key>.lock, removed by its holder when done);
        no lock where it cannot be taken (the entry is checked on load all the same)."""
        path = self.directory / f"{key}.lock"
        fd = acquire(path)
        try:
            yield
        finally:
            if fd is not None:
                with contextlib.suppress(OSError):
                    os.unlink(path)  # waiters holding the old file notice (_acquire) and take a new one
                os.close(fd)

    def _discard(self, path: Path, problem: str, counter: str) -> None:
        warnings.warn(f"map cache entry {path.name} {problem}: deleting and rebuilding it", RuntimeWarning,
                      stacklevel=5)
        setattr(self, counter, getattr(self, counter) + 1)
        with contextlib.suppress(OSError):
            path.unlink()

    def _load(self, kind: str, key: str, verify=None, with_bytes: bool = False):
        """The entry's map (and its bytes), None when absent. An entry that is not a regular file, does not load,
        differs from the digest its note records or disagrees with its key (verify(map) -> None or the
        disagreement) is reported, deleted and counted."""
        path = self.path(kind, key)
        try:
            fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
        except OSError as e:
            if e.errno in (errno.ENOENT, errno.ENOTDIR):
                return None
            if os.path.islink(path):
                self._discard(path, "is a symbolic link", "rebuilt_damaged")
            else:
                self._discard(path, f"cannot be opened ({e.strerror})", "rebuilt_damaged")
            return None
        try:
            mode = os.fstat(fd).st_mode
            if not stat.S_ISREG(mode):
                from .data_files import file_kind

                self._discard(path, f"is {file_kind(mode)}, not a regular file", "rebuilt_damaged")
                return None
            via = f"/proc/self/fd/{fd}"  # the file opened and checked above, whatever the name points to now
            source = via if os.path.exists(via) else str(path)
            try:
                m = map_files.load(source, kind)  # OSError unless it holds a whole map of that kind
            except OSError as e:
                self._discard(path, f"is damaged ({str(e).replace(via, path.name)})", "rebuilt_damaged")
                return None
            found, data = fd_digest(fd, keep=with_bytes)  # the bytes just loaded, through the same descriptor
            problem = note_disagrees(read_note(self.directory / f"{kind}-{key}.json", kind, key), found)
            if problem:
                self._discard(path, problem, "rebuilt_mismatched")
                return None
            try:
                problem = verify(m) if verify is not None else None
            except (ValueError, TypeError, RuntimeError, LookupError) as e:  # a header the checks cannot even use
                problem = f"it cannot be checked: {' '.join(str(e).split())[:200]}"
            if problem:
                self._discard(path, f"does not match its key ({problem})", "rebuilt_mismatched")
                return None
            return (m, data) if with_bytes else m
        finally:
            os.close(fd)

    def lookup(self, kind: str, fields: dict, verify=None):
        """The cached map of these key fields, or None (an entry that is damaged or disagrees with `verify` is
        deleted)."""
        m = self._load(kind, key_of(fields), verify)
        if m is not None:
            self.hits += 1
        return m

    def lookup_bytes(self, kind: str, fields: dict, verify=None) -> bytes | None:
        """The bytes of the cached map of these key fields, the very bytes that were loaded and checked, or None."""
        found = self._load(kind, key_of(fields), verify, with_bytes=True)
        if found is None:
            return None
        self.hits += 1
        return found[1]

    def _note(self, kind: str, key: str, fields: dict, data: bytes) -> Path:
        note = {"kind": kind, "key": key, "fields": _plain(fields), "sha256": digest(data), "bytes": len(data),
                "octoreach": __version__, "format": map_format_version(),
                "created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
        return write_atomically(self.directory / f"{kind}-{key}.json", json.dumps(note, indent=1), "cache note")

    def _stored(self, kind: str, key: str, fields: dict, make) -> bool:
        """The entry's bytes from make(), its note (with their digest), then the entry; False with a warning when
        they cannot be made or written (a full disk)."""
        path = self.path(kind, key)
        note = path.with_suffix(".json")
        try:
            check_target(path, "map cache entry")
            data = make()
            self._note(kind, key, fields, data)
            write_atomically(path, data, "map cache entry")
            return True
        except OSError as e:
            warnings.warn(f"map cache {str(self.directory)!r}: cannot store {path.name} ({e}): the map is built and "
                          "used without the cache", RuntimeWarning, stacklevel=4)
            with contextlib.suppress(OSError):
                if not os.path.lexists(path) and os.path.isfile(note) and not os.path.islink(note):
                    note.unlink()  # a note without its entry describes nothing
            return False

    def store_bytes(self, kind: str, fields: dict, data: bytes) -> bool:
        """Stores a map file's bytes under its key (atomic rename); False when it cannot be stored (warned)."""
        if not self.writable():
            return False
        return self._stored(kind, key_of(fields), fields, lambda: data)

    def get_or_build(self, kind: str, fields: dict, build, to_bytes=entry_bytes, verify=None):
        """The cached map of these key fields (checked by verify(map) -> None or a disagreement), else build()
        stored as the file bytes to_bytes(map); a map that cannot be stored is returned all the same. One
        process builds a key at a time; the others wait for it and load its entry."""
        m = self.lookup(kind, fields, verify)
        if m is not None:
            return m
        if not self.writable():
            self.builds += 1
            return build()
        key = key_of(fields)
        with self._lock(key):
            m = self._load(kind, key, verify)  # another process may have built it while we waited
            if m is not None:
                self.hits += 1
                return m
            m = build()
            self.builds += 1
            self._stored(kind, key, fields, lambda: to_bytes(m))
        return m

    # ------------------------------------------------------------------ maps
    def capability_map(self, robot: Robot, arm, options=None, progress=True, approach_axis=None,
                       **kwargs) -> CapabilityMap:
        """The capability map of an arm (name, Arm or tuple) from the cache, built and stored on a miss;
        keywords set CapabilityMapOptions fields as in arms.capability_map."""
        a = Arm.resolve(robot, arm, approach_axis=approach_axis)
        o = capability_options(options, **kwargs)
        fields = capability_key_fields(robot, a, o)
        return self.get_or_build("capability", fields,
                                 lambda: CapabilityMap.build_for_arm(robot, a, o, progress=progress),
                                 entry_bytes,
                                 lambda m: cache_check.capability_mismatch(m, fields, robot))

    # ------------------------------------------------------------------ listing
    def entries(self) -> list[dict]:
        """One dict per map entry: kind, key, file, bytes, and from its note (when it has a readable one) created
        and the key fields (robot, arm, options...); "note": "missing or damaged" otherwise."""
        out = []
        if not self.directory.is_dir():
            return out
        for path in sorted(self.directory.iterdir()):
            m = _OWN.fullmatch(path.name)
            if not m or m.group(4) or m.group(3) in (None, ".json") or not regular(path):
                continue
            kind, key = m.group(2), path.name.split("-", 1)[1].split(".")[0]
            info = {"kind": kind, "key": key, "file": str(path), "bytes": path.stat().st_size}
            note = read_note(self.directory / f"{kind}-{key}.json", kind, key)
            out.append({**note, **info} if note else {**info, "note": "missing or damaged", "fields": {}})
        return out

    def clear(self) -> int:
        """Deletes what the cache wrote (maps, notes, locks, leftover temporary files) and nothing else; returns
        the number of maps deleted. A folder without the cache's marker: ValueError, nothing deleted."""
        if not self.directory.is_dir():
            return 0
        if not regular(self.directory / MARKER):
            raise ValueError(f"{str(self.directory)!r} is not an octoreach map cache (it has no {MARKER} file): "
                             "nothing deleted")
        maps = 0
        for path in self.directory.iterdir():
            m = _OWN.fullmatch(path.name)
            if not m or os.path.isdir(path) and not os.path.islink(path):
                continue
            with contextlib.suppress(OSError):
                path.unlink()
                maps += m.group(3) in _EXT.values() and not m.group(4)
        return maps


def resolve(cache) -> MapCache | None:
    """The MapCache of a `cache` argument: None/False (no cache), True (the default directory), a path or a MapCache."""
    if cache is None or cache is False:
        return None
    if cache is True:
        return MapCache()
    if isinstance(cache, MapCache):
        return cache
    if isinstance(cache, (str, os.PathLike)):
        return MapCache(cache)
    raise TypeError(f"cache must be True, False, a directory or a MapCache, got {type(cache).__name__}")
