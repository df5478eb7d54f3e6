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


def finite_pose(value, name: str):
    """value as a (4, 4) float array; ValueError naming the argument for another shape or a NaN or inf entry
    (whether it is rigid is the compiled module's check)."""
    import numpy as np

    a = float_array(value, name, "a 4x4 pose")
    if a.shape != (4, 4):
        raise ValueError(f"{name} must be a 4x4 pose, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} holds NaN or inf: {shown(a.tolist())}")
    return a


def shown(value) -> str:
    """repr(value) for an error message, bounded in time and length (reprlib: at most a few items per level and
    a few levels, then at most limits.MAX_SHOWN characters): a message names a value, it never spells out a
    megabyte list or an alias bomb."""
    import reprlib

    from .limits import MAX_SHOWN

    r = reprlib.Repr()
    r.maxlevel, r.maxlist, r.maxtuple, r.maxdict, r.maxset = 3, 6, 6, 4, 4
    r.maxstring = r.maxother = r.maxlong = MAX_SHOWN
    try:
        text = r.repr(value)
    except ValueError:  # an int past sys.get_int_max_str_digits() has no repr
        text = f"<{type(value).__name__} of {value.bit_length()} bits>" if isinstance(value, int) else "<unprintable>"
    return text if len(text) <= MAX_SHOWN else text[:MAX_SHOWN - 3] + "..."
