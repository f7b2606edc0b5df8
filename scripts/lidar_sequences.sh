#!/usr/bin/env bash
# GASP's LiDAR pairs over many simulated sequences (issue 49; docs/lidar.md, docs/benchmarks.md "A
# simulated LiDAR sequence"): gasp-simulate renders each sequence (60 sweeps at 10 Hz) and
# bench_lidar_sequence registers every pair 1, 5 and 10 sweeps apart with no prior against the
# exact truth. Prints one line per sequence: right / coarse / wrong / no estimate (those sharing at
# least 30 % of their depth in brackets) at each skip, then every wrong and coarse pose found.
# One seed of one sequence hides wrong poses that others show
# (docs/experiments/2026-12-01-lidar-scene-axes.md, 2026-12-01-lidar-claimed-basin.md).
#
# Usage: scripts/lidar_sequences.sh [BUILD_DIR] [OUT_DIR] [BENCH_ARGS...]
#   defaults: build/ci, a temporary directory; extra arguments go to every bench_lidar_sequence
#   run (e.g. --params my.yaml; not --skips: the summary names skips 1, 5 and 10). About 10
#   minutes on two cores.
set -euo pipefail
build=${1:-build/ci}
[ -x "$build/bin/bench_lidar_sequence" ] && [ -x "$build/bin/gasp-simulate" ] \
  || { echo "error: $build/bin/bench_lidar_sequence and gasp-simulate must be built" >&2; exit 1; }
out=${2:-$(mktemp -d)}
shift $(( $# < 2 ? $# : 2 ))
mkdir -p "$out"
bench_args=("$@")
# name: gasp-simulate's options (all with --frames 60 --rate 10)
sequences=(
  "room16:--sensor lidar16"
  "room16_seed2:--sensor lidar16 --seed 2"
  "room16_seed3:--sensor lidar16 --seed 3"
  "room16_seed4:--sensor lidar16 --seed 4"
  "room16_seed5:--sensor lidar16 --seed 5"
  "room16_noise_free:--sensor lidar16 --no-noise"
  "room16_clouds:--sensor lidar16 --point-clouds"
  "room16_clouds_noise_free:--sensor lidar16 --point-clouds --no-noise"
  "room32:--sensor lidar32"
  "room64:--sensor lidar64"
  "room64_noise_free:--sensor lidar64 --no-noise"
  "street16:--scene street --sensor lidar16"
  "street16_noise_free:--scene street --sensor lidar16 --no-noise"
  "street64:--scene street --sensor lidar64"
)
found=()
for entry in "${sequences[@]}"; do
  name=${entry%%:*}
  read -r -a options <<< "${entry#*:}"
  dir="$out/$name"
  rm -rf "$dir"
  "$build/bin/gasp-simulate" "${options[@]}" --frames 60 --rate 10 --out "$dir" > "$dir.simulate.log" 2>&1 \
    || { echo "error: gasp-simulate failed for $name (see $dir.simulate.log)" >&2; exit 1; }
  # Written to a temporary file beside the table, renamed once the run succeeded.
  "$build/bin/bench_lidar_sequence" "$dir" --method gasp ${bench_args[@]+"${bench_args[@]}"} > "$dir.table.txt.tmp" 2>&1 \
    || { echo "error: bench_lidar_sequence failed for $name (see $dir.table.txt.tmp)" >&2; exit 1; }
  mv "$dir.table.txt.tmp" "$dir.table.txt"
  # The table's rows: | skip | pairs | right | coarse | wrong | no estimate (sharing) | ...
  summary=$(awk -F'|' '/^\| [0-9]+ \|/ {gsub(/ /, "", $7); printf "%s/%s/%s/%s  ", $4+0, $5+0, $6+0, $7}' "$dir.table.txt")
  [ -n "$summary" ] || { echo "error: no table in $dir.table.txt" >&2; exit 1; }
  printf '%-26s %s\n' "$name" "$summary"
  while IFS= read -r line; do found+=("$name: $line"); done < <(grep -E '^(wrong|coarse) pose:' "$dir.table.txt" || true)
done
echo "(right/coarse/wrong/no estimate (sharing >= 30 %) at skips 1, 5, 10; tables in $out)"
if [ ${#found[@]} -eq 0 ]; then
  echo "no wrong or coarse pose"
else
  printf '%s\n' "${found[@]}"
fi
