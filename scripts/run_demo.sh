#!/usr/bin/env bash
# The main command (README.md): installs what is missing, builds GASP (Release), then runs the
# main job on the embedded default -- a synthetic sequence GASP renders itself -- or, given a
# TUM RGB-D folder, on that folder. Results go to out/demo/.
#   scripts/run_demo.sh            # embedded synthetic default
#   scripts/run_demo.sh TUM_DIR    # a TUM RGB-D folder (depth.txt, depth/; groundtruth.txt for the benchmark)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
BUILD_DIR=${GASP_BUILD_DIR:-build/release}
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DGASP_BUILD_TESTS=OFF >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)"
BIN="$BUILD_DIR/bin"
OUT=out/demo
mkdir -p "$OUT"

if [ $# -ge 1 ]; then
  DATA="$1"
  echo "== using the TUM folder $DATA"
else
  DATA="$OUT/synthetic"
  echo "== rendering the embedded synthetic sequence (scene 'room', seed 1)"
  "$BIN/gasp-simulate" --scene room --seed 1 --out "$DATA"
fi

if [ $# -ge 1 ]; then
  # A sample for MRPT's check only: a whole TUM sequence with colour would take ~0.7 MB a frame.
  echo "== converting its first 30 frames to an MRPT rawlog"
  "$BIN/gasp-tum2rawlog" --max-frames 30 "$DATA" "$OUT/sequence.rawlog"
else
  echo "== converting to an MRPT rawlog"
  "$BIN/gasp-tum2rawlog" "$DATA" "$OUT/sequence.rawlog"
fi
if command -v rawlog-edit >/dev/null; then
  echo "== MRPT's rawlog-edit --info on it"
  (cd "$OUT" && rawlog-edit --info -i sequence.rawlog 2>&1 | grep -E "number of objects|format|sensor labels|Sensor \(" ) || true
fi

if [ $# -ge 1 ]; then
  if [ -f "$DATA/groundtruth.txt" ]; then
    echo "== the pair benchmark (paper protocol) on $DATA: skips 10,20,30,40, start every 10th frame"
    "$BIN/gasp-pairs" --tum "$DATA" --skips 10,20,30,40 --starts-every 10 --method gasp,gasp-norefine \
      --csv "$OUT/pairs.csv" --pairs-csv "$OUT/pairs_detail.csv"
  else
    echo "== no groundtruth.txt in $DATA: the pair benchmark needs ground truth, skipped"
  fi
  N=$(grep -vc '^#' "$DATA/depth.txt" || true)
  if [ "${N:-0}" -gt 10 ]; then
    echo "== associations and pose of the pair 0 -> 10"
    "$BIN/gasp-associate" --tum "$DATA" --from 0 --to 10 --out "$OUT/associations_0_10.png" || true
  fi
else
  # The hard cases GASP is for, each as one pair: associate, register, print the pose error,
  # write the association picture (same colour = associated; green line = correct, red = wrong).
  for pair in "3 9 wide-baseline (0.59 m, 12 deg)" "44 59 180-degree-roll" "33 36 occluder-appears" "18 24 partial-overlap"; do
    set -- $pair
    echo "== ${*:3}: frames $1 -> $2"
    "$BIN/gasp-associate" --tum "$DATA" --from "$1" --to "$2" --out "$OUT/associations_$1_$2.png" \
      | grep -E "^(patches_a|patches_b|associations|precision|inliers|verified_associations|verified_precision|pose_error|pose:|picture)" || true
  done
  echo "== the pair benchmark on the synthetic sequence: pairs (i, i+3) and (i, i+6), every 6th frame"
  "$BIN/gasp-pairs" --tum "$DATA" --skips 3,6 --starts-every 6 --method gasp,gasp-norefine \
    --csv "$OUT/pairs.csv" --pairs-csv "$OUT/pairs_detail.csv"
fi
echo "== done: outputs in $OUT (association pictures, pairs.csv, sequence.rawlog)"
