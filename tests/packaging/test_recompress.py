"""scripts/recompress_wheel.py: the recompressed archive holds the same members, byte for byte, with their names,
order, time stamps and permissions, and is no larger; its streams are standard deflate (zipfile and zlib read
them) and a second run reuses the cached streams."""
from __future__ import annotations

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "recompress_wheel.py"
pytestmark = pytest.mark.skipif(not SCRIPT.is_file(), reason="needs the source tree (scripts/recompress_wheel.py)")


@pytest.fixture(scope="module")
def recompress():
    """Runs the script as `make wheel` does; returns the finished process."""
    pytest.importorskip("zopfli", reason="zopfli is a release tool (pyproject's dependency group 'release')")
    return lambda *args: subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True, text=True)


def _members(path: Path) -> list[tuple]:
    with zipfile.ZipFile(path) as z:
        return [(i.filename, i.date_time, i.external_attr, z.read(i)) for i in z.infolist()]


def _wheel(tmp_path: Path) -> Path:
    path = tmp_path / "demo-1.0-py3-none-any.whl"
    code = b"".join(b"def f%d(x):\n    return x * %d + %d\n" % (i, i % 7, i % 13) for i in range(3000))
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as z:
        z.writestr(zipfile.ZipInfo("demo/", (2024, 5, 6, 7, 8, 10)), b"")
        lib = zipfile.ZipInfo("demo.libs/libdemo.so", (2024, 5, 6, 7, 8, 12))
        lib.external_attr = 0o100755 << 16
        z.writestr(lib, os.urandom(2000) + code, zipfile.ZIP_DEFLATED, 9)
        z.writestr("demo/module.py", code)
        z.writestr("demo/donn\u00e9es.txt", "r\u00e9sum\u00e9\n" * 50)
        z.writestr("demo/empty.txt", b"")
        z.writestr("demo/stored.bin", os.urandom(300), zipfile.ZIP_STORED)
    return path


def test_the_members_stay_the_same_and_the_archive_does_not_grow(recompress, tmp_path):
    path = _wheel(tmp_path)
    before, size = _members(path), path.stat().st_size
    done = recompress(path, "--cache", tmp_path / "cache")
    assert done.returncode == 0, done.stderr
    assert f"{path.name} recompressed with Zopfli: {size} -> {path.stat().st_size} bytes" in done.stdout
    assert _members(path) == before
    assert path.stat().st_size < size
    with zipfile.ZipFile(path) as z:
        assert z.testzip() is None
        assert z.getinfo("demo.libs/libdemo.so").external_attr >> 16 == 0o100755
        assert z.getinfo("demo/module.py").compress_type == zipfile.ZIP_DEFLATED


def test_a_second_run_reuses_the_cache_and_gives_the_same_bytes(recompress, tmp_path):
    path = _wheel(tmp_path)
    recompress(path, "--cache", tmp_path / "cache")
    first = path.read_bytes()
    cached = sorted(p.name for p in (tmp_path / "cache").iterdir())
    assert cached and all(n.endswith("-1.deflate") for n in cached)
    recompress(path, "--cache", tmp_path / "cache")
    assert path.read_bytes() == first
    assert sorted(p.name for p in (tmp_path / "cache").iterdir()) == cached


def test_a_damaged_cache_entry_is_compressed_again(recompress, tmp_path):
    path = _wheel(tmp_path)
    before = _members(path)
    cache = tmp_path / "cache"
    recompress(path, "--cache", cache)
    for p in cache.iterdir():
        p.write_bytes(b"\x03\x00")  # an empty deflate stream: decompresses to the wrong bytes
    recompress(path, "--cache", cache)
    assert _members(path) == before


def test_iterations_below_one_are_refused(recompress, tmp_path):
    done = recompress(_wheel(tmp_path), "--iterations", 0)
    assert done.returncode == 2 and "--iterations must be at least 1, got 0" in done.stderr
