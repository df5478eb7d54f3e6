"""Argument type checks of the Python entry points: a wrong type raises TypeError naming the argument and
the type it expects, as the compiled module does for its own arguments (never an AttributeError or a
message from deep inside)."""
from __future__ import annotations

import os

PATH = (str, os.PathLike)


def check_type(value, types, name: str, expected: str) -> None:
    """TypeError "<name> must be <expected>, got <type>" unless value is an instance of types (a bool is
    not accepted as a number)."""
    types = types if isinstance(types, tuple) else (types,)
    if not isinstance(value, types) or (isinstance(value, bool) and bool not in types and
                                         any(t is not object and issubclass(bool, t) for t in types)):
        raise TypeError(f"{name} must be {expected}, got {type(value).__name__}")


def check_paths(values, name: str) -> list[str]:
    """A list of paths (str or os.PathLike) as str; TypeError naming the argument otherwise."""
    if isinstance(values, PATH) or not hasattr(values, "__iter__"):
        raise TypeError(f"{name} must be a list of paths, got {type(values).__name__}")
    out = []
    for i, v in enumerate(values):
        check_type(v, PATH, f"{name}[{i}]", "a path (str or os.PathLike)")
        out.append(str(v))
    return out


def float_array(value, name: str, expected: str):
    """value as a float numpy array; TypeError naming the argument when it is not numbers at all (the caller
    checks the shape: ValueError)."""
    import numpy as np

    if value is None:
        raise TypeError(f"{name} must be {expected}, got NoneType")
    try:
        return np.asarray(value, float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be {expected}, got {type(value).__name__}") from None
