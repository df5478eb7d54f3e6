#!/usr/bin/env bash
# Installs the Debian packages octoreach needs, only those that are missing.
# Runs as root or through sudo. Used by `make demo` and `make test`.
set -euo pipefail
PACKAGES=(
  build-essential cmake ninja-build git pkg-config
  python3 python3-dev python3-venv python3-pip
  libeigen3-dev liboctomap-dev liborocos-kdl-dev liburdfdom-dev libconsole-bridge-dev libtinyxml-dev
  libfcl-dev libccd-dev libqhull-dev libassimp-dev libgtest-dev zlib1g-dev
  chromium chromium-driver
)
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
