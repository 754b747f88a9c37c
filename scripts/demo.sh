#!/usr/bin/env bash
# The main job: runs the shapestruct command-line tool end to end on collections it generates.
# Usage: scripts/demo.sh PATH/TO/shapestruct OUTPUT_DIR
set -euo pipefail
cli=$1
out=$2
mkdir -p "$out"
run() { echo "+ $*"; "$@"; }
stamp=$(date +%Y%m%d-%H%M%S)
out="$out/run-$stamp"   # a fresh folder per run: nothing from an earlier run is overwritten
mkdir -p "$out"

echo "== 1. generate synthetic collections with ground truth =="
run "$cli" generate creatures 6 -o "$out/creatures" --seed 1
run "$cli" generate chairs 24 -o "$out/chairs" --seed 1

echo "== 2. inspect them =="
run "$cli" inspect "$out/creatures/$(ls "$out/creatures" | grep -m1 -E '\.(off|obj|ply)$')"

if "$cli" --help | grep -q "^  match "; then
  echo "== 3. blended intrinsic map between two creatures =="
  a=$(ls "$out/creatures" | grep -E '^creature_.*\.off$' | sed -n 1p)
  b=$(ls "$out/creatures" | grep -E '^creature_.*\.off$' | sed -n 2p)
  run "$cli" match "$out/creatures/$a" "$out/creatures/$b" -o "$out/creature_map.map" --colors "$out/creature_map"
fi
if "$cli" --help | grep -q "^  templates "; then
  echo "== 4. part-based templates learned from the chairs =="
  run "$cli" templates "$out/chairs" -o "$out/chair_templates"
fi
echo
echo "shapestruct demo finished; results are in: $out"
