#!/usr/bin/env bash
# Pairs across an object that moved (docs/pipeline.md, "Objects that moved"): the
# simulator renders its scenes with one object (or a table with what stands on it) moved at frame
# M (gasp-simulate --move), and gasp-pairs registers every pair from every 3rd frame at skips 3, 6,
# 10 and 15; the pairs from before M to M or later straddle the move, the others are static.
# scripts/moved_object_summary.py reads the folders and CSVs this writes.
#
# Usage: scripts/moved_object_pairs.sh [BUILD_DIR] [OUT_DIR] [GASP_PAIRS_ARGS...]
#   defaults: build/ci, a temporary directory; extra arguments go to every gasp-pairs run
#   (e.g. --params lifted.yaml, a params file whose section certify sets
#   visibility_max_two_way_violation_ratio: 1, the two-way limit lifted; docs/parameters.md)
set -euo pipefail
build=${1:-build/ci}
[ -x "$build/bin/gasp-pairs" ] && [ -x "$build/bin/gasp-simulate" ] \
  || { echo "error: $build/bin/gasp-pairs and gasp-simulate must be built" >&2; exit 1; }
out=${2:-$(mktemp -d)}
shift $(( $# < 2 ? $# : 2 ))
mkdir -p "$out"
source "$(dirname "$0")/moved_object_cases.sh"
pairs_args=("$@")  # extra arguments for every gasp-pairs run
register_pairs() {  # DIR NAME M
  "$build/bin/gasp-pairs" --tum "$1" --skips 3,6,10,15 --starts-every 3 --method gasp "${pairs_args[@]}" \
      --pairs-csv "$1.pairs.csv" > "$1.table.txt" 2> "$1.progress.log" \
    || { echo "error: gasp-pairs failed for $2 at $3 (see $1.progress.log)" >&2; exit 1; }
}
simulate_moved_cases "$build" "$out" register_pairs
echo "written to $out" >&2
