"""Map files of any kind: ``load(path)`` reads a surface (.orsm), capability (.orcm) or inverse point map
file, whichever kind it holds (the file's header names its kind; the extension does not matter).

    m = octoreach.map_files.load("demo_out/table_either_arm.orsm")   # a SurfaceMap

The command line (`octoreach info`, `export`, `view`) and the viewer read map files through it.
"""
from __future__ import annotations

import os


def load(path: str | os.PathLike):
    """The SurfaceMap, CapabilityMap or InversePointMap stored at `path`. A file that is not an octoreach
    map, or a damaged one: OSError naming the file and the problem (one message, not one per kind)."""
    from ._core import CapabilityMap, InversePointMap, SurfaceMap

    path = os.fspath(path)
    errors = []
    for cls in (SurfaceMap, CapabilityMap, InversePointMap):
        try:
            return cls.load(path)
        except OSError as e:
            if "holds a" not in str(e):  # not "holds a <kind> map, expected a <kind> map": the file's own error
                raise
            errors.append(str(e))
    raise OSError(errors[-1])
