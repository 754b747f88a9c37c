#!/usr/bin/env bash
# Installs, with apt, whichever of shapestruct's build and test dependencies are missing (Debian 12), saying
# which. Needs root (or sudo). Usage: scripts/install_deps.sh [--with-optional]
set -euo pipefail
required=(g++ cmake make libeigen3-dev libspectra-dev libnanoflann-dev libboost-graph-dev doctest-dev
          libbenchmark-dev gnuplot-nox pkg-config libcpp-httplib-dev nlohmann-json3-dev libpng-dev
          libcli11-dev)
# Optional: adapters and examples that are compiled and tested only when these are present.
optional=(libopenmesh-dev libcgal-dev libopenmpi-dev openmpi-bin clang libclang-rt-14-dev chromium)
wanted=("${required[@]}")
[[ ${1:-} == --with-optional ]] && wanted+=("${optional[@]}")
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install_deps: all dependencies present"
  exit 0
fi
echo "install_deps: installing missing packages: ${missing[*]}"
sudo_cmd=()
[[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install_deps: done"
