"""Sphinx extension of the octoreach site: runs Doxygen on the public headers before the pages are read, and
fails the build (a warning, an error under -W) when a public class, function or value of the Python package,
or a public C++ header, has no entry in the API reference.

Public Python API: the names in ``__all__`` of ``octoreach``, of its subpackages and modules, and every public
name of ``octoreach._core`` (the compiled module; most of it is re-exported by ``octoreach``).
"""
from __future__ import annotations

import importlib
import inspect
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)

DOCS = Path(__file__).resolve().parent.parent
ROOT = DOCS.parent
HEADERS = ROOT / "cpp" / "include" / "octoreach"
XML = ROOT / "build" / "docs" / "doxygen" / "xml"

# The package's public modules: octoreach, what it imports or loads on first use, and the command line.
PUBLIC_MODULES = (
    "octoreach", "octoreach._core", "octoreach.arms", "octoreach.cache", "octoreach.map_files",
    "octoreach.progress", "octoreach.robots", "octoreach.rooms", "octoreach.surface_maps", "octoreach.cluster",
    "octoreach.experiments", "octoreach.jobs", "octoreach.plots", "octoreach.exploration", "octoreach.planning",
    "octoreach.testing", "octoreach.viewer", "octoreach.cli",
)


def run_doxygen(app: Sphinx) -> None:
    """Doxygen XML of the public headers, made again when a header or the Doxyfile is newer."""
    doxyfile = DOCS / "Doxyfile"
    index = XML / "index.xml"
    sources = [doxyfile, *HEADERS.glob("*.hpp")]
    if index.is_file() and index.stat().st_mtime >= max(p.stat().st_mtime for p in sources):
        return
    if shutil.which("doxygen") is None:
        raise RuntimeError("doxygen is not installed: run `bash scripts/install_deps.sh` (Debian package doxygen)")
    XML.parent.mkdir(parents=True, exist_ok=True)
    done = subprocess.run(["doxygen", str(doxyfile)], cwd=DOCS, capture_output=True, text=True)
    for line in (done.stdout + done.stderr).splitlines():
        if line.strip():
            logger.warning("doxygen: %s", line)
    if done.returncode != 0:
        raise RuntimeError(f"doxygen failed with status {done.returncode}")
    # Include lists, graphs and "subclassed by" lists would link to pages and labels breathe does not make.
    for xml in XML.glob("*.xml"):
        text = xml.read_text(encoding="utf-8")
        text = re.sub(r"\s*<(includes|includedby|derivedcompoundref)\b[^>]*>[^<]*</\1>", "", text)
        text = re.sub(r"\s*<(incdepgraph|invincdepgraph|inheritancegraph|collaborationgraph)>.*?</\1>", "", text,
                      flags=re.S)
        xml.write_text(text, encoding="utf-8")


def header_directives(header: str) -> list[str]:
    """The breathe directives that document one public header: each class and struct it declares (with their
    members) and each enum, typedef, function and constant of namespace octoreach it declares."""
    index = ET.parse(XML / "index.xml").getroot()
    refid = next((c.get("refid") for c in index.findall("compound")
                  if c.get("kind") == "file" and c.findtext("name") == header), None)
    if refid is None:
        raise ValueError(f"octoreach-header: no header {header!r} in the Doxygen XML")
    compound = ET.parse(XML / f"{refid}.xml").getroot()
    brief = " ".join("".join(compound.find("compounddef/briefdescription").itertext()).split())
    lines = [re.sub(r"([\\*`_|])", r"\\\1", brief) or header, ""]  # the header's brief, as plain text
    classes = [(c.get("refid"), c.text) for c in compound.iter("innerclass")]
    names = {name for _, name in classes}
    for cid, name in classes:
        if "::detail::" in name or name.rsplit("::", 1)[0] in names:  # internals; nested ones come with their class
            continue
        kind = "struct" if cid.startswith("struct") else "class"
        lines += [f".. doxygen{kind}:: {name}", "   :members:", "   :undoc-members:", ""]
    directive = {"enum": "doxygenenum", "typedef": "doxygentypedef", "function": "doxygenfunction",
                 "variable": "doxygenvariable"}
    members = []  # (namespace, memberdef) of octoreach and its public nested namespaces (octoreach::limits)
    for path in sorted(XML.glob("namespaceoctoreach*.xml")):
        namespace = ET.parse(path).getroot()
        name = namespace.findtext("compounddef/compoundname")
        if "detail" in name.split("::"):
            continue
        members += [(name, m) for m in namespace.iter("memberdef") if m.get("kind") in directive
                    and Path(m.find("location").get("file")).name == header]
    overloaded = {n for n in (m.findtext("name") for _, m in members)
                  if sum(1 for _, x in members if x.findtext("name") == n) > 1}
    for space, m in members:
        target = f"{space}::{m.findtext('name')}"
        if m.get("kind") == "function" and m.findtext("name") in overloaded:
            types = ["".join(p.find("type").itertext()).strip() for p in m.findall("param")]
            target += "(" + ", ".join(types) + ")"
        lines += [f".. {directive[m.get('kind')]}:: {target}", ""]
    return lines


class HeaderDirective(SphinxDirective):
    """``octoreach-header:: NAME.hpp``: the reference entries of one public header."""

    required_arguments = 1

    def run(self):
        lines = header_directives(self.arguments[0])
        body = nodes.section()
        self.state.nested_parse(StringList(lines, source=self.get_source_info()[0]), self.content_offset, body)
        return body.children


def public_names(modname: str) -> dict[str, object]:
    """The public names of a module: its ``__all__``, else what it defines itself (no leading underscore)."""
    module = importlib.import_module(modname)
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n, v in vars(module).items() if not n.startswith("_")
                 and (inspect.isclass(v) or inspect.isroutine(v) or type(v).__name__ == "builtin_function_or_method")
                 and getattr(v, "__module__", modname) == modname]
    return {n: getattr(module, n) for n in names if n != "__version__"}


def missing_python_entries(objects: set[str], modules: set[str]) -> list[str]:
    """Each public object with no reference entry under any of its public names, by its first public name."""
    names: dict[int, list[str]] = {}
    values: dict[int, object] = {}
    for modname in PUBLIC_MODULES:
        for name, value in public_names(modname).items():
            names.setdefault(id(value), []).append(f"{modname}.{name}")
            values[id(value)] = value
    missing = []
    for key, value in values.items():
        if inspect.ismodule(value):
            if value.__name__ not in modules:
                missing.append(f"module {value.__name__}")
            continue
        canonical = f"{getattr(value, '__module__', '')}.{getattr(value, '__qualname__', '')}"
        if not any(n in objects for n in names[key]) and canonical not in objects:
            missing.append(names[key][0])
    return missing


def documented_headers() -> set[str]:
    """Headers named by a ``doxygenfile`` directive on some page."""
    named = set()
    for page in DOCS.rglob("*.md"):
        named.update(re.findall(r"octoreach-header::\s*(\S+\.hpp)", page.read_text(encoding="utf-8")))
    return named


def check_reference(app: Sphinx, env) -> None:
    domain = env.get_domain("py")
    objects = set(domain.objects)
    modules = set(domain.modules)
    for full in missing_python_entries(objects, modules):
        logger.warning("%s has no entry in the API reference: add it to a page under docs/api/", full)
    for header in sorted({p.name for p in HEADERS.glob("*.hpp")} - documented_headers()):
        logger.warning("cpp/include/octoreach/%s has no entry in the C++ reference: add a doxygenfile "
                       "directive for it to docs/api/cpp.md", header)


def tidy_signature(app, what, name, obj, options, signature, return_annotation):
    """Compiled signatures as users write them: no ``self: octoreach._core.X`` first argument, and the compiled
    classes by the name users import them under (``octoreach.Robot``, not ``octoreach._core.Robot``)."""
    if signature is None:
        return None
    signature = re.sub(r"^\(self(: [\w.]+)?(, )?", "(", signature)
    tidy = lambda text: text and text.replace("octoreach._core.", "octoreach.")  # noqa: E731
    return tidy(signature), tidy(return_annotation)


def tidy_bases(app, name, obj, options, bases):
    """pybind11's base class of every compiled class says nothing to a user."""
    bases[:] = [b for b in bases if getattr(b, "__name__", "") != "pybind11_object"]


def setup(app: Sphinx) -> dict:
    app.connect("autodoc-process-signature", tidy_signature)
    app.connect("autodoc-process-bases", tidy_bases)
    app.add_directive("octoreach-header", HeaderDirective)
    app.connect("builder-inited", run_doxygen)
    app.connect("env-check-consistency", check_reference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
