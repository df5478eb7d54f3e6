"""The code blocks of the README and the documentation pages, and a runner that executes them page by page.

Every fenced block runs unless an HTML comment on the line just above it says otherwise:

- ``python`` blocks run in one namespace per page, in page order (a page reads as one script);
- ``sh`` / ``bash`` / ``console`` blocks run in bash (``set -euo pipefail``) in the page's working folder, with
  the interpreter's bin folder first on PATH (the ``octoreach`` command);
- ``json`` / ``yaml`` blocks are parsed;
- ``<!-- snippet: file NAME -->``: the block is written to NAME in the working folder (a room file, a URDF)
  before any block of the page runs (a page may list a long file at its end), and parsed when it is JSON or
  YAML;
- ``<!-- snippet: in PATH -->``: every non-blank line of the block appears, in order, in the repository file
  PATH (C++ and CMake that ctest compiles there);
- ``<!-- snippet: commands -->`` (sh blocks that take minutes: benchmarks, installs, a cluster): the commands
  are checked, not run: every ``python SCRIPT`` / ``python -m MODULE`` / ``octoreach ...`` line's options appear in
  its ``--help``, every ``make TARGET`` is a Makefile target and every ``bash FILE`` exists; other programs
  (``pip``, ``cmake``, ``ray``) are left as they are;
- ``<!-- snippet: skip REASON -->``: not run (``pip install``, a server, a long benchmark); the reason is
  required and the tests count these.

``text`` blocks are pictures in characters (a folder tree, a diagram), not code: they are neither run nor
counted. Any other block (``cpp``, ``cmake``, ...) without a marker is an error. A failure names the page and line:
``docs/guides/room.md:42: ...``.

Every page's working folder starts with a copy of ``docs/examples/`` (files several pages share: the robot of
the guides, ``rover.urdf``). Run one page by hand: ``python tests/python/doc_snippets.py docs/getting_started.md``.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import traceback
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FENCE = re.compile(r"^(?P<indent> {0,3})(?P<fence>`{3,}|~{3,})(?P<info>[^`]*)$")
MARKER = re.compile(r"^\s*<!--\s*snippet:\s*(?P<kind>skip|file|in|commands)\b\s*(?P<arg>.*?)\s*-->\s*$")
RUN_LANGS = {"python": "python", "py": "python", "sh": "sh", "bash": "sh", "console": "sh", "shell": "sh",
             "json": "json", "yaml": "yaml", "yml": "yaml"}


@dataclass
class Block:
    page: str          # path relative to the repository
    line: int          # line of the block's first code line (1-based)
    lang: str
    code: str
    marker: str = ""   # "", "skip", "file", "in" or "commands"
    arg: str = ""

    @property
    def where(self) -> str:
        return f"{self.page}:{self.line}"


def pages() -> list[Path]:
    """README.md and every Markdown page of the site."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


def blocks(path: Path) -> list[Block]:
    """The fenced code blocks of a Markdown page, with the snippet marker above each."""
    lines = path.read_text(encoding="utf-8").splitlines()
    rel = str(path.relative_to(ROOT))
    out, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, info = m["fence"], m["info"].strip()
        j = i + 1
        while j < len(lines) and not lines[j].strip().startswith(fence):
            j += 1
        if j == len(lines):
            raise ValueError(f"{rel}:{i + 1}: a code block that never ends")
        lang = info.split()[0].lower() if info else ""
        if not lang.startswith("{") and lang != "text":  # MyST directives ({toctree}, ...) and pictures are not code
            code = "\n".join(l[len(m["indent"]):] for l in lines[i + 1:j]) + "\n"
            block = Block(rel, i + 2, lang, code)
            above = MARKER.match(lines[i - 1]) if i > 0 else None
            if above:
                block.marker, block.arg = above["kind"], above["arg"]
            out.append(block)
        i = j + 1
    return out


def problem(block: Block) -> str | None:
    """Why a block can be neither run nor checked, or None."""
    if block.marker in ("skip", "file", "in") and not block.arg:
        return f"{block.where}: the snippet marker '{block.marker}' needs an argument"
    if block.marker == "commands" and RUN_LANGS.get(block.lang) != "sh":
        return f"{block.where}: the snippet marker 'commands' is for sh blocks"
    if block.marker == "in" and not (ROOT / block.arg).is_file():
        return f"{block.where}: snippet marker 'in {block.arg}': no such file"
    if not block.marker and block.lang not in RUN_LANGS:
        return (f"{block.where}: a '{block.lang or 'plain'}' block neither runs nor carries a marker "
                "(<!-- snippet: skip REASON -->, <!-- snippet: in PATH --> or <!-- snippet: file NAME -->)")
    return None


def check_lines_in(block: Block) -> None:
    """Every non-blank line of the block appears in the file, in order."""
    text = [l.strip() for l in (ROOT / block.arg).read_text(encoding="utf-8").splitlines()]
    at = 0
    for k, line in enumerate(block.code.splitlines()):
        if not line.strip():
            continue
        try:
            at = text.index(line.strip(), at) + 1
        except ValueError:
            raise AssertionError(f"{block.page}:{block.line + k}: this line is not in {block.arg} (in this order): "
                                 f"{line.strip()!r}") from None


def _help_of(program: list[str], cache: dict) -> str:
    key = tuple(program)
    if key not in cache:
        done = subprocess.run(program + ["--help"], cwd=ROOT, capture_output=True, text=True, timeout=120,
                              env=dict(os.environ, MPLBACKEND="Agg"))
        cache[key] = done.stdout if done.returncode == 0 else ""
    return cache[key]


def check_commands(block: Block, cache: dict) -> None:
    """The block's commands exist and take the options it gives them (see the module docstring)."""
    import shlex

    targets = set(re.findall(r"^([\w\-]+):", (ROOT / "Makefile").read_text(encoding="utf-8"), re.M))
    for k, line in enumerate(block.code.splitlines()):
        where = f"{block.page}:{block.line + k}"
        words = shlex.split(line, comments=True)
        words = words[:next((i for i, w in enumerate(words) if w in (">", "|", "&&", ";")), len(words))]
        if not words:
            continue
        head, rest = words[0], words[1:]
        if head == "make":
            missing = [t for t in rest if not t.startswith("-") and "=" not in t and t not in targets]
            assert not missing, f"{where}: no Makefile target {missing}"
            continue
        if head == "bash":
            assert (ROOT / rest[0]).is_file(), f"{where}: no such file {rest[0]}"
            continue
        if head in ("python", "python3") and rest[:1] == ["-m"]:
            program, rest = [sys.executable, "-m", rest[1]], rest[2:]
        elif head in ("python", "python3"):
            assert (ROOT / rest[0]).is_file(), f"{where}: no such script {rest[0]}"
            program, rest = [sys.executable, str(ROOT / rest[0])], rest[1:]
        elif head == "octoreach":
            program = [str(Path(sys.executable).parent / "octoreach")]
            while rest and re.fullmatch(r"[a-z][a-z\-]*", rest[0]):   # subcommands
                program.append(rest.pop(0))
        else:
            continue
        text = _help_of(program, cache)
        assert text, f"{where}: '{' '.join(words[:3])} --help' failed"
        unknown = [w.split("=")[0] for w in rest if w.startswith("--") and w.split("=")[0] not in text]
        assert not unknown, f"{where}: {' '.join(words[:3])} does not take {unknown}"


def parse(block: Block, lang: str) -> None:
    try:
        if lang == "json":
            json.loads(block.code)
        else:
            import yaml

            yaml.safe_load(block.code)
    except Exception as e:  # noqa: BLE001 (any parse error is the page's fault)
        raise AssertionError(f"{block.where}: the {lang} block does not parse: {e}") from None


def run_shell(block: Block, cwd: Path) -> None:
    env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}")
    done = subprocess.run(["bash", "-euo", "pipefail", "-c", block.code], cwd=cwd, env=env,
                          capture_output=True, text=True)
    sys.stdout.write(done.stdout)
    if done.returncode != 0:
        raise AssertionError(f"{block.where}: the shell block failed with status {done.returncode}:\n"
                             f"{block.code}{done.stderr[-3000:]}")


def run_python(block: Block, namespace: dict) -> None:
    # Padding with blank lines makes tracebacks give the line of the page itself.
    code = compile("\n" * (block.line - 1) + block.code, block.page, "exec")
    try:
        exec(code, namespace)
    except Exception:  # noqa: BLE001
        tb = traceback.format_exc(limit=-4)
        raise AssertionError(f"{block.where}: the python block raised:\n{tb}") from None


def run_page(path: Path, workdir: Path) -> dict[str, int]:
    """Runs every block of one page in order; returns the counts (ran, checked, skipped)."""
    counts = {"ran": 0, "checked": 0, "skipped": 0}
    namespace: dict = {"__name__": "__main__"}
    helps: dict = {}
    page = blocks(path)
    for block in page:
        why = problem(block)
        if why:
            raise AssertionError(why)
        if block.marker == "file":
            (workdir / block.arg).parent.mkdir(parents=True, exist_ok=True)
            (workdir / block.arg).write_text(block.code, encoding="utf-8")
            if RUN_LANGS.get(block.lang) in ("json", "yaml"):
                parse(block, RUN_LANGS[block.lang])
            counts["checked"] += 1
    for block in page:
        lang = RUN_LANGS.get(block.lang, "")
        if block.marker == "file":
            continue
        if block.marker == "skip":
            counts["skipped"] += 1
        elif block.marker == "in":
            check_lines_in(block)
            counts["checked"] += 1
        elif block.marker == "commands":
            check_commands(block, helps)
            counts["checked"] += 1
        elif lang in ("json", "yaml"):
            parse(block, lang)
            counts["checked"] += 1
        elif lang == "sh":
            run_shell(block, workdir)
            counts["ran"] += 1
        else:
            run_python(block, namespace)
            counts["ran"] += 1
    return counts


def main(argv: list[str]) -> int:
    """Runs the pages given (paths), each in a fresh working folder; prints the counts as JSON."""
    import matplotlib

    matplotlib.use("Agg")
    results = {}
    for arg in argv:
        path = Path(arg).resolve()
        with tempfile.TemporaryDirectory(prefix="octoreach-snippets-") as tmp:
            for example in (ROOT / "docs" / "examples").glob("*"):  # the pages' shared files (rover.urdf)
                shutil.copy(example, tmp)
            os.chdir(tmp)
            try:
                results[arg] = run_page(path, Path(tmp))
            except AssertionError as e:
                print(str(e), file=sys.stderr)
                return 1
            finally:
                os.chdir(ROOT)
    print(json.dumps(results))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
