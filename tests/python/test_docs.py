"""The documentation cannot rot: every code block of the README and the site runs (doc_snippets.py), internal
links and anchors resolve, the README stays a front door (at most 200 lines) and no file tells round history."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from doc_snippets import ROOT, blocks, pages, problem

README_MAX_LINES = 200
ROUND = re.compile(r"round [0-9]+", re.IGNORECASE)
ROUND_NAME = re.compile(r"round[ _\-]?[0-9]+", re.IGNORECASE)
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\((?P<target>[^)\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^(#{1,6})\s+(?P<title>.+?)\s*#*\s*$")


def _rel(path: Path) -> str:
    return str(path.relative_to(ROOT))


def _pages_with_code() -> list[str]:
    return [_rel(p) for p in pages() if any(not b.marker for b in blocks(p))
            or any(b.marker in ("file", "in", "commands") for b in blocks(p))]


@pytest.fixture(scope="session")
def snippet_cache(tmp_path_factory):
    """One map cache for every page: a capability map a page builds with cache=True serves the next page."""
    return tmp_path_factory.mktemp("snippet-cache")


@pytest.mark.parametrize("page", _pages_with_code())
def test_page_code_runs(page, snippet_cache):
    env = dict(os.environ, OCTOREACH_CACHE_DIR=str(snippet_cache), MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, str(Path(__file__).with_name("doc_snippets.py")), page], cwd=ROOT,
                          env=env, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-6000:] or done.stdout[-3000:]
    counts = json.loads(done.stdout.strip().splitlines()[-1])[page]
    assert counts["ran"] + counts["checked"] > 0


def test_every_block_runs_or_says_why_not():
    """A block that is not run carries a marker with a reason; the skipped ones are counted and few."""
    problems, total, skipped = [], 0, []
    for page in pages():
        for b in blocks(page):
            total += 1
            why = problem(b)
            if why:
                problems.append(why)
            if b.marker == "skip":
                skipped.append(f"{b.where} ({b.arg})")
    assert not problems, "\n".join(problems)
    print(f"{total} code blocks, {len(skipped)} not run:\n" + "\n".join(skipped))
    assert len(skipped) <= total // 5, f"{len(skipped)} of {total} blocks are not run:\n" + "\n".join(skipped)


def _slug(title: str) -> str:
    """GitHub's (and MyST's) anchor of a heading."""
    title = re.sub(r"`([^`]*)`", r"\1", title)
    title = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", title)
    title = re.sub(r"[^\w\- ]", "", title.strip().lower())
    return title.replace(" ", "-")


def _prose(path: Path) -> list[tuple[int, str]]:
    """The lines of a page outside code blocks, inline code removed."""
    out, fence = [], None
    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        m = re.match(r"^ {0,3}(`{3,}|~{3,})", line)
        if m and (fence is None or m.group(1).startswith(fence)):
            fence = None if fence else m.group(1)
            continue
        if fence is None:
            out.append((n, re.sub(r"`[^`]*`", "", line)))
    return out


def _anchors(path: Path) -> set[str]:
    found = set()
    for _, line in _prose(path):
        m = HEADING.match(line)
        if m:
            found.add(_slug(m["title"]))
        found.update(re.findall(r"^\(([\w\-]+)\)=\s*$", line))  # MyST targets: (name)=
    return found


def test_internal_links_resolve():
    """Relative links and images of the README and the pages name files that exist, and anchors that exist."""
    broken = []
    for page in pages():
        for n, line in _prose(page):
            for m in LINK.finditer(line):
                target = m["target"]
                if re.match(r"^[a-z]+:", target) or target.startswith("{"):
                    continue
                file, _, anchor = target.partition("#")
                dest = (page.parent / file).resolve() if file else page
                if not dest.exists():
                    broken.append(f"{_rel(page)}:{n}: {target}: no such file")
                elif anchor and dest.suffix == ".md" and anchor not in _anchors(dest):
                    broken.append(f"{_rel(page)}:{n}: {target}: no heading with the anchor #{anchor}")
    assert not broken, "\n".join(broken)


def test_readme_is_a_front_door():
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    assert len(lines) <= README_MAX_LINES, f"README.md has {len(lines)} lines, at most {README_MAX_LINES}"


def test_no_round_history():
    """The tree tells what is, not how it came to be: no file under docs/, python/, cpp/, bindings/, tests/ names a
    round of work (git keeps the history)."""
    hits = []
    for folder in ("docs", "python", "cpp", "bindings", "tests"):
        for path in (ROOT / folder).rglob("*"):
            if not path.is_file() or "__pycache__" in path.parts:
                continue
            if ROUND_NAME.search(path.name):
                hits.append(f"{_rel(path)}: the file name")
            try:
                text = path.read_text(encoding="utf-8")
            except (UnicodeDecodeError, OSError):
                continue
            for n, line in enumerate(text.splitlines(), 1):
                if ROUND.search(line):
                    hits.append(f"{_rel(path)}:{n}: {line.strip()[:100]}")
    assert not hits, "\n".join(hits[:50]) + (f"\n... {len(hits)} in all" if len(hits) > 50 else "")
