"""Keyword arguments for the compiled core: a None leaves the choice to the C++ default, which is
defined once, in C++; and explore()'s keywords mapped onto its ExploreOptions, in one place."""
from __future__ import annotations

import copy

import numpy as np

from .._core import ExploreOptions

# explore() keywords that are not the name of an ExploreOptions or NbvOptions field
_ALIASES = {"candidates": "sampled_poses"}
# ... whose value must be an integer (a bool is refused, as a float is)
_INTEGERS = ("max_views", "patience", "candidates")


def given(**kwargs) -> dict:
    """The keyword arguments that are not None."""
    return {k: v for k, v in kwargs.items() if v is not None}


def explore_options(options=None, **settings) -> ExploreOptions:
    """A copy of `options` (None: ExploreOptions()) with each keyword that is not None set: an ExploreOptions
    field (`candidates`: sampled_poses), else a field of its search (NbvOptions; `score_size`: (width,
    height) of its score grid). TypeError for an unknown keyword, ValueError for a bad value."""
    if options is not None and not isinstance(options, ExploreOptions):
        raise TypeError(f"options must be an ExploreOptions or None, got {type(options).__name__}")
    o = ExploreOptions() if options is None else copy.copy(options)
    for key, value in given(**settings).items():
        if key in _INTEGERS and (not isinstance(value, (int, np.integer)) or isinstance(value, bool)):
            raise ValueError(f"{key} must be an integer >= 1, got {value!r}")
        if key == "score_size":
            o.search.score_width, o.search.score_height = value
            continue
        field = _ALIASES.get(key, key)
        target = o if _settable(o, field) and field != "search" else o.search if _settable(o.search, field) else None
        if target is None:
            raise TypeError(f"unexpected keyword argument {key!r}: not a field of ExploreOptions or of its search "
                            f"(NbvOptions){_did_you_mean(key, o)}")
        setattr(target, field, value)
    o.validate()
    return o


def _did_you_mean(key: str, o: ExploreOptions) -> str:
    """'; did you mean ...?' naming the settable fields (and aliases) closest to `key`, or ''."""
    import difflib

    names = [n for obj in (o, o.search) for n in dir(type(obj)) if not n.startswith("_") and _settable(obj, n)]
    near = difflib.get_close_matches(key, names + list(_ALIASES) + ["score_size"], n=3)
    return f"; did you mean {', '.join(repr(n) for n in near)}?" if near else ""


def _settable(obj, name: str) -> bool:
    """`name` is a settable field of obj's class."""
    f = getattr(type(obj), name, None)
    return isinstance(f, property) and f.fset is not None
