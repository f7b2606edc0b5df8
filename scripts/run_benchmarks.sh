#!/usr/bin/env bash
# The side-by-side pair benchmark of docs/benchmarks.md: GASP (with and without refinement) beside
# FPFH, SHOT, colour SHOT, SIFT and dense SIFT on the same pairs of fr3_cabinet_kf (keyframe skips
# 1, 2) and fr1_xyz (skips 10, 30, 50, 100 from every 10th frame), then the error-against-skip
# figure and one association picture per method on fr1_xyz 0 -> 30 (JPEG, to keep the repository small).
#   scripts/run_benchmarks.sh [OUT_DIR (default out/benchmarks)]
# Environment: GASP_DATA_DIR (default ../shared/data), GASP_BENCH_BUILD_DIR (default build/release),
# GASP_BENCH_NO_BUILD=1 to use an existing build, GASP_BENCH_FIG_DIR (default docs/images).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${GASP_BENCH_BUILD_DIR:-build/release}
DATA=${GASP_DATA_DIR:-../shared/data}/tum
OUT=${1:-out/benchmarks}
FIG=${GASP_BENCH_FIG_DIR:-docs/images}
if [ -z "${GASP_BENCH_NO_BUILD:-}" ]; then
  scripts/install_deps.sh
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DGASP_BUILD_BASELINES=ON
  cmake --build "$BUILD_DIR" -j"$(nproc)" --target gasp-pairs gasp-pairs-plot
fi
B=$BUILD_DIR/bin
METHODS=gasp,gasp-norefine,fpfh,shot,cshot,sift,dsift
COMMIT=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
# Only the code that produces the numbers counts (modules, programs).
if ! git diff --quiet HEAD -- modules rawlog_tools 2>/dev/null; then COMMIT="$COMMIT+uncommitted"; fi
mkdir -p "$OUT" "$FIG"
START=$(date +%s)
echo "== fr3_cabinet_kf, keyframe skips 1 and 2, every start frame (commit $COMMIT)"
"$B/gasp-pairs" --tum "$DATA/fr3_cabinet_kf" --skips 1,2 --starts-every 1 --method "$METHODS" \
    --csv "$OUT/cabinet.csv" --pairs-csv "$OUT/cabinet_pairs.csv" | tee "$OUT/cabinet.txt"
echo "== fr1_xyz, skips 10, 30, 50, 100 from every 10th frame (commit $COMMIT)"
"$B/gasp-pairs" --tum "$DATA/fr1_xyz" --skips 10,30,50,100 --starts-every 10 --method "$METHODS" \
    --csv "$OUT/fr1_xyz.csv" --pairs-csv "$OUT/fr1_xyz_pairs.csv" | tee "$OUT/fr1_xyz.txt"
echo "== wall time of both runs: $(( $(date +%s) - START )) s"
echo "== figures"
"$B/gasp-pairs-plot" --csv "$OUT/cabinet.csv,$OUT/fr1_xyz.csv" \
    --title "fr3_cabinet_kf (skip in keyframes)" --title "fr1_xyz (skip in frames; colour methods: pairs with rgb only)" \
    --out "$FIG/benchmarks_error_vs_skip.png" --caption "scripts/run_benchmarks.sh (commit $COMMIT)"
# gasp-norefine has the same associations as gasp: one GASP picture.
"$B/gasp-pairs" --tum "$DATA/fr1_xyz" --picture 0,30 --pictures-only --method "${METHODS/gasp-norefine,/}" \
    --picture-prefix "$FIG/benchmarks_fr1_xyz_0_30_" --picture-format jpg | tee "$OUT/pictures.txt"
