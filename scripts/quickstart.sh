#!/usr/bin/env bash
# From a fresh Debian 12 machine: installs the missing packages (apt, says which), builds shapestruct in
# Release, and runs the main job (scripts/demo.sh) on a collection the project generates itself.
# Usage: scripts/quickstart.sh [OUTPUT_DIR]      (default: ./demo-output)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
out=${1:-$root/demo-output}
scripts/install_deps.sh
echo "== configure and build (Release) =="
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DSHAPESTRUCT_BUILD_TESTS=OFF -DSHAPESTRUCT_BUILD_EXAMPLES=ON >/dev/null
cmake --build build/release -j"$(nproc)"
scripts/demo.sh build/release/examples/shapestruct "$out"
