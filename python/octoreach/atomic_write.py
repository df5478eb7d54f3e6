"""The one way the Python layers save a file (room files, viewer pages and screenshots, plots, cache notes,
build-many outputs): a temporary file created exclusively (mkstemp: O_EXCL, an unpredictable name) in the
target's folder, written, flushed to disk and renamed over the target. A crash never leaves half a file, and a
name planted in a shared folder cannot redirect the write.

The target must be a regular file or not exist yet: a symbolic link, a FIFO, a device (/dev/full) or a folder
is refused with an OSError naming it, never replaced (saving to a link's target: give that path). The file
gets the mode a new file gets from the umask (0666 & ~umask), as open() would give it.
"""
from __future__ import annotations

import contextlib
import io
import os
import stat
import tempfile
import threading
from pathlib import Path

from ._checks import PATH, check_type
from .data_files import file_kind

_umask_lock = threading.Lock()


def _umask() -> int:
    """The process's umask, read without changing it where Linux says it (/proc), else set and restored."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    with _umask_lock:
        mask = os.umask(0o22)
        os.umask(mask)
    return mask


def check_target(path, kind: str = "file") -> Path:
    """`path` as a Path when it may be replaced (a regular file, or nothing yet); OSError naming it otherwise."""
    check_type(path, PATH, "path", "a file path (str or os.PathLike)")
    path = Path(os.fspath(path))
    if "\x00" in str(path):
        raise ValueError(f"{kind} path {str(path)!r} holds a NUL character")
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return path
    if stat.S_ISLNK(st.st_mode):
        raise OSError(f"cannot write {kind} {str(path)!r}: it is a symbolic link (to {os.readlink(path)!r}); "
                      "octoreach does not replace links: give the path of the file itself")
    if stat.S_ISDIR(st.st_mode):
        raise IsADirectoryError(f"cannot write {kind} {str(path)!r}: it is a folder")
    if not stat.S_ISREG(st.st_mode):
        raise OSError(f"cannot write {kind} {str(path)!r}: it is {file_kind(st.st_mode)}, not a regular file; "
                      "octoreach refuses to replace it")
    return path


def write_atomically(path, data: bytes | str, kind: str = "file") -> Path:
    """Writes `data` (str: UTF-8) to `path` through a temporary file in its folder, fsync and rename (see the
    module docstring); returns the path."""
    check_type(data, (bytes, str), "data", "bytes or str")
    path = check_target(path, kind)
    if isinstance(data, str):
        data = data.encode("utf-8")
    folder = path.parent if str(path.parent) else Path(".")
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=path.name + ".tmp.")
    except OSError as e:
        raise type(e)(e.errno, f"cannot write {kind} {str(path)!r}: {e.strerror}") from None
    try:
        os.fchmod(fd, 0o666 & ~_umask())
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    return path


def save_figure(fig, path, **kwargs) -> Path:
    """A matplotlib figure saved atomically (its format from the file name's extension, else PNG)."""
    suffix = Path(os.fspath(path)).suffix.lstrip(".").lower()
    kwargs.setdefault("format", suffix if suffix in ("png", "pdf", "svg", "jpg", "jpeg", "eps", "ps") else "png")
    buffer = io.BytesIO()
    fig.savefig(buffer, **kwargs)
    return write_atomically(path, buffer.getvalue(), "figure")
