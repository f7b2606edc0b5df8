#!/usr/bin/env bash
# The main command (README.md): installs what is missing, builds GASP (Release), then runs the
# main job on the embedded default -- a synthetic sequence GASP renders itself -- or, given a
# TUM RGB-D folder, on that folder. Results go to out/demo/.
#   scripts/run_demo.sh            # embedded synthetic default
#   scripts/run_demo.sh TUM_DIR    # a TUM RGB-D folder (depth.txt, groundtruth.txt, depth/)
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

echo "== converting to an MRPT rawlog"
"$BIN/gasp-tum2rawlog" "$DATA" "$OUT/sequence.rawlog"
if command -v rawlog-edit >/dev/null; then
  echo "== MRPT's rawlog-edit --info on it"
  (cd "$OUT" && rawlog-edit --info -i sequence.rawlog 2>&1 | grep -E "number of objects|format|sensor labels|Sensor \(" ) || true
fi

echo "== evaluating a stand-still odometry baseline against the ground truth"
echo "   (every estimated pose = the first pose: the motion GASP has to recover; GASP's own"
echo "    estimates replace it as the pipeline lands)"
awk 'BEGIN{first=""} /^#/ {next} { if (first=="") first=$2" "$3" "$4" "$5" "$6" "$7" "$8; print $1, first }' \
  "$OUT/sequence_groundtruth.txt" > "$OUT/standstill.txt"
"$BIN/gasp-eval" ate --gt "$OUT/sequence_groundtruth.txt" --est "$OUT/standstill.txt"
"$BIN/gasp-eval" rpe --gt "$OUT/sequence_groundtruth.txt" --est "$OUT/standstill.txt" --delta 1 --delta-unit frames
echo "== done: outputs in $OUT"
