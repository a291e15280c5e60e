#!/usr/bin/env bash
# Sets up, builds clpc and compiles the bundled example for the Haas UMC-750.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build --target clpc
build/clpc compile examples/bracket.cls -t haas-umc750 -o examples/bracket.nc
echo "--- examples/bracket.nc"
cat examples/bracket.nc
