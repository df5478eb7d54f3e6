#!/usr/bin/env python3
"""Recompresses a wheel in place with Zopfli: every member keeps its name, order, time stamp, permissions and
bytes (RECORD's hashes stay valid); only the deflate streams change, a few percent smaller than zlib's level 9.
Zopfli writes standard deflate, so pip, uv and unzip read the wheel as before and unpack it as fast: users
download less and install the same files.

    python scripts/recompress_wheel.py WHEEL [--cache DIR] [--iterations N]

Members are compressed in parallel; each stream is kept in DIR under the hash of its bytes, so a rebuild that
changes only the extension module does not compress the vendored libraries again. A member Zopfli does not
shrink keeps its old stream. The rewritten wheel is read back (every member, byte for byte) before it replaces
the old one.
"""
from __future__ import annotations

import argparse
import concurrent.futures
import hashlib
import os
import struct
import sys
import zipfile
import zlib
from pathlib import Path

import zopfli.zopfli

# Past a few iterations Zopfli gains a few bytes per megabyte for seconds of CPU (the docs suggest 5 for
# multi-megabyte inputs; 1 already gives nearly all of the gain on these binaries).
DEFAULT_ITERATIONS = 1
UTF8_FLAG = 0x800


def deflate(data: bytes, iterations: int) -> bytes:
    """A raw deflate stream of `data` (Zopfli's zlib container without its 2-byte header and 4-byte checksum)."""
    return zopfli.zopfli.compress(data, numiterations=iterations, gzip_mode=0)[2:-4]


def cached_deflate(data: bytes, iterations: int, cache: Path | None) -> bytes:
    if cache is None:
        return deflate(data, iterations)
    path = cache / f"{hashlib.sha256(data).hexdigest()}-{iterations}.deflate"
    if path.exists():
        stream = path.read_bytes()
        try:
            if zlib.decompress(stream, -15) == data:
                return stream
        except zlib.error:
            pass  # a damaged entry: compressed again below
    stream = deflate(data, iterations)
    tmp = path.with_suffix(f".tmp{os.getpid()}")
    tmp.write_bytes(stream)
    tmp.replace(path)
    return stream


def _dos_time(date_time: tuple) -> tuple[int, int]:
    y, mo, d, h, mi, s = date_time
    return (h << 11) | (mi << 5) | (s // 2), ((y - 1980) << 9) | (mo << 5) | d


def write_zip(out, members: list[tuple[zipfile.ZipInfo, int, bytes, int]]) -> None:
    """Writes (info, crc, stream, method) entries as a plain zip (no zip64: a wheel member stays under 4 GB)."""
    central = []
    for info, crc, stream, method in members:
        name = info.filename.encode("utf-8")
        flags = UTF8_FLAG if not info.filename.isascii() else 0
        dtime, ddate = _dos_time(info.date_time)
        if max(len(stream), info.file_size, out.tell()) >= 0xFFFFFFFF:
            raise ValueError(f"{info.filename}: too large for a zip without zip64")
        offset = out.tell()
        out.write(struct.pack("<4s5H3L2H", b"PK\x03\x04", 20, flags, method, dtime, ddate, crc, len(stream),
                              info.file_size, len(name), 0) + name + stream)
        central.append(struct.pack("<4s6H3L5H2L", b"PK\x01\x02", (info.create_system << 8) | 20, 20, flags, method,
                                   dtime, ddate, crc, len(stream), info.file_size, len(name), 0, 0, 0,
                                   info.internal_attr, info.external_attr, offset) + name)
    start = out.tell()
    for entry in central:
        out.write(entry)
    out.write(struct.pack("<4s4H2LH", b"PK\x05\x06", 0, 0, len(central), len(central), out.tell() - start, start, 0))


def recompress(wheel: Path, cache: Path | None, iterations: int) -> tuple[int, int]:
    """Rewrites `wheel`; returns its size before and after."""
    if cache is not None:
        cache.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(wheel) as z:
        infos = z.infolist()
        blobs = [z.read(i) for i in infos]
    with open(wheel, "rb") as f:  # the old streams, kept where Zopfli does not do better
        old = []
        for i in infos:
            f.seek(i.header_offset + 26)
            name_len, extra_len = struct.unpack("<2H", f.read(4))
            f.seek(i.header_offset + 30 + name_len + extra_len)
            old.append(f.read(i.compress_size))
    largest_first = sorted(range(len(blobs)), key=lambda k: -len(blobs[k]))
    with concurrent.futures.ProcessPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        jobs = {k: pool.submit(cached_deflate, blobs[k], iterations, cache) for k in largest_first}
        streams = [jobs[k].result() for k in range(len(blobs))]
    members = []
    for info, data, new, prev in zip(infos, blobs, streams, old):
        choices = [(len(new), zlib.crc32(data), new, zipfile.ZIP_DEFLATED),
                   (len(prev), info.CRC, prev, info.compress_type)]
        if info.compress_type not in (zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED):
            choices.pop()
        _, crc, stream, method = min(choices, key=lambda c: c[0])
        members.append((info, crc, stream, method))
    tmp = wheel.with_name(wheel.name + ".tmp")
    with open(tmp, "wb") as out:
        write_zip(out, members)
    with zipfile.ZipFile(tmp) as z:  # every member reads back, byte for byte, under its name and attributes
        same = [(i.filename, i.external_attr, i.date_time) for i in z.infolist()] == \
               [(i.filename, i.external_attr, i.date_time) for i in infos]
        bad = [i.filename for i, data in zip(z.infolist(), blobs) if z.read(i) != data] if same else ["(names)"]
    if bad:
        tmp.unlink()
        raise RuntimeError(f"{wheel}: the recompressed wheel does not read back: {bad[:3]}")
    before = wheel.stat().st_size
    tmp.replace(wheel)
    return before, wheel.stat().st_size


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("wheel", type=Path)
    p.add_argument("--cache", type=Path, default=None, help="folder of compressed streams kept between builds")
    p.add_argument("--iterations", type=int, default=DEFAULT_ITERATIONS, help="Zopfli iterations per member")
    args = p.parse_args(argv)
    if args.iterations < 1:
        p.error(f"--iterations must be at least 1, got {args.iterations}")
    before, after = recompress(args.wheel, args.cache, args.iterations)
    print(f"octoreach: {args.wheel.name} recompressed with Zopfli: {before} -> {after} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
