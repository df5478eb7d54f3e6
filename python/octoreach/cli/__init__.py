"""The `octoreach` command line: one module per command group (robot, build, files, view, experiment, scale)."""
from __future__ import annotations

import argparse
import sys

from . import build, experiment, files, robot, scale, view


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="octoreach", description="Where a robot should stand and where it should look.")
    sub = p.add_subparsers(dest="command", required=True)
    for group in (robot, build, files, view, experiment, scale):
        group.add_commands(sub)
    return p


def _one_line(message, category, filename, lineno, file=None, line=None) -> None:
    """How the command line shows a warning (a map build's MapWarning, an SRDF's entries left out): one line."""
    print(f"octoreach: warning: {message}", file=sys.stderr)


def main(argv=None) -> int:
    import warnings

    args = build_parser().parse_args(argv)
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _one_line
            return args.func(args)
    except (ValueError, OSError, RuntimeError, ImportError) as e:  # ConnectionError is an OSError
        print(f"octoreach: error: {e}", file=sys.stderr)
        return 2


__all__ = ["build_parser", "main"]
