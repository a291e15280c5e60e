#!/usr/bin/env bash
# Installs the Debian packages clpc needs to build and test. Idempotent: packages already
# present are not reinstalled, and apt is only asked when something is missing.
#
#   scripts/setup.sh            build + unit-test packages
#   scripts/setup.sh --tests    also the independent checkers the test suite starts
#                               (LinuxCNC's rs274 interpreter, Chromium for the plot test,
#                               Python's jsonschema for the machine-file schema test,
#                               Emscripten for the browser page, web/)
set -euo pipefail

build_pkgs=(cmake ninja-build g++ clang re2c bison pkg-config libeigen3-dev
            libtomlplusplus-dev libgtest-dev libgmock-dev libcli11-dev libbenchmark-dev time
            help2man gzip dpkg-dev file)
test_pkgs=(linuxcnc-uspace chromium python3 python3-jsonschema man-db bsdextrautils emscripten)

want=("${build_pkgs[@]}")
[[ ${1:-} == --tests ]] && want+=("${test_pkgs[@]}")

missing=()
for p in "${want[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "setup: all packages present"
  exit 0
fi

SUDO=""
if ((EUID != 0)); then
  command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
