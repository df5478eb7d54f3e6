"""Keyword arguments for the compiled core: a None leaves the choice to the C++ default, which is
defined once, in C++."""
from __future__ import annotations


def given(**kwargs) -> dict:
    """The keyword arguments that are not None."""
    return {k: v for k, v in kwargs.items() if v is not None}
