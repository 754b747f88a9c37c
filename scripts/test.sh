#!/usr/bin/env bash
# The whole test suite, from a fresh machine: installs missing packages, builds, and runs
#   1. every unit test, the concept (static) tests and the package-consumer tests (Release + asserts);
#   2. the same unit tests again under AddressSanitizer and UndefinedBehaviorSanitizer;
#   3. the data-driven tests (label "data") when $SHAPESTRUCT_DATA points at the benchmark data, on a bounded
#      subset unless SHAPESTRUCT_DATA_FULL=1; they report themselves skipped otherwise.
# Usage: scripts/test.sh            (build folders: build/test, build/sanitize)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scripts/install_deps.sh --with-optional
jobs=$(nproc)

echo "== build (Release, asserts on) =="
cmake -S . -B build/test -DCMAKE_BUILD_TYPE=Release -DSHAPESTRUCT_BUILD_TESTS=ON -DSHAPESTRUCT_BUILD_EXAMPLES=ON >/dev/null
cmake --build build/test -j"$jobs"
echo "== unit tests =="
(cd build/test && ctest --output-on-failure -j"$jobs" -LE data)

echo "== build (ASan + UBSan) =="
cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHAPESTRUCT_SANITIZE=ON \
      -DSHAPESTRUCT_BUILD_TESTS=ON -DSHAPESTRUCT_BUILD_EXAMPLES=OFF -DSHAPESTRUCT_INSTALL=OFF >/dev/null
cmake --build build/sanitize -j"$jobs"
echo "== unit tests under sanitizers =="
(cd build/sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j"$jobs" -L unit)

echo "== data-driven tests =="
if [[ -n ${SHAPESTRUCT_DATA:-} && -d ${SHAPESTRUCT_DATA} ]]; then
  (cd build/test && ctest --output-on-failure -j"$jobs" -L data)
else
  echo "SHAPESTRUCT_DATA is not set: the data-driven tests are skipped (see docs/data.md)"
  (cd build/test && ctest --output-on-failure -j"$jobs" -L data)
fi
