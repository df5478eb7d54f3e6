"""Room, polygon and job files: JSON, or YAML where PyYAML is installed, read within the limits of
``octoreach.limits`` before anything is built from them.

* the path must name a regular file (not a FIFO, a device such as /dev/zero, or a folder), at most
  MAX_DATA_FILE_BYTES long: checked with fstat on the opened file, before reading (a FIFO is opened without
  blocking);
* the text is UTF-8;
* YAML (a file that is not JSON, of at most MAX_YAML_BYTES) is loaded safely (no Python objects) and its
  node graph is checked before anything is constructed:
  at most MAX_DATA_NODES nodes with every alias expanded (an alias bomb is refused, not built), at most
  MAX_DATA_ALIASES aliases, no alias inside the node it names (a recursive structure), nesting at most
  MAX_DATA_DEPTH; JSON's values and nesting likewise;
* a key given twice in one mapping is an error (JSON and YAML would keep the last one silently).

Every refusal is a ValueError (OSError for the file itself) naming the file and the limit.
"""
from __future__ import annotations

import json
import os
import stat
from pathlib import Path

from . import limits

_KINDS = {stat.S_IFIFO: "a FIFO", stat.S_IFCHR: "a character device", stat.S_IFBLK: "a block device",
          stat.S_IFSOCK: "a socket", stat.S_IFDIR: "a folder", stat.S_IFLNK: "a symbolic link"}


def file_kind(mode: int) -> str:
    """What a stat mode names, in words ("a FIFO", "a character device", ...; "a regular file")."""
    return "a regular file" if stat.S_ISREG(mode) else _KINDS.get(stat.S_IFMT(mode), "a special file")


def read_bytes(path, kind: str, limit: int = limits.MAX_DATA_FILE_BYTES,
               limit_name: str = "octoreach.limits.MAX_DATA_FILE_BYTES") -> bytes:
    """The bytes of a regular file of at most `limit` bytes (`limit_name` says where that limit is); OSError
    naming the file otherwise (checked before reading: a FIFO or /dev/zero is never read)."""
    from ._checks import PATH, check_type

    check_type(path, PATH, "path", "a file path (str or os.PathLike)")
    where = f"{kind} {str(path)!r}"
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as e:
        raise type(e)(e.errno, f"cannot read {where}: {e.strerror}") from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise OSError(f"cannot read {where}: it is {file_kind(st.st_mode)}, not a regular file")
        if st.st_size > limit:
            raise OSError(f"cannot read {where}: {st.st_size:,} bytes, more than the limit of {limit:,} "
                          f"({limit_name})")
        chunks, total = [], 0
        while True:
            try:
                chunk = os.read(fd, min(1 << 20, limit + 1 - total))
            except OSError as e:
                raise type(e)(e.errno, f"cannot read {where}: {e.strerror}") from None
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
            if total > limit:  # it grew while being read
                raise OSError(f"cannot read {where}: more than the limit of {limit:,} bytes")
        return b"".join(chunks)
    finally:
        os.close(fd)


def sha256_of(path, kind: str) -> str:
    """The SHA-256 (hex) of a regular file, read in chunks (a mesh or OctoMap a room names: part of a map's
    cache key); OSError for anything else (a FIFO or a device is never read)."""
    import hashlib

    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise OSError(f"{kind} {str(path)!r} is {file_kind(st.st_mode)}, not a regular file")
        h = hashlib.sha256()
        while chunk := os.read(fd, 1 << 20):
            h.update(chunk)
        return h.hexdigest()
    finally:
        os.close(fd)


class _Refused(ValueError):
    """A bound or a duplicate key: not a reason to try the other format."""


def _duplicates_refused(pairs):
    out = {}
    for key, value in pairs:
        if key in out:
            raise _Refused(f"the key {key!r} is given twice in one mapping")
        out[key] = value
    return out


def _check_json(data) -> None:
    """The nesting and value count of parsed JSON against the limits (JSON has no aliases: what it holds is
    what the file spells out)."""
    stack, count = [(data, 1)], 1
    while stack:
        node, depth = stack.pop()
        if depth > limits.MAX_DATA_DEPTH:
            raise _Refused(f"it nests deeper than {limits.MAX_DATA_DEPTH} levels (octoreach.limits.MAX_DATA_DEPTH)")
        children = node.values() if isinstance(node, dict) else node
        count += len(children) * (1 + isinstance(node, dict))  # a mapping's keys are values too
        if count > limits.MAX_DATA_NODES:
            raise _Refused(f"it holds more than {limits.MAX_DATA_NODES:,} values (octoreach.limits.MAX_DATA_NODES)")
        stack.extend((c, depth + 1) for c in children if isinstance(c, (dict, list)))


class _Graph:
    """The checks of a composed YAML node graph (see the module docstring), before construction."""

    MERGE = "tag:yaml.org,2002:merge"

    def __init__(self):
        self.seen: dict[int, tuple[int, int]] = {}  # id(node) -> (expanded nodes, height)
        self.path: set[int] = set()
        self.aliases = 0

    def check(self, node, depth: int = 1) -> tuple[int, int]:
        import yaml

        key = id(node)
        if key in self.seen:
            self.aliases += 1
            if self.aliases > limits.MAX_DATA_ALIASES:
                raise _Refused(f"it holds more than {limits.MAX_DATA_ALIASES:,} aliases "
                               "(octoreach.limits.MAX_DATA_ALIASES)")
            size, height = self.seen[key]
            if depth + height - 1 > limits.MAX_DATA_DEPTH:
                raise _Refused(f"it nests deeper than {limits.MAX_DATA_DEPTH} levels with its aliases expanded "
                               "(octoreach.limits.MAX_DATA_DEPTH)")
            return size, height
        if key in self.path:
            raise _Refused("an alias refers to a node that holds it (a recursive structure), line "
                           f"{node.start_mark.line + 1}")
        if depth > limits.MAX_DATA_DEPTH:
            raise _Refused(f"it nests deeper than {limits.MAX_DATA_DEPTH} levels (octoreach.limits.MAX_DATA_DEPTH)")
        size, height = 1, 1
        if not isinstance(node, yaml.ScalarNode):
            self.path.add(key)
            children = node.value if isinstance(node, yaml.SequenceNode) else [n for kv in node.value for n in kv]
            if isinstance(node, yaml.MappingNode):
                self._no_duplicates(node)
            for child in children:
                s, h = self.check(child, depth + 1)
                size += s
                height = max(height, h + 1)
                if size > limits.MAX_DATA_NODES:
                    raise _Refused(f"it holds more than {limits.MAX_DATA_NODES:,} values with its aliases expanded "
                                   "(octoreach.limits.MAX_DATA_NODES)")
            self.path.discard(key)
        self.seen[key] = (size, height)
        return size, height

    def _no_duplicates(self, node) -> None:
        import yaml

        keys = set()
        for k, _ in node.value:
            if isinstance(k, yaml.ScalarNode) and k.tag != self.MERGE:
                if (k.tag, k.value) in keys:
                    raise _Refused(f"the key {k.value[:limits.MAX_SHOWN]!r} is given twice in one mapping "
                                   f"(line {k.start_mark.line + 1})")
                keys.add((k.tag, k.value))


def _load_yaml(text: str):
    import yaml

    loader_class = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    loader = loader_class(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        _Graph().check(node)
        return loader.construct_document(node)
    finally:
        loader.dispose()


def parse(text: str, where: str):
    """The data of JSON or YAML text (see the module docstring); ValueError starting with `where`."""
    try:
        data = json.loads(text, object_pairs_hook=_duplicates_refused)
        if isinstance(data, (dict, list)):
            _check_json(data)
        return data
    except _Refused as e:
        raise ValueError(f"{where}: {e}") from None
    except RecursionError:
        raise ValueError(f"{where}: it nests deeper than {limits.MAX_DATA_DEPTH} levels "
                         "(octoreach.limits.MAX_DATA_DEPTH)") from None
    except json.JSONDecodeError as json_error:
        try:
            import yaml  # optional
        except ImportError:
            raise ValueError(f"{where} is not valid JSON ({json_error}); YAML needs PyYAML") from None
        size = len(text.encode("utf-8", "surrogatepass"))
        if size > limits.MAX_YAML_BYTES:
            raise ValueError(f"{where} is not valid JSON ({json_error}), and at {size:,} bytes it is more YAML than "
                             f"the limit of {limits.MAX_YAML_BYTES:,} (octoreach.limits.MAX_YAML_BYTES): write large "
                             "files as JSON") from None
        try:
            return _load_yaml(text)
        except _Refused as e:
            raise ValueError(f"{where}: {e}") from None
        except RecursionError:
            raise ValueError(f"{where}: it nests deeper than {limits.MAX_DATA_DEPTH} levels "
                             "(octoreach.limits.MAX_DATA_DEPTH)") from None
        except (yaml.YAMLError, ValueError, TypeError, OverflowError) as e:
            problem = " ".join(str(e).split())[:400]  # one line: YAML's messages draw the place over several
            raise ValueError(f"{where} is neither JSON nor YAML: {problem}") from None
    except ValueError as e:  # an integer of more than sys.get_int_max_str_digits() digits
        raise ValueError(f"{where}: {' '.join(str(e).split())[:400]}") from None


def read_data(path, kind: str):
    """The data of a room, polygon or job file (`kind` names it in messages): JSON or YAML, within the limits
    of octoreach.limits; OSError for the file, ValueError for its text."""
    data = read_bytes(path, kind)
    where = f"{kind} {str(Path(path))!r}"
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ValueError(f"{where} is not UTF-8 text (byte {e.start})") from None
    return parse(text, where)
