"""Helpers of the robustness tests: run code in a child process (with a memory cap and a timeout, so a
crash or a hang fails the test instead of killing the run), forge octoreach map files (and reseal the notes of
map cache entries), make .bt files."""
from __future__ import annotations

import os
import signal
import struct
import subprocess
import sys
import textwrap
import time
import zlib
from dataclasses import dataclass

MAGIC = b"OCTOREACH-MAP\n"


@dataclass
class Child:
    returncode: int | None  # None: killed after the timeout (a hang)
    stdout: str
    stderr: str
    seconds: float

    @property
    def crashed(self) -> bool:
        return self.returncode is not None and self.returncode < 0

    @property
    def hung(self) -> bool:
        return self.returncode is None


_PRELUDE = """
import resource, sys
_cap = {mem}
if _cap:
    resource.setrlimit(resource.RLIMIT_AS, (_cap, _cap))
"""


# Under AddressSanitizer (make test-sanitize preloads it) every call is several times slower and a memory
# error is caught at its first occurrence: the thread hammer tests repeat less there.
SANITIZED = "asan" in os.environ.get("LD_PRELOAD", "")


def run_python(code: str, timeout: float = 60.0, mem_bytes: int = 3 << 30, env: dict | None = None) -> Child:
    """Runs `code` in a fresh interpreter with the test's sys.path; address space capped at mem_bytes."""
    if "asan" in os.environ.get("LD_PRELOAD", ""):
        mem_bytes = 0  # AddressSanitizer reserves terabytes of address space: no RLIMIT_AS under it
    full = _PRELUDE.format(mem=int(mem_bytes)) + textwrap.dedent(code)
    e = dict(os.environ)
    e["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    e.setdefault("OMP_NUM_THREADS", "1")
    if env:
        e.update(env)
    t0 = time.monotonic()
    p = subprocess.Popen([sys.executable, "-c", full], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=e, text=True)
    try:
        out, err = p.communicate(timeout=timeout)
        return Child(p.returncode, out, err, time.monotonic() - t0)
    except subprocess.TimeoutExpired:
        p.kill()
        out, err = p.communicate()
        return Child(None, out, err, time.monotonic() - t0)


def _default_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, [signal.SIGINT])


def interrupt_latency(code: str, ready_marker: str = "READY", delay: float = 0.3, timeout: float = 60.0) -> tuple[Child, float]:
    """Starts `code` (which prints `ready_marker` and flushes just before the long call), sends SIGINT
    `delay` seconds after the marker and returns the child and the seconds from the signal to its exit."""
    full = textwrap.dedent(code)
    e = dict(os.environ)
    e["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
    # The child gets Ctrl-C as an interactive Python does, whatever earlier tests or libraries in this
    # process did to SIGINT (an ignored or blocked signal is inherited across exec, and a Python started
    # with SIGINT ignored never raises KeyboardInterrupt).
    p = subprocess.Popen([sys.executable, "-u", "-c", full], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=e,
                         text=True, preexec_fn=_default_sigint)
    t_start = time.monotonic()
    line = ""
    while ready_marker not in line:
        line = p.stdout.readline()
        if not line and p.poll() is not None:
            out, err = p.communicate()
            return Child(p.returncode, out, err, time.monotonic() - t_start), float("inf")
    time.sleep(delay)
    t_sig = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=timeout)
        rc = p.returncode
    except subprocess.TimeoutExpired:
        p.kill()
        out, err = p.communicate()
        rc = None
    latency = time.monotonic() - t_sig
    return Child(rc, out, err, time.monotonic() - t_start), latency


# ---- octoreach map files: parse and forge (header edited, checksum recomputed) ----

@dataclass
class MapFile:
    version: int
    kind: bytes
    header: dict
    raw_size: int
    compressed: bytes
    sections: bytes = b""  # what follows the payload: a version 2 file's section count and sections, as read

    def payload(self) -> bytes:
        return zlib.decompress(self.compressed)


def read_map(path) -> MapFile:
    data = open(path, "rb").read()
    assert data.startswith(MAGIC)
    pos = len(MAGIC)
    version, klen = struct.unpack_from("<II", data, pos)
    pos += 8
    kind = data[pos:pos + klen]
    pos += klen
    (hlen,) = struct.unpack_from("<I", data, pos)
    pos += 4
    text = data[pos:pos + hlen].decode()
    pos += hlen
    raw, size, _crc = struct.unpack_from("<QQI", data, pos)
    pos += 20
    header = dict(line.split("=", 1) for line in text.splitlines() if line)
    return MapFile(version, kind, header, raw, data[pos:pos + size], data[pos + size:])


def write_map(path, m: MapFile, payload: bytes | None = None) -> None:
    """Writes `m` with a correct checksum (so only the content checks can catch a forged header)."""
    comp = m.compressed if payload is None else zlib.compress(payload)
    raw = m.raw_size if payload is None else len(payload)
    text = "".join(f"{k}={v}\n" for k, v in m.header.items()).encode()
    crc = zlib.crc32(comp, zlib.crc32(text, zlib.crc32(m.kind)))
    with open(path, "wb") as f:
        f.write(MAGIC)
        f.write(struct.pack("<II", m.version, len(m.kind)))
        f.write(m.kind)
        f.write(struct.pack("<I", len(text)))
        f.write(text)
        f.write(struct.pack("<QQI", raw, len(comp), crc & 0xFFFFFFFF))
        f.write(comp)
        f.write(m.sections)


def forge(src, dst, **changes) -> None:
    m = read_map(src)
    for k, v in changes.items():
        m.header[k] = str(v)
    write_map(dst, m)


# ---- OctoMap .bt files ----

def reseal(entry) -> None:
    """The note beside a map cache entry rewritten to record the entry's present bytes (SHA-256), its kind and
    the key its file name says: what a writer of a shared cache folder can do after forging an entry, which
    leaves only the header and content checks to catch it."""
    import hashlib
    import json
    from pathlib import Path

    entry = Path(entry)
    note_path = entry.with_suffix(".json")
    note = json.loads(note_path.read_text()) if note_path.exists() else {"fields": {}}
    kind, key = entry.stem.split("-", 1)
    note.update(kind=kind, key=key, sha256=hashlib.sha256(entry.read_bytes()).hexdigest(), bytes=entry.stat().st_size)
    note_path.write_text(json.dumps(note))


def bt_file(children: list[bytes], size: int, res: float = 0.1) -> bytes:
    """An OctoMap binary file: header and the node bit fields (2 bytes per inner node, depth first)."""
    head = f"# Octomap OcTree binary file\nid OcTree\nsize {size}\nres {res}\ndata\n".encode()
    return head + b"".join(children)


def absurd_bt(res: float = 0.1) -> bytes:
    """A root whose 8 children are occupied leaves at depth 1: 2^48 cells at the finest resolution."""
    return bt_file([b"\xaa\xaa"], size=9, res=res)
