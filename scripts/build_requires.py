"""Prints the [build-system] requirements of pyproject.toml, one shell word each."""
import pathlib
import tomllib

data = tomllib.loads((pathlib.Path(__file__).resolve().parent.parent / "pyproject.toml").read_text())
print(" ".join(data["build-system"]["requires"]))
