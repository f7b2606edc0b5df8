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
# name scene move [move ...] (the cases of moved_object_pairs.sh)
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
    if [ "$name" = person ] && [ "$m" -lt 52 ]; then continue; fi  # it appears at frame 38
    dir="$out/${name}_$m"
    args=()
    for mv in "${words[@]:2}"; do args+=(--move "$mv@$m"); done
    echo "$name moved at frame $m" >&2
    "$build/bin/gasp-simulate" --scene "$scene" --rate 5 "${args[@]}" --out "$dir" > "$dir.sim.txt" \
      || { echo "error: gasp-simulate failed for $name at $m (see $dir.sim.txt)" >&2; exit 1; }
    for variant in on off; do
      extra=()
      [ "$variant" = off ] && extra=(--no-scene-change)
      # exit 3: some frames not tracked (a result, not an error)
      rc=0
      "$build/bin/gasp-odometry" --tum "$dir" "${extra[@]}" "$@" --out "$dir.$variant.txt" \
          --frames-csv "$dir.$variant.csv" > "$dir.$variant.log" 2>&1 || rc=$?
      [ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] \
        || { echo "error: gasp-odometry failed ($rc) for $name at $m (see $dir.$variant.log)" >&2; exit 1; }
    done
  done
done
echo "written to $out" >&2
