"""The type stubs of the compiled module (python/octoreach/_core.pyi) name what the module has."""
from __future__ import annotations

import ast
from pathlib import Path

import octoreach
from octoreach import _core


def _stub_tree():
    return ast.parse((Path(octoreach.__file__).parent / "_core.pyi").read_text())


def test_stub_classes_and_functions_match_the_module():
    tree = _stub_tree()
    stub_names = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))} | {
        n.target.id for n in tree.body
        if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name) and not n.target.id.startswith("_")}
    public = {n for n in dir(_core) if not n.startswith("_")} - {"Cancelled"}
    assert public - stub_names == set(), f"missing from the stubs: {sorted(public - stub_names)}"
    assert stub_names - set(dir(_core)) == set(), f"stubs name what the module lacks: {sorted(stub_names - set(dir(_core)))}"


def test_stub_methods_exist():
    for node in _stub_tree().body:
        if isinstance(node, ast.ClassDef) and hasattr(_core, node.name):
            cls = getattr(_core, node.name)
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and not item.name.startswith("__"):
                    assert hasattr(cls, item.name), f"{node.name}.{item.name} is in the stubs, not in the module"
    assert (Path(octoreach.__file__).parent / "py.typed").is_file()
