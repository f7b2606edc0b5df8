#!/usr/bin/env bash
# Pairs on the plane-dominated scenes of the simulator (issue 46; docs/simulator.md): for each
# scene, gasp-simulate renders 150 frames of its hand-held camera (Kinect noise, seed 1) and
# gasp-pairs registers every pair from every 5th frame at skips 5, 10 and 20 against the exact
# truth. scripts/plane_scenes_summary.py then counts, per scene and skip, the right and wrong
# full poses, the partial poses and the pairs without an estimate.
#
# Usage: scripts/plane_scenes.sh [BUILD_DIR] [OUT_DIR] [GASP_PAIRS_ARGS...]
#   defaults: build/ci, a temporary directory; extra arguments go to every gasp-pairs run (e.g.
#   --params my.yaml)
set -euo pipefail
build=${1:-build/ci}
[ -x "$build/bin/gasp-pairs" ] && [ -x "$build/bin/gasp-simulate" ] \
  || { echo "error: $build/bin/gasp-pairs and gasp-simulate must be built" >&2; exit 1; }
out=${2:-$(mktemp -d)}
shift $(( $# < 2 ? $# : 2 ))
mkdir -p "$out"
pairs_args=("$@")
scenes=(floor_0 floor_1 floor_3 floor_6 wall_door corridor_walk table_top)
for scene in "${scenes[@]}"; do
  dir="$out/$scene"
  rm -rf "$dir"
  "$build/bin/gasp-simulate" --scene "$scene" --frames 150 --seed 1 --out "$dir" > "$dir.simulate.log" 2>&1 \
    || { echo "error: gasp-simulate failed for $scene (see $dir.simulate.log)" >&2; exit 1; }
  "$build/bin/gasp-pairs" --tum "$dir" --skips 5,10,20 --starts-every 5 --method gasp "${pairs_args[@]}" \
      --pairs-csv "$dir.pairs.csv" > "$dir.table.txt" 2> "$dir.progress.log" \
    || { echo "error: gasp-pairs failed for $scene (see $dir.progress.log)" >&2; exit 1; }
  echo "$scene: $dir.pairs.csv" >&2
done
python3 "$(dirname "$0")/plane_scenes_summary.py" "${scenes[@]/#/$out/}"
