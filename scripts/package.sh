#!/usr/bin/env bash
# Builds clpc's Debian package (CPack): the program, its manual page, bash completion and the
# docs, with its runtime Depends found by dpkg-shlibdeps.
#
#   bash scripts/package.sh [BUILD_DIR]     -> BUILD_DIR/package/clpc_VERSION_ARCH.deb
#
# Install it with `sudo apt install ./build/package/clpc_*.deb` (apt pulls in the Depends).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build=${1:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j "$(nproc)"
out=$(cd "$build" && pwd)/package
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$out" >/dev/null
ls "$out"/*.deb
