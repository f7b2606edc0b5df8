#!/usr/bin/env bash
# Tracking throughput (docs/benchmarks.md "Tracking throughput"): gasp-odometry and gasp-slam over
# whole sequences, as a user runs them, one after the other on an otherwise idle machine:
#   - fr1_xyz, all 798 frames (the Kinect's 30 Hz; ATE against its ground truth);
#   - a simulated fast sequence: the simulator's room at 30 Hz, 300 frames (its path over 10 s:
#     about 0.6 m/s along the wide baseline and a 180-degree roll at 1.3 rad/s, an occluder
#     walking in; docs/simulator.md; exact ground truth), made once by gasp-simulate.
# For each build given (e.g. the current main's first, then the change's), one markdown row per
# run (fr1_xyz also with --sequential: each frame segmented on the main thread when it is added;
# and with the tracking path off, the whole pipeline on every frame):
# frames on the tracking path, per-stage medians [ms per frame], wall time, frames per second of
# wall time, the real-time factor (the sequence's duration over the wall time), the cores' busy
# share (CPU time over wall time times the cores, /usr/bin/time) and the ATE.
#
# Usage: scripts/tracking_bench.sh [DATA_DIR] [OUT_DIR] BUILD_DIR [BUILD_DIR ...]
#   defaults: ../shared/data/tum, a temporary directory, build/ci
set -euo pipefail
data=${1:-../shared/data/tum}
out=${2:-$(mktemp -d)}
shift $(( $# < 2 ? $# : 2 ))
builds=("$@")
[ ${#builds[@]} -gt 0 ] || builds=(build/ci)
for b in "${builds[@]}"; do
  for p in gasp-odometry gasp-slam gasp-simulate; do
    [ -x "$b/bin/$p" ] || { echo "error: $b/bin/$p not built" >&2; exit 1; }
  done
done
[ -x /usr/bin/time ] || { echo "error: /usr/bin/time is needed (Debian package time)" >&2; exit 1; }
[ -d "$data/fr1_xyz" ] || { echo "error: no data folder $data/fr1_xyz" >&2; exit 1; }
mkdir -p "$out"
sim="$out/sim_room_fast"
if [ ! -f "$sim/groundtruth.txt" ]; then
  "${builds[0]}/bin/gasp-simulate" --scene room --frames 300 --rate 30 --out "$sim" > "$out/simulate.log" 2>&1 \
    || { echo "error: gasp-simulate failed (see $out/simulate.log)" >&2; exit 1; }
fi

# The whole pipeline on every frame: the tracking path off.
printf 'odometry:\n  tracking: false\n' > "$out/whole_pipeline.yaml"

# A report line's value: `key: value ...` -> value (the first word).
value() { sed -n "s/^$1: \([^ ]*\).*/\1/p" "$2" | head -n 1; }

row() {  # build, label, program, log
  local b=$1 label=$2 program=$3 log=$4
  local tracked medians
  tracked=$(sed -n 's/^tracking_path: \([0-9]* of [0-9]*\).*/\1/p' "$log" | head -n 1)
  medians=$(sed -n 's/^median_ms_per_frame: .*(medians: segmentation \([0-9.]*\), registration \([0-9.]*\)).*/\1, \2/p' "$log" | head -n 1)
  # The cores' busy share over the whole process (reading the input included): CPU time over
  # wall time times the cores; the rest is idle.
  local busy
  busy=$(awk -v cores="$cores" '/^cpu_s:/ {cpu = $2 + $3} /^wall_s:/ {wall = $2}
    END {if (wall > 0) printf "%.0f %%", 100 * cpu / (wall * cores); else print "?"}' "$log.time")
  printf '| %s | %s | %s | %s | %s | %s s | %s | %s | %s | %s m |\n' "$b" "$label" "$program" "${tracked:-?}" \
    "${medians:-?}" "$(value wall_time_s "$log")" "$(value fps "$log")" "$(value real_time_factor "$log")" \
    "$busy" "$(value ate_rmse_m "$log")"
}

run() {  # build, tag, program, input folder, label, extra options...
  local b=$1 tag=$2 program=$3 input=$4 label=$5
  shift 5
  local name="${tag}_${program}_${label}${1:+_${1#--}}"
  [ "${1:-}" != --params ] || name="${tag}_${program}_${label}_whole_pipeline"
  local log="$out/$name.log"
  echo "$b: $program on $label $*" >&2
  # Exit 3 (written, some frames not tracked) is a result, not a failure.
  /usr/bin/time -f "cpu_s: %U %S"$'\n'"wall_s: %e" -o "$log.time" \
    "$b/bin/$program" --tum "$input" --out "$out/$name.txt" "$@" > "$log" 2> "$log.err" || {
    rc=$?
    [ $rc -eq 3 ] || { echo "error: $program failed on $label with exit $rc (see $log.err)" >&2; exit 1; }
  }
  local shown="$program${1:+ $*}"
  [ "${1:-}" != --params ] || shown="$program (tracking: false)"
  row "$b" "$label" "$shown" "$log"
}

cores=$(nproc)
echo "| build | sequence | program | frames on the tracking path | median ms per frame (segmentation, registration) | wall time | fps | real-time factor | busy share of the $cores cores | ATE RMSE |"
echo "|---|---|---|---|---|---|---|---|---|---|"
i=0
for b in "${builds[@]}"; do
  i=$((i + 1))
  run "$b" "b$i" gasp-odometry "$data/fr1_xyz" fr1_xyz
  run "$b" "b$i" gasp-odometry "$data/fr1_xyz" fr1_xyz --sequential
  run "$b" "b$i" gasp-odometry "$data/fr1_xyz" fr1_xyz --params "$out/whole_pipeline.yaml"
  run "$b" "b$i" gasp-odometry "$sim" sim_room_fast
  run "$b" "b$i" gasp-slam "$data/fr1_xyz" fr1_xyz
done
echo "(logs and trajectories in $out)" >&2
