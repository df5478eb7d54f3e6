#!/usr/bin/env bash
# Installs the Debian packages octoreach needs, only those that are missing: the one list of them.
# Runs as root or through sudo. Used by `make demo` and `make test` (every package); with --build only what
# building the library and the Python package from source needs (`pip install .`, the CMake install).
set -euo pipefail
BUILD=(
  build-essential cmake ninja-build pkg-config python3-dev python3-venv
  libeigen3-dev liboctomap-dev liburdfdom-dev libconsole-bridge-dev libtinyxml-dev
  libfcl-dev libccd-dev libqhull-dev libassimp-dev zlib1g-dev
)
# Development: the C++ tests (GoogleTest), the benchmark references (KDL), viewer screenshots (Chromium),
# the bare-root wheel test (debootstrap), the documentation's C++ reference (Doxygen).
DEVELOP=(git python3 python3-pip liborocos-kdl-dev libgtest-dev chromium chromium-driver debootstrap doxygen)
case "${1:-}" in
  --build) PACKAGES=("${BUILD[@]}") ;;
  "") PACKAGES=("${BUILD[@]}" "${DEVELOP[@]}") ;;
  *) echo "usage: $0 [--build]" >&2; exit 2 ;;
esac
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "octoreach: installing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
