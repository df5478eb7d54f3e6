# octoreach: `make demo` and `make test` set everything up on a fresh Debian 12 machine (Debian
# packages, a virtual environment, the project) and then run. Running them again with nothing changed
# rebuilds nothing. The project is built once, as the wheel users install (`make wheel`: scikit-build-core
# then auditwheel repair); the virtual environment installs that repaired wheel, and the same CMake build
# gives ctest its binaries and the tests their benchmark module (octoreach_bench, never in the wheel).
#
# Another interpreter gets its own environment and build: PYTHON=/path/to/python3.12 make wheel.

PYTHON ?= python3
ifeq ($(PYTHON),python3)
SUFFIX :=
else
SUFFIX := -$(notdir $(PYTHON))
endif
VENV   ?= .venv$(SUFFIX)
PY     := $(VENV)/bin/python
PIP    := $(PY) -m pip
BUILD  := build/py$(SUFFIX)
DIST   ?= dist
JOBS   ?= $(shell nproc 2>/dev/null || echo 2)
# The file that names the repaired wheel of this interpreter (written by scripts/build_wheel.sh).
WHEEL  := $(BUILD)/wheel.txt
EXTRAS := robots,test,viewer,cluster,planning

SOURCES := $(shell find cpp bindings python tests/cpp cmake urdf benchmarks/reference -type f 2>/dev/null) \
           CMakeLists.txt pyproject.toml scripts/build_wheel.sh scripts/recompress_wheel.py

.PHONY: all demo demo-exploration stubs test test-cpp test-python test-packaging install sysdeps venv benchmarks \
        clean fuzz test-sanitize wheel test-wheel sdist test-sdist check-sizes check-layers docs

all: install

sysdeps:
	@bash scripts/install_deps.sh

$(VENV)/.created: | sysdeps
	$(PYTHON) -m venv $(VENV)
	$(PIP) install -q --upgrade pip
	@touch $@

# Build requirements and release tools come from pyproject.toml ([build-system], dependency group "release").
$(VENV)/.build-deps: $(VENV)/.created pyproject.toml
	$(PIP) install -q $$($(PY) scripts/build_requires.py)
	@touch $@

$(WHEEL): $(VENV)/.build-deps $(SOURCES)
	CMAKE_BUILD_PARALLEL_LEVEL=$(JOBS) bash scripts/build_wheel.sh $(PY) $(BUILD) $(DIST)

wheel: sysdeps $(WHEEL)

# The repaired wheel with every extra, and the benchmark module beside it (site-packages/octoreach_bench).
$(BUILD)/.installed: $(WHEEL)
	$(PIP) install -q --force-reinstall --no-deps "$$(cat $(WHEEL))"
	$(PIP) install -q "$$(cat $(WHEEL))[$(EXTRAS)]"
	cp $(BUILD)/bench/octoreach_bench*.so "$$($(PY) -c 'import sysconfig; print(sysconfig.get_paths()["platlib"])')/"
	@touch $@

install: sysdeps $(BUILD)/.installed

test-cpp: install
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Two runs: each folder has its own conftest.py (fixtures; a single run would work too since the pose helpers moved to pose_helpers.py).
test-python: install
	$(PY) -m pytest -q tests/python
	$(PY) -m pytest -q tests/fuzz

# The installed package is the repaired wheel, auditwheel finds nothing outside the policy, the wheel holds
# octoreach's code once and no benchmark module, one version everywhere.
test-packaging: install
	OCTOREACH_WHEEL="$$(cat $(WHEEL))" $(PY) -m pytest -q -p no:cacheprovider tests/packaging

# A long fuzz run: the file-damage fuzzer (counts per category: cases, loaded, OSError, crashes, hangs,
# wrong errors), the input-file fuzzer over room, job and polygon files (counts per category: cases, accepted,
# clean errors, tracebacks, hangs, memory blow-ups, crashes), the cache forgeries and the property tests with
# many examples. FUZZ_CASES, FUZZ_INPUT_CASES and FUZZ_SEED choose the run.
FUZZ_CASES ?= 3000
FUZZ_INPUT_CASES ?= 2000
FUZZ_SEED  ?= 1
fuzz: install
	$(PY) tests/fuzz/file_fuzz.py --cases $(FUZZ_CASES) --seed $(FUZZ_SEED)
	$(PY) tests/fuzz/input_fuzz.py --cases $(FUZZ_INPUT_CASES) --seed $(FUZZ_SEED)
	OCTOREACH_FUZZ_CACHE_CASES=300 $(PY) -m pytest -q -s tests/fuzz/test_cache_forgery.py
	OCTOREACH_FUZZ_PROFILE=long $(PY) -m pytest -q tests/fuzz/test_properties.py tests/fuzz/test_threads.py \
	  tests/fuzz/test_wrong_types.py

# Sanitizer builds, each in its own build directory: AddressSanitizer + UndefinedBehaviorSanitizer
# (the library, the C++ tests and the Python module; ctest, then the fuzz suite and the robustness
# tests with the ASan runtime preloaded into the interpreter), and ThreadSanitizer (the C++ threads test).
SAN_CMAKE = cmake -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DBUILD_TESTING=ON \
  -Dpybind11_DIR=$$($(PY) -c 'import pybind11; print(pybind11.get_cmake_dir())') -DPython_EXECUTABLE=$(PY)
# ctest checks leaks too (the C++ tests are ours alone). The interpreter is not instrumented: the ASan
# runtime is preloaded into it, with detect_leaks=0: CPython and
# numpy keep their interned objects and module state until exit on purpose, which LeakSanitizer would
# report as thousands of leaks that are not ours. Ctrl-C tests are left out (their latency bound is
# meaningless under a sanitizer).
ASAN_RUN = LD_PRELOAD="$$(gcc -print-file-name=libasan.so) $$(gcc -print-file-name=libubsan.so)" \
  ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 PYTHONPATH=build/asan/py \
  OCTOREACH_FUZZ_FILE_CASES=120
test-sanitize: install
	$(SAN_CMAKE) -S . -B build/asan -DOCTOREACH_SANITIZE=address -DOCTOREACH_PYTHON=ON
	cmake --build build/asan -j $(JOBS)
	cd build/asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) -E packaging
	rm -rf build/asan/py && mkdir -p build/asan/py/octoreach && cp -r python/octoreach/. build/asan/py/octoreach/ \
	  && cp build/asan/*.so* build/asan/py/octoreach/ && cp -r urdf build/asan/py/octoreach/urdf
	$(ASAN_RUN) $(PY) -m pytest -q -p no:cacheprovider tests/fuzz
	$(ASAN_RUN) $(PY) -m pytest -q -p no:cacheprovider tests/python/test_robustness.py tests/python/test_file_safety.py \
	  tests/python/test_limits.py -k "not ctrl_c"
	$(SAN_CMAKE) -S . -B build/tsan -DOCTOREACH_SANITIZE=thread -DOCTOREACH_PYTHON=OFF
	cmake --build build/tsan -j $(JOBS) --target octoreach_thread_tests
	TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 build/tsan/tests/cpp/octoreach_thread_tests

test: check-sizes check-layers test-cpp test-packaging test-python docs

# Size limits of the code: prints the largest file and function, names every one over its limit, fails if any.
check-sizes:
	$(PYTHON) scripts/check_sizes.py

# The layering of docs/architecture.md: includes from cpp/src, no layer including a higher one, the table's files
# present, recipes of at most eight files.
check-layers:
	$(PYTHON) scripts/check_layers.py

# The release check: the repaired wheel in a bare Debian 12 root (debootstrap minbase + python3-venv, cached
# in build/debian12-root), installed with its extras from PyPI, runs tests/wheel/smoke.py.
test-wheel: wheel
	bash scripts/test_wheel_root.sh "$$(cat $(WHEEL))" build/debian12-root

sdist: $(VENV)/.build-deps
	$(PY) -m build --sdist --outdir $(DIST)

# Installs the sdist from source into a scratch environment (a full compile) and imports it.
test-sdist: sdist
	rm -rf build/sdist-venv && $(PYTHON) -m venv build/sdist-venv
	build/sdist-venv/bin/python -m pip install -q "$$(ls -t $(DIST)/octoreach-*.tar.gz | head -1)"
	cd build && sdist-venv/bin/python -c "import octoreach, sys; r = octoreach.robots.from_urdf(octoreach.robots.project_urdf('test_arm')); print('octoreach', octoreach.__version__, 'from the sdist:', r.dof, 'joints')"

# The documentation site into build/docs/html (MyST pages, the Python reference from the installed package, the
# C++ reference from Doxygen XML of the public headers); any warning fails it. Its tools are pyproject.toml's
# `docs` extra and Debian's doxygen. The pages' code blocks run in tests/python/test_docs.py.
$(VENV)/.docs-deps: $(VENV)/.created pyproject.toml
	$(PIP) install -q $$($(PY) -c 'import tomllib; print(" ".join(tomllib.load(open("pyproject.toml", "rb"))["project"]["optional-dependencies"]["docs"]))')
	@touch $@

docs: install $(VENV)/.docs-deps
	$(VENV)/bin/sphinx-build -b html -E -W --keep-going -n -q -d build/docs/doctrees docs build/docs/html
	@echo "octoreach: the documentation is in build/docs/html/index.html"

demo: install
	$(PY) -m octoreach.demo --out demo_out

demo-exploration: install
	$(PY) -m octoreach.exploration --scene 2 --out demo_out/exploration

benchmarks: install
	$(PY) benchmarks/ik.py
	$(PY) benchmarks/capability_map.py
	$(PY) benchmarks/surface_map.py
	$(PY) benchmarks/exploration.py
	$(PY) benchmarks/robustness.py
	$(PY) benchmarks/planning.py
	$(PY) benchmarks/python_layers.py

# Regenerates the type stubs of the compiled module (python/octoreach/_core.pyi); review the diff.
stubs: install
	$(PIP) install -q pybind11-stubgen
	$(VENV)/bin/pybind11-stubgen octoreach._core -o build/stubs
	@echo "generated build/stubs/octoreach/_core.pyi: compare with python/octoreach/_core.pyi"

clean:
	rm -rf build $(VENV) demo_out $(DIST)
