# octoreach: `make demo` and `make test` set everything up on a fresh Debian 12
# machine (Debian packages, a virtual environment, the project) and then run.
# Running them again with nothing changed rebuilds nothing.

PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
PIP    := $(PY) -m pip
BUILD  := build/py
JOBS   ?= $(shell nproc 2>/dev/null || echo 2)

SOURCES := $(shell find cpp bindings python tests/cpp tests/packaging cmake urdf -type f 2>/dev/null) \
           CMakeLists.txt pyproject.toml

.PHONY: all demo demo-exploration stubs test test-cpp test-python install sysdeps venv benchmarks clean

all: install

sysdeps:
	@bash scripts/install_deps.sh

$(VENV)/.created: | sysdeps
	$(PYTHON) -m venv $(VENV)
	$(PIP) install -q --upgrade pip
	@touch $@

# Build requirements come from pyproject.toml's [build-system] table.
$(VENV)/.build-deps: $(VENV)/.created pyproject.toml
	$(PIP) install -q $$($(PY) scripts/build_requires.py)
	@touch $@

$(BUILD)/.installed: $(VENV)/.build-deps $(SOURCES)
	CMAKE_BUILD_PARALLEL_LEVEL=$(JOBS) $(PIP) install --no-build-isolation \
	  -Cbuild-dir=$(BUILD) -Ccmake.define.BUILD_TESTING=ON ".[robots,test,viewer]"
	@touch $@

install: sysdeps $(BUILD)/.installed

test-cpp: install
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-python: install
	$(PY) -m pytest -q tests/python

test: test-cpp test-python

demo: install
	$(PY) -m octoreach.demo --out demo_out

demo-exploration: install
	$(PY) -m octoreach.exploration --scene 2 --out demo_out/exploration

benchmarks: install
	$(PY) benchmarks/ik.py
	$(PY) benchmarks/capability_map.py
	$(PY) benchmarks/surface_map.py
	$(PY) benchmarks/exploration.py

# Regenerates the type stubs of the compiled module (python/octoreach/_core.pyi); review the diff.
stubs: install
	$(PIP) install -q pybind11-stubgen
	$(VENV)/bin/pybind11-stubgen octoreach._core -o build/stubs
	@echo "generated build/stubs/octoreach/_core.pyi: compare with python/octoreach/_core.pyi"

clean:
	rm -rf build $(VENV) demo_out
