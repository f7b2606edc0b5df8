#!/usr/bin/env bash
# Loop detection without odometry (docs/benchmarks.md "Loop detection without odometry"):
# gasp-loops over fr1_xyz (every 10th frame; the reference as written and looked up 30 ms earlier,
# docs/evaluation.md), fr3_cabinet_kf (every frame), the simulated room (60 frames at 5 Hz, every
# 3rd) and the simulated long loop two_rooms (400 frames at 5 Hz, every 4th, loops at least 20
# keyframes back; exact truth), then their precision-recall curves as one picture; and, with
# --drift 1,30, whether the detections close a drift of 1 m and 30 deg bent into the keyframes'
# odometry chain (a second table).
# One markdown row per run: keyframes, queries, positives, detections (within 5 cm / 2 deg, and
# consistent with their information), precision and recall at the loop closer's 40 inliers, and
# the recall at 100 % precision with its threshold, by either rule.
#
# Usage: scripts/loop_detection.sh [DATA_DIR] [OUT_DIR] [BUILD_DIR] [PICTURE.svg]
#   defaults: ../shared/data/tum, a temporary directory, build/ci, OUT_DIR/loop_pr.svg
set -euo pipefail
data=${1:-../shared/data/tum}
out=${2:-$(mktemp -d)}
build=${3:-build/ci}
picture=${4:-$out/loop_pr.svg}
for p in gasp-loops gasp-simulate; do
  [ -x "$build/bin/$p" ] || { echo "error: $build/bin/$p not built" >&2; exit 1; }
done
for d in fr1_xyz fr3_cabinet_kf; do
  [ -d "$data/$d" ] || { echo "error: no data folder $data/$d" >&2; exit 1; }
done
mkdir -p "$out"
here=$(cd "$(dirname "$0")" && pwd)
if [ ! -f "$out/sim_room/groundtruth.txt" ]; then
  "$build/bin/gasp-simulate" --out "$out/sim_room" --frames 60 --rate 5 > "$out/simulate.log" 2>&1 \
    || { echo "error: gasp-simulate failed (see $out/simulate.log)" >&2; exit 1; }
fi
if [ ! -f "$out/two_rooms/groundtruth.txt" ]; then
  "$build/bin/gasp-simulate" --scene two_rooms --out "$out/two_rooms" --frames 400 --rate 5 > "$out/simulate2.log" 2>&1 \
    || { echo "error: gasp-simulate failed (see $out/simulate2.log)" >&2; exit 1; }
fi

echo "| Sequence | Keyframes | Queries | Positives | Detections (within 5 cm / 2 deg; consistent) | At >= 40 inliers: precision, recall | Recall at 100 % precision (threshold): within 5 cm / 2 deg; consistent |"
echo "|---|---|---|---|---|---|---|"
run() {  # tag, label, gasp-loops arguments...
  local tag=$1 label=$2
  shift 2
  local log="$out/$tag.log"
  local rc=0
  "$build/bin/gasp-loops" "$@" --csv "$out/$tag.csv" --curve-csv "$out/$tag-pr.csv" > "$log" 2> "$log.err" || rc=$?
  # 3: written, but --drift found no odometry chain (said in the second table).
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 3 ]; then echo "error: gasp-loops failed ($rc), see $log.err" >&2; exit 1; fi
  local v
  v() { sed -n "s/^$1: \([0-9]*\).*/\1/p" "$log"; }
  local within consistent at40 full_w full_c
  within=$(sed -n 's/^detections: [0-9]* (\([0-9]*\) within.*/\1/p' "$log")
  consistent=$(sed -n 's/^detections: .*, \([0-9]*\) consistent.*/\1/p' "$log")
  at40=$(sed -n 's/^within_5cm_2deg: at >= [0-9]* inliers precision \([0-9.]*\), recall \([0-9.]*\).*/\1, \2/p' "$log")
  full_w=$(sed -n 's/^within_5cm_2deg: .*recall at 100 % precision \([0-9.]*\)\( (at >= \([0-9]*\) inliers)\)\{0,1\}.*/\1 (\3)/p' "$log" | sed 's/ ()$/ (-)/')
  full_c=$(sed -n 's/^consistent: .*recall at 100 % precision \([0-9.]*\)\( (at >= \([0-9]*\) inliers)\)\{0,1\}.*/\1 (\3)/p' "$log" | sed 's/ ()$/ (-)/')
  printf '| %s | %s | %s | %s | %s (%s; %s) | %s | %s; %s |\n' "$label" "$(v keyframes)" "$(v queries)" "$(v positives)" \
    "$(v detections)" "$within" "$consistent" "$at40" "$full_w" "$full_c"
}
run xyz "fr1_xyz, every 10th frame" --tum "$data/fr1_xyz" --every 10
run xyz_shifted "fr1_xyz, every 10th frame, reference 30 ms earlier" --tum "$data/fr1_xyz" --every 10 --gt-offset -0.03 \
  --drift 1,30
run cabinet "fr3_cabinet_kf, every frame (min gap 3)" --tum "$data/fr3_cabinet_kf" --every 1 --min-gap 3
run sim_room "simulated room, 60 frames at 5 Hz, every 3rd (min gap 3)" --tum "$out/sim_room" --every 3 --min-gap 3
run two_rooms "simulated two_rooms, 400 frames, every 4th (min gap 20)" --tum "$out/two_rooms" --every 4 --min-gap 20 \
  --drift 1,30
python3 "$here/pr_curve.py" --curve "fr1_xyz=$out/xyz-pr.csv" --curve "fr1_xyz, reference -30 ms=$out/xyz_shifted-pr.csv" \
  --curve "fr3_cabinet_kf=$out/cabinet-pr.csv" --curve "simulated room=$out/sim_room-pr.csv" \
  --curve "simulated two_rooms=$out/two_rooms-pr.csv" --out "$picture"
echo
echo "| Sequence | Drift injected | Chain ATE [m]: as registered, with the drift | Closed ATE [m]: as registered, with the drift | Loop edges (dropped) |"
echo "|---|---|---|---|---|"
for tag in xyz_shifted two_rooms; do
  log="$out/$tag.log"
  if grep -q '^drift: not possible' "$log"; then
    printf '| %s | - | %s | - | - |\n' "$tag" "$(sed -n 's/^drift: not possible: //p' "$log" | cut -c1-90)"
    continue
  fi
  printf '| %s | %s | %s | %s | %s |\n' "$tag" "$(sed -n 's/^drift_injected: \([^(]*\) at.*/\1/p' "$log")" \
    "$(sed -n 's/^odometry_chain_ate_rmse_m: \([0-9.]*\) (with the drift: \([0-9.]*\)).*/\1, \2/p' "$log")" \
    "$(sed -n 's/^closed_ate_rmse_m: \([0-9.]*\) (with the drift: \([0-9.]*\)).*/\1, \2/p' "$log")" \
    "$(sed -n 's/^closed_ate_rmse_m: .*; \([0-9]*\) loop edges at >= [0-9]* inliers, \([0-9]*\) (with the drift: \([0-9]*\)).*/\1 (\2, \3)/p' "$log")"
done
echo "picture: $picture; logs and CSVs: $out"
