#!/usr/bin/env bash
# From a fresh Debian 12 machine: installs the missing packages (apt, says which), builds shapestruct in
# Release, and runs the main job (scripts/demo.sh: `shapestruct analyze` on generated chairs with ground truth,
# printing the accuracy, the report's path and how to open the explorer).
# Usage: scripts/quickstart.sh [OUTPUT_DIR]      (default: ./demo-output)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
out=${1:-$root/demo-output}
scripts/install_deps.sh
echo "== configure and build (Release) =="
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DSHAPESTRUCT_BUILD_TESTS=OFF -DSHAPESTRUCT_BUILD_EXAMPLES=ON >/dev/null
# The tool and the explorer's page only: the examples and tests are not needed for the main job.
targets=(shapestruct_cli)
help=$(cmake --build build/release --target help)
[[ $help == *explore_page* ]] && targets+=(explore_page)
cmake --build build/release -j"$(nproc)" --target "${targets[@]}"
scripts/demo.sh build/release/examples/shapestruct "$out"
