#!/usr/bin/env bash
# Pairs across an object that moved (docs/pipeline.md, "Objects that moved"): the
# simulator renders its scenes with one object (or a table with what stands on it) moved at frame
# M (gasp-simulate --move), and gasp-pairs registers every pair from every 3rd frame at skips 3, 6,
# 10 and 15; the pairs from before M to M or later straddle the move, the others are static.
# scripts/moved_object_summary.py reads the folders and CSVs this writes.
#
# Usage: scripts/moved_object_pairs.sh [BUILD_DIR] [OUT_DIR] [GASP_PAIRS_ARGS...]
#   defaults: build/ci, a temporary directory; extra arguments go to every gasp-pairs run
#   (e.g. --max-two-way-violation 1)
set -euo pipefail
build=${1:-build/ci}
[ -x "$build/bin/gasp-pairs" ] && [ -x "$build/bin/gasp-simulate" ] \
  || { echo "error: $build/bin/gasp-pairs and gasp-simulate must be built" >&2; exit 1; }
out=${2:-$(mktemp -d)}
shift $(( $# < 2 ? $# : 2 ))
mkdir -p "$out"
# name scene move [move ...] (several moves of one case, at the same frame)
cases=(
  "chair room chair:0,-0.6,0"
  "chair_turned room chair:0.3,0,0,90"
  "table room table:0,-0.5,0 book:0,-0.5,0 vase:0,-0.5,0 ball:0,-0.5,0"
  "cabinet room cabinet:-0.4,0.3,0,30"
  "big_ball room big_ball:0,-0.8,0"
  "bin room bin:-0.6,-0.3,0"
  "crate room crate:0.5,0.3,0"
  "person room occluder:0,0.8,0"
  "box repeated box0:0.3,0.4,0,20"
  "sparse_box sparse box:0.5,0.5,0,20"
)
frames=(7 16 25 40 52)
for c in "${cases[@]}"; do
  read -ra words <<< "$c"
  name=${words[0]} scene=${words[1]}
  for m in "${frames[@]}"; do
    dir="$out/${name}_$m"
    args=()
    for mv in "${words[@]:2}"; do args+=(--move "$mv@$m"); done
    # The person appears at frame 38: only at 52 does every straddling pair (from frame 37 on at
    # skip 15, every 3rd frame: 39 on) see it before the move as well as after.
    if [ "$name" = person ] && [ "$m" -lt 52 ]; then continue; fi
    echo "$name moved at frame $m" >&2
    "$build/bin/gasp-simulate" --scene "$scene" "${args[@]}" --out "$dir" > "$dir.sim.txt" \
      || { echo "error: gasp-simulate failed for $name at $m (see $dir.sim.txt)" >&2; exit 1; }
    "$build/bin/gasp-pairs" --tum "$dir" --skips 3,6,10,15 --starts-every 3 --method gasp "$@" \
        --pairs-csv "$dir.pairs.csv" > "$dir.table.txt" 2> "$dir.progress.log" \
      || { echo "error: gasp-pairs failed for $name at $m (see $dir.progress.log)" >&2; exit 1; }
  done
done
echo "written to $out" >&2
