#!/usr/bin/env bash
# `make test-wheel`: the repaired wheel in a bare Debian 12 root, as a new user's machine has it.
#   scripts/test_wheel_root.sh WHEEL ROOT [--extras-line]
# ROOT is made once with `debootstrap --variant=minbase --include=python3,python3-venv bookworm` (no
# compiler, no -dev package, none of the C++ libraries the wheel vendors) and kept; each run enters it with
# chroot and runs tests/wheel/smoke.py with Debian's python3, which makes a fresh virtual environment in it,
# installs the wheel with its extras from PyPI and checks every vendored library. Needs root and debootstrap
# (scripts/install_deps.sh installs it).
set -euo pipefail
wheel=$(readlink -f "$1")
root=$2
shift 2
here=$(cd "$(dirname "$0")/.." && pwd)
if [ "$(id -u)" -ne 0 ]; then echo "test-wheel: chroot needs root" >&2; exit 1; fi
if [ ! -f "$root/.octoreach-root" ]; then
  command -v debootstrap >/dev/null || { echo "test-wheel: debootstrap is missing (scripts/install_deps.sh)" >&2; exit 1; }
  rm -rf "$root.partial"
  mkdir -p "$(dirname "$root")"
  debootstrap --variant=minbase --include=python3,python3-venv bookworm "$root.partial"
  touch "$root.partial/.octoreach-root"
  rm -rf "$root"
  mv "$root.partial" "$root"
fi
for lib in liboctomap libfcl libassimp liburdfdom_model libqhull_r; do   # the root stays bare
  if ls "$root"/usr/lib/x86_64-linux-gnu/$lib.so* >/dev/null 2>&1; then
    echo "test-wheel: $root has $lib: not a bare root" >&2; exit 1
  fi
done
if chroot "$root" sh -c 'command -v cc gcc g++' >/dev/null 2>&1; then echo "test-wheel: $root has a compiler" >&2; exit 1; fi

# Network settings and the host's CA certificates (a proxy's CA, if the host trusts one) for pip in the root.
cp /etc/resolv.conf "$root/etc/resolv.conf"
cp /etc/ssl/certs/ca-certificates.crt "$root/etc/host-ca-certificates.crt"
rm -rf "$root/smoke" && mkdir -p "$root/smoke"
cp "$wheel" "$here/tests/wheel/smoke.py" "$root/smoke/"
mounted=()
cleanup() {
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount "${mounted[i]}" 2>/dev/null || umount -l "${mounted[i]}"; done
}
trap cleanup EXIT
for fs in proc dev dev/pts dev/shm; do
  mount --bind "/$fs" "$root/$fs"
  mounted+=("$root/$fs")
done
chroot "$root" /usr/bin/env -i PATH=/usr/bin:/bin LANG=C.UTF-8 PIP_CERT=/etc/host-ca-certificates.crt \
  python3 /smoke/smoke.py "/smoke/$(basename "$wheel")" "$@"
