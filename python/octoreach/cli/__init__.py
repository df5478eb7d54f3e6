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
            code = args.func(args)
            sys.stdout.flush()  # here, not at the interpreter's exit: a reader that has gone shows in this try
            return code
    except BrokenPipeError as e:
        if _stdout_closed():  # the reader of the output went away (`octoreach ... | head`): not an error of ours
            return 0
        return _input_error(e)
    except _INPUT_ERRORS as e:
        return _input_error(e)
    except MemoryError:
        print("octoreach: error: out of memory (an input larger than this machine can hold?)", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("octoreach: interrupted", file=sys.stderr)
        return 130


def _input_error(e: BaseException) -> int:
    message = " ".join(str(e.args[0] if isinstance(e, KeyError) and e.args else e).split())
    print(f"octoreach: error: {message[:2000] or type(e).__name__}", file=sys.stderr)
    return 2


def _stdout_closed() -> bool:
    """True when standard output is a pipe whose reader has gone (the pipe reports an error to a poll); then it is
    pointed at /dev/null, so that the interpreter's own flush at exit does not fail again."""
    import os
    import select

    try:
        poll = select.poll()
        poll.register(sys.stdout.fileno(), select.POLLOUT)
        closed = any(event & select.POLLERR for _, event in poll.poll(0))
    except (OSError, ValueError, AttributeError):  # no file descriptor (a captured stream)
        return False
    if closed:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return closed


__all__ = ["build_parser", "main"]
