#!/usr/bin/env bash
# The whole test suite, from a fresh machine: installs missing packages, builds, and runs
#   1. every unit test and the concept (static) tests, under AddressSanitizer and UndefinedBehaviorSanitizer;
#   2. the command-line tool's end-to-end tests, the package-consumer tests and the header check (Release);
#   3. the data-driven tests (label "data"), a bounded subset of each benchmark, when $SHAPESTRUCT_DATA points
#      at the benchmark data; they report themselves skipped otherwise.
# Usage: scripts/test.sh            (build folders: build/test, build/sanitize)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scripts/install_deps.sh --with-optional
jobs=$(nproc)

# The unit tests are compiled once, with the sanitizers at -O1 (a third of the compile time of -O2 -g with
# them); the optimised build holds what needs speed or the installed tool: the data-driven tests, the
# command-line tool and its end-to-end tests, the header self-containment check and the package consumers.
echo "== build unit tests (ASan + UBSan, -O1, warnings as errors) =="
cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 -DSHAPESTRUCT_SANITIZE=ON \
      -DSHAPESTRUCT_BUILD_TESTS=ON -DSHAPESTRUCT_BUILD_UNIT_TESTS=ON -DSHAPESTRUCT_BUILD_DATA_TESTS=OFF \
      -DSHAPESTRUCT_CHECK_HEADERS=OFF -DSHAPESTRUCT_BUILD_EXAMPLES=OFF -DSHAPESTRUCT_INSTALL=OFF >/dev/null
cmake --build build/sanitize -j"$jobs"
echo "== unit tests under AddressSanitizer and UndefinedBehaviorSanitizer =="
(cd build/sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
   ctest --output-on-failure -j"$jobs" -L unit)

echo "== build tool, data-driven tests, header and package checks (Release) =="
cmake -S . -B build/test -DCMAKE_BUILD_TYPE=Release -DSHAPESTRUCT_BUILD_TESTS=ON -DSHAPESTRUCT_BUILD_UNIT_TESTS=OFF \
      -DSHAPESTRUCT_BUILD_DATA_TESTS=ON -DSHAPESTRUCT_BUILD_EXAMPLES=ON >/dev/null
cmake --build build/test -j"$jobs"
echo "== end-to-end and package tests =="
(cd build/test && ctest --output-on-failure -j"$jobs" -L unit)

echo "== data-driven tests =="
if [[ -z ${SHAPESTRUCT_DATA:-} || ! -d ${SHAPESTRUCT_DATA} ]]; then
  echo "SHAPESTRUCT_DATA is not set: the data-driven tests report themselves skipped (see docs/data.md)"
fi
(cd build/test && ctest --output-on-failure -j"$jobs" -L data)
