"""Map files of any kind: ``load(path)`` reads a surface (.orsm), capability (.orcm) or inverse point map
(.orpm) file, whichever kind it holds (the file's header names its kind; the extension does not matter).

    m = octoreach.map_files.load("demo_out/table_either_arm.orsm")   # a SurfaceMap
    octoreach.map_files.kind("demo_out/table_either_arm.orsm")       # "surface"

The registry of kinds lives in C++ (``octoreach/map_files.hpp``): every map class names its kind
(``SurfaceMap.kind == "surface"``). The command line (`octoreach info`, `export`, `view`), the viewer and the
map cache read map files through it.
"""
from __future__ import annotations

import os


def kinds() -> dict[str, str]:
    """Every map kind a file can hold: {kind: usual file extension}, e.g. {"surface": ".orsm", ...}."""
    from ._core import map_kinds

    return map_kinds()


def kind(path: str | os.PathLike) -> str:
    """The kind the map file at `path` names in its header, without loading the map. A file that is not an
    octoreach map: OSError naming the file and the problem."""
    from ._core import map_kind

    return map_kind(os.fspath(path))


def load(path: str | os.PathLike, kind: str | None = None):
    """The SurfaceMap, CapabilityMap or InversePointMap stored at `path`; with `kind` ("surface", "capability",
    "point") the file must hold that kind. A file that is not an octoreach map, of another kind than asked
    for, or a damaged one: OSError naming the file and the problem. An unknown `kind`: ValueError."""
    from ._core import load_any

    return load_any(os.fspath(path), kind or "")
