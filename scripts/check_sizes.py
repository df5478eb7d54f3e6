#!/usr/bin/env python3
"""Size limits of the code: prints the largest file and the largest function of the C++ (cpp/src, bindings)
and of the Python package (python/octoreach), lists every one over its limit, and exits 1 when any is.

    python3 scripts/check_sizes.py          # from anywhere; the repository is this script's parent folder

A file or function over its limit is a smell: split it along the concepts inside it. C++ functions are
measured by a brace scanner that skips comments, strings and preprocessor lines (a function's lines run from
its signature's last line, where its body opens, to its closing brace); Python functions by the ast, from
`def` to their last line (a nested function counts in its own right and inside its parent).
"""
from __future__ import annotations

import ast
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CPP_DIRS = ("cpp/src", "bindings")
CPP_SUFFIXES = (".cpp", ".hpp", ".h", ".cc")
PY_DIRS = ("python/octoreach",)
LIMITS = {"cpp file": 500, "cpp function": 120, "python module": 400, "python function": 80}

# Known offenders in areas other work is still changing, by (kind, file, function or "" for the file itself).
# This list must end empty: each entry goes when the change that splits it lands.
ALLOWED: set[tuple[str, str, str]] = set()

_CONTAINER = re.compile(r"\b(namespace|class|struct|union|enum|extern)\b")
_NAME = re.compile(r"(~?[A-Za-z_]\w*(?:\s*::\s*~?[A-Za-z_]\w*)*|operator\s*\S+?)\s*\($")


def strip_cpp(text: str) -> str:
    """The text with comments, string and character literals and preprocessor lines blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            out.append(c)
            i += 1
            continue
        if line_start and c == "#":  # a preprocessor line, with its continuations
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append("\n")
                    i += 2
                    continue
                i += 1
            continue
        line_start = c == "\n"
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append("\n" * text.count("\n", i, end))
            i = end
            continue
        raw = re.match(r'R"([^(\s]{0,16})\(', text[i:i + 20]) if c == "R" and (i == 0 or not
                                                                         (text[i - 1].isalnum() or text[i - 1] == "_")) else None
        if raw:
            close = ")" + raw.group(1) + '"'
            end = text.find(close, i + raw.end())
            end = n if end < 0 else end + len(close)
            out.append('""' + "\n" * text.count("\n", i, end))
            i = end
            continue
        if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum() and \
                re.match(r"[0-9a-fA-FxXbB']*$", _number_before(text, i)):
            i += 1  # a digit separator (1'000)
            continue
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def _number_before(text: str, i: int) -> str:
    j = i
    while j > 0 and (text[j - 1].isalnum() or text[j - 1] in "'."):
        j -= 1
    word = text[j:i]
    return word if word[:1].isdigit() else "x!"


def _strip_template(header: str) -> str:
    """The header without a leading access specifier or template <...> clause."""
    header = re.sub(r"^\s*(public|protected|private)\s*:(?!:)", "", header)
    m = re.match(r"\s*template\s*<", header)
    if not m:
        return header
    depth, i = 1, m.end()
    while i < len(header) and depth:
        depth += {"<": 1, ">": -1}.get(header[i], 0)
        i += 1
    return _strip_template(header[i:])


def _classify(header: str) -> str:
    """What a brace opened outside any function opens: "container", "function" or "init" (a braced initializer)."""
    h = _strip_template(header).strip()
    head = h.split("(", 1)[0]
    if _CONTAINER.search(head) and "=" not in head:
        return "container"
    if "(" not in h or re.search(r"=\s*[^(]*$", h.split("(", 1)[0]) and not re.search(r"operator\s*=", h):
        return "init"
    if re.search(r"\)\s*:", h) and re.search(r"[\w>]\s*$", h) and not re.search(r"->[^()]*$", h):
        return "init"  # a member braced initializer in a constructor's initializer list
    return "function"


def _function_name(header: str) -> str:
    h = re.sub(r"\s+", " ", _strip_template(header)).strip()
    depth, i = 0, len(h) - 1
    # The name stands before the parameter list: find the '(' matching the last top-level ')' before the body.
    close = h.rfind(")")
    m_init = re.search(r"\)\s*:(?!:)", h)
    if m_init:
        close = m_init.start()
    for i in range(close, -1, -1):
        depth += {")": 1, "(": -1}.get(h[i], 0)
        if depth == 0:
            break
    m = _NAME.search(h[:i + 1])
    if m:
        return re.sub(r"\s+", "", m.group(1))
    return h[max(0, i - 40):i].strip() or "?"


def cpp_functions(text: str) -> list[tuple[str, int, int]]:
    """(name, first line, lines) of each function body outside any other function, in order."""
    s = strip_cpp(text)
    found = []
    stack = []  # kinds of the open braces
    header_start = 0
    line = 1
    body_start = {}
    for i, c in enumerate(s):
        if c == "\n":
            line += 1
        elif c == "{":
            if "function" in stack or "init" in stack and stack[-1] == "init":
                stack.append("block")
                continue
            kind = _classify(s[header_start:i])
            if kind == "function":
                body_start[len(stack)] = (_function_name(s[header_start:i]), line)
            stack.append(kind)
            if kind != "init":
                header_start = i + 1
        elif c == "}":
            kind = stack.pop() if stack else "container"
            if kind == "function":
                name, first = body_start.pop(len(stack))
                found.append((name, first, line - first + 1))
            if kind in ("function", "container"):
                header_start = i + 1
        elif c == ";" and ("function" not in stack):
            if not stack or stack[-1] != "init":
                header_start = i + 1
    return found


def python_functions(text: str, path: str) -> list[tuple[str, int, int]]:
    tree = ast.parse(text, filename=path)
    out = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            out.append((node.name, node.lineno, node.end_lineno - node.lineno + 1))
    return out


def measure(root: Path = ROOT) -> list[tuple[str, str, str, int, int]]:
    """Every file and function as (kind, file, function, first line, lines); kind as in LIMITS."""
    rows = []
    for language, dirs, suffixes in (("cpp", CPP_DIRS, CPP_SUFFIXES), ("python", PY_DIRS, (".py",))):
        files = sorted(p for d in dirs for p in (root / d).rglob("*") if p.suffix in suffixes and p.is_file())
        for p in files:
            rel = p.relative_to(root).as_posix()
            text = p.read_text(encoding="utf-8", errors="replace")
            rows.append((f"{language} {'file' if language == 'cpp' else 'module'}", rel, "", 1,
                         text.count("\n") + (not text.endswith("\n") and bool(text))))
            functions = cpp_functions(text) if language == "cpp" else python_functions(text, rel)
            rows += [(f"{language} function", rel, name, first, n) for name, first, n in functions]
    return rows


def main(argv: list[str]) -> int:
    root = Path(argv[1]).resolve() if len(argv) > 1 else ROOT
    rows = measure(root)
    for kind in LIMITS:
        of_kind = [r for r in rows if r[0] == kind]
        if of_kind:
            k, f, name, first, n = max(of_kind, key=lambda r: r[4])
            where = f"{f}:{first} {name}" if name else f
            print(f"largest {kind}: {n} lines ({where}; limit {LIMITS[kind]})")
    over = [r for r in rows if r[4] > LIMITS[r[0]]]
    allowed = [r for r in over if (r[0], r[1], r[2]) in ALLOWED]
    failing = [r for r in over if (r[0], r[1], r[2]) not in ALLOWED]
    for title, group in (("over the limit, allowed while other work splits them", allowed),
                         ("OVER THE LIMIT", failing)):
        if group:
            print(f"{title}:")
            for k, f, name, first, n in sorted(group):
                print(f"  {k} {f}:{first} {name} {n} lines (limit {LIMITS[k]})".replace("  ", " ").replace(" ", "  ", 1))
    stale = ALLOWED - {(r[0], r[1], r[2]) for r in allowed}
    for k, f, name in sorted(stale):
        print(f"allow-list entry no longer needed (remove it): {k} {f} {name}".rstrip())
    if failing or stale:
        return 1
    print("all within the limits" + (" (but for the allow-list)" if allowed else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
