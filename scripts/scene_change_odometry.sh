#!/usr/bin/env bash
# Odometry through scenes that change (docs/odometry.md, "Scenes that change"): the simulator's
# moved-object cases of scripts/moved_object_pairs.sh, rendered at 5 Hz (the object moved at frame
# 7, 16, 25, 40 or 52 of the 60-frame path; the person at 52 only), each run through gasp-odometry
# with the scene-change attempt (default) and without it (--no-scene-change).
# scripts/scene_change_summary.py reads the folders and files this writes.
#
# Usage: scripts/scene_change_odometry.sh [BUILD_DIR] [OUT_DIR] [GASP_ODOMETRY_ARGS...]
#   defaults: build/ci, a temporary directory; extra arguments go to every gasp-odometry run
set -euo pipefail
build=${1:-build/ci}
[ -x "$build/bin/gasp-odometry" ] && [ -x "$build/bin/gasp-simulate" ] \
  || { echo "error: $build/bin/gasp-odometry and gasp-simulate must be built" >&2; exit 1; }
out=${2:-$(mktemp -d)}
shift $(( $# < 2 ? $# : 2 ))
mkdir -p "$out"
source "$(dirname "$0")/moved_object_cases.sh"
odometry_args=("$@")  # extra arguments for every gasp-odometry run
run_odometry() {  # DIR NAME M
  local variant extra rc
  for variant in on off; do
    extra=()
    [ "$variant" = off ] && extra=(--no-scene-change)
    # exit 3: some frames not tracked (a result, not an error)
    rc=0
    "$build/bin/gasp-odometry" --tum "$1" "${extra[@]}" "${odometry_args[@]}" --out "$1.$variant.txt" \
        --frames-csv "$1.$variant.csv" > "$1.$variant.log" 2>&1 || rc=$?
    [ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] \
      || { echo "error: gasp-odometry failed ($rc) for $2 at $3 (see $1.$variant.log)" >&2; exit 1; }
  done
}
simulate_moved_cases "$build" "$out" run_odometry --rate 5
echo "written to $out" >&2
