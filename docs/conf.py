"""Sphinx configuration of the octoreach documentation site (`make docs` builds it into build/docs/html).

Pages are MyST Markdown; the Python reference comes from the installed package's docstrings (autodoc), the C++
reference from the public headers (Doxygen XML, rendered by breathe). Warnings are errors in `make docs`, and
docs/_ext/octoreach_reference.py fails the build when a public class or function has no reference entry.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS / "_ext"))

import octoreach  # noqa: E402  (the installed package: the reference documents what users import)

project = "octoreach"
author = "the octoreach authors"
copyright = "the octoreach authors"
release = octoreach.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "breathe",
    "octoreach_reference",
]

source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "Doxyfile"]

myst_enable_extensions = ["colon_fence", "deflist", "dollarmath"]
myst_heading_anchors = 3

html_theme = "furo"
html_title = f"octoreach {release}"
html_static_path: list[str] = []
html_show_sourcelink = False

# Every cross-reference must resolve; the types in compiled signatures that are not ours are named here.
nitpicky = True
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|typing|collections|pathlib|os|concurrent|argparse|matplotlib|viser|ray|pybind11_builtins)(\..*)?"),
    (r"py:.*", r"(NDArray|ArrayLike|Any|Callable|Iterable|Sequence|Mapping|Path|PathLike|SupportsFloat|"
               r"SupportsInt|SupportsIndex|Annotated|Optional|Union|Literal|Self|TextIO|object|float|int|str|"
               r"bool|bytes|list|dict|tuple|set|None|type|Exception|KeyboardInterrupt|ValueError|"
               r"RuntimeError|TypeError|OSError)"),
    # Numpy's shapes in pybind11 signatures: numpy.ndarray[numpy.float64[m, 3]] and the like.
    (r"py:.*", r"(m|n|\d+|\[.*|.*\])"),
    # The C++ reference: standard library and Eigen types, which breathe cannot link.
    (r"cpp:.*", r"(std|Eigen|fcl|octomap|size_t|uint\w*|int\w*)(::.*)?"),
    # The namespaces (declared by no directive: octoreach, octoreach::limits), Eigen's Identity() of Pose, internals named in declarations.
    (r"cpp:.*", r"(octoreach|octoreach::limits|limits|Pose::Identity|detail(::.*)?)"),
]

autodoc_default_options = {"members": True, "undoc-members": True, "show-inheritance": True}
autodoc_member_order = "groupwise"
autodoc_typehints = "signature"
autodoc_docstring_signature = True
autodoc_mock_imports: list[str] = []

breathe_projects = {"octoreach": str(ROOT / "build" / "docs" / "doxygen" / "xml")}
breathe_default_project = "octoreach"
breathe_domain_by_extension = {"hpp": "cpp"}
breathe_default_members = ("members",)


# The index's toctrees list the pages in reading order. A page added later that no toctree lists joins the
# toctree of its folder (guides/, concepts/ and design/ under Concepts, the rest under Reference) at its end,
# so a new guide appears in the menu without an edit here.
_FOLDER_TOCTREE = {"guides": ":caption: Guides", "concepts": ":caption: Concepts", "design": ":caption: Concepts"}


def _pages_not_listed(app, docname, source):
    if docname != root_doc:
        return
    text = source[0]
    docs = Path(app.srcdir)
    for page in sorted(docs.rglob("*.md")):
        name = page.relative_to(docs).with_suffix("").as_posix()
        if name == root_doc or name.startswith("api/") or re.search(rf"^{re.escape(name)}$", text, re.M):
            continue
        caption = _FOLDER_TOCTREE.get(name.split("/")[0], ":caption: Reference")
        start = text.index(caption)
        end = text.index("```", start)
        text = text[:end] + name + "\n" + text[end:]
    source[0] = text


def setup(app):
    app.connect("source-read", _pages_not_listed)
