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


# What bad input raises (ConnectionError and FileNotFoundError are OSErrors, JobError a ValueError, an unknown
# surface a KeyError, an integer too large for a float an OverflowError): one line on stderr, status 2.
_INPUT_ERRORS = (ValueError, TypeError, OSError, RuntimeError, ImportError, LookupError, ArithmeticError)


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
    except _INPUT_ERRORS as e:
        message = " ".join(str(e.args[0] if isinstance(e, KeyError) and e.args else e).split())
        print(f"octoreach: error: {message[:2000] or type(e).__name__}", file=sys.stderr)
        return 2
    except MemoryError:
        print("octoreach: error: out of memory (an input larger than this machine can hold?)", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("octoreach: interrupted", file=sys.stderr)
        return 130


__all__ = ["build_parser", "main"]
