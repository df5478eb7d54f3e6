"""The map cache: a map is identified by a content key and looked up before it is built.

The key of a capability map is a SHA-256 of what decides its bytes: the robot's model hash (URDF and
allowed-collision matrix), the arm (base link, tip link, approach axis), every CapabilityMapOptions
field but ``threads`` (which never changes a map), the map file format version and the library version.
Same key, same bytes: builds are deterministic and map files hold no timing.

The cache directory is ``cache_dir=`` when given, else ``$OCTOREACH_CACHE_DIR``, else
``$XDG_CACHE_HOME/octoreach/maps`` (``~/.cache/octoreach/maps``). Entries are ``<kind>-<key>.<ext>`` with
a ``.json`` note beside (robot, arm, options; what ``octoreach cache list`` prints). Several processes may
share a directory: a builder holds an exclusive lock on ``<key>.lock`` (others wait, then load its entry),
and every file is written to a temporary name and renamed into place, so a reader sees a whole entry or
none. An entry that does not load (checksum mismatch, truncation: map files carry a CRC-32) is reported,
deleted and rebuilt, never used. A directory that cannot be written: maps are built anyway, with one
warning per directory.
"""
from __future__ import annotations

import contextlib
import hashlib
import json
import os
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from . import map_files
from ._core import Arm, CapabilityMap, CapabilityMapOptions, Robot, __version__, map_format_version

ENV_DIR = "OCTOREACH_CACHE_DIR"
_EXT = map_files.kinds()  # {kind: file extension} of every map kind (the C++ registry)
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
    return {"kind": "capability", "robot": robot.name, "model_hash": int(robot.model_hash), "arm": arm_fields(arm),
            "options": fields}


def key_of(fields: dict) -> str:
    """The content key of a map: SHA-256 of its key fields, the file format version and the library version."""
    text = json.dumps({"fields": _plain(fields), "format": map_format_version(), "octoreach": __version__},
                      sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:40]


def write_atomically(path: Path, data: bytes) -> None:
    """Writes bytes to a temporary file beside `path`, flushes it to disk and renames it into place."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name + ".tmp.")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


class MapCache:
    """A cache directory of maps by content key (see the module docstring). ``hits``, ``builds`` and
    ``rebuilt_damaged`` count what happened in this object's life."""

    def __init__(self, directory: str | os.PathLike | None = None):
        self.directory = Path(directory) if directory is not None else default_dir()
        self.hits = 0
        self.builds = 0
        self.rebuilt_damaged = 0

    def __repr__(self) -> str:
        return f"<octoreach.MapCache {str(self.directory)!r}>"

    # ------------------------------------------------------------------ entries
    def path(self, kind: str, key: str) -> Path:
        return self.directory / f"{kind}-{key}{_EXT[kind]}"

    def writable(self) -> bool:
        """True when entries can be stored (the directory exists or can be made, and takes files); else warns once."""
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            probe = tempfile.NamedTemporaryFile(dir=self.directory, prefix=".probe.", delete=True)
            probe.close()
            return True
        except OSError as e:
            where = str(self.directory)
            if where not in _warned:
                _warned.add(where)
                warnings.warn(f"map cache {where!r} is not writable ({e.strerror or e}): building without the cache",
                              RuntimeWarning, stacklevel=3)
            return False

    @contextlib.contextmanager
    def _lock(self, key: str):
        """Exclusive lock of one key across processes (flock on <key>.lock); no lock where it cannot be taken."""
        import fcntl

        try:
            f = open(self.directory / f"{key}.lock", "a+")
        except OSError:
            yield
            return
        with f:
            fcntl.flock(f.fileno(), fcntl.LOCK_EX)
            try:
                yield
            finally:
                fcntl.flock(f.fileno(), fcntl.LOCK_UN)

    def _load(self, kind: str, key: str):
        """The entry's map, None when absent; a damaged entry is reported, deleted and counted."""
        path = self.path(kind, key)
        if not path.exists():
            return None
        try:
            return map_files.load(path, kind)  # OSError unless the entry holds a whole map of that kind
        except OSError as e:
            warnings.warn(f"map cache entry {path.name} is damaged ({e}): rebuilding it", RuntimeWarning, stacklevel=4)
            self.rebuilt_damaged += 1
            with contextlib.suppress(OSError):
                path.unlink()
            return None

    def lookup(self, kind: str, fields: dict):
        """The cached map of these key fields, or None (a damaged entry is deleted)."""
        m = self._load(kind, key_of(fields))
        if m is not None:
            self.hits += 1
        return m

    def lookup_bytes(self, kind: str, fields: dict) -> bytes | None:
        """The bytes of the cached map of these key fields (checked by loading it), or None."""
        key = key_of(fields)
        if self._load(kind, key) is None:
            return None
        try:
            data = self.path(kind, key).read_bytes()
        except OSError:
            return None
        self.hits += 1
        return data

    def _note(self, kind: str, key: str, fields: dict) -> None:
        note = {"kind": kind, "key": key, "fields": _plain(fields), "octoreach": __version__,
                "format": map_format_version(), "created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
        write_atomically(self.directory / f"{kind}-{key}.json", json.dumps(note, indent=1).encode())

    def store_bytes(self, kind: str, fields: dict, data: bytes) -> bool:
        """Stores a map file's bytes under its key (atomic rename); False when the directory is not writable."""
        if not self.writable():
            return False
        key = key_of(fields)
        write_atomically(self.path(kind, key), data)
        self._note(kind, key, fields)
        return True

    def get_or_build(self, kind: str, fields: dict, build, save):
        """The cached map of these key fields, else build() saved with save(map, path) and stored. One process
        builds a key at a time; the others wait for it and load its entry."""
        m = self.lookup(kind, fields)
        if m is not None:
            return m
        if not self.writable():
            self.builds += 1
            return build()
        key = key_of(fields)
        with self._lock(key):
            m = self._load(kind, key)  # another process may have built it while we waited
            if m is not None:
                self.hits += 1
                return m
            m = build()
            self.builds += 1
            save(m, str(self.path(kind, key)))  # the map's own atomic save (temporary file, fsync, rename)
            self._note(kind, key, fields)
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
                                 lambda m, path: m.save(path, with_solutions=m.has_solutions))

    # ------------------------------------------------------------------ listing
    def entries(self) -> list[dict]:
        """One dict per entry: kind, key, file, bytes, created and the key fields (robot, arm, options...)."""
        out = []
        if not self.directory.is_dir():
            return out
        for note in sorted(self.directory.glob("*.json")):
            try:
                info = json.loads(note.read_text())
                path = self.path(info["kind"], info["key"])
            except (OSError, ValueError, KeyError):
                continue
            if path.exists():
                out.append({**info, "file": str(path), "bytes": path.stat().st_size})
        return out

    def clear(self) -> int:
        """Deletes every entry (maps, notes, locks, leftover temporary files); returns the number of maps deleted."""
        if not self.directory.is_dir():
            return 0
        maps = 0
        for path in self.directory.iterdir():
            if path.suffix in (*_EXT.values(), ".json", ".lock") or ".tmp." in path.name:
                with contextlib.suppress(OSError):
                    path.unlink()
                    maps += path.suffix in _EXT.values()
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
