#!/usr/bin/env bash
# Sweep the ratio of depth to lateral scale on fr1_xyz and score each value on two halves of the
# sequence (pairs starting before / from frame 400): a diagnostic of the fr1 sensor's depth
# calibration (docs/pipeline.md, "A depth-free check"), not a setting GASP uses.
#
# For a factor k, the focal lengths are multiplied by k and the depth by k (--depth-scale 5000/k):
# lateral coordinates stay as they are, depths grow by k. The lens coefficients are rescaled with
# the focal lengths (k1 k^2, k2 k^4, p1 p2 k, k3 k^6), so the undistortion's pixel map is the same
# for every k. The intrinsics are fr1's (the script is for fr1 sequences; DATA_DIR only says where
# the folder is). The reference is looked up 30 ms earlier (fr1's lag).
#
# With RGB_CHECK=1 it also asks the colour images (no motion capture): for each k, the rotation
# of the pairs among the first 90 frames (the ones with rgb; skips 10, 30, 50, every start) from
# the images alone (--rgb-rotation-check with the colour camera's own intrinsics, --rgb-intrinsics
# fr1) against GASP's, and scores the motion-capture pairs that start from frame 100 on, which the
# images never saw.
#
# Usage: [RGB_CHECK=1] scripts/depth_ratio_sweep.sh [BUILD_DIR] [DATA_DIR] [OUT_DIR] [FACTORS...]
#   defaults: build/ci, ../shared/data/tum/fr1_xyz, a temporary directory, 1.000 1.025 1.050 1.075 1.100
set -euo pipefail
build=${1:-build/ci}
data=${2:-../shared/data/tum/fr1_xyz}
out=${3:-$(mktemp -d)}
shift $(( $# < 3 ? $# : 3 ))
factors=("$@")
[ ${#factors[@]} -gt 0 ] || factors=(1.000 1.025 1.050 1.075 1.100)
[ -x "$build/bin/gasp-pairs" ] || { echo "error: $build/bin/gasp-pairs not built" >&2; exit 1; }
[ -d "$data" ] || { echo "error: no data folder $data" >&2; exit 1; }
mkdir -p "$out"
for k in "${factors[@]}"; do
  python3 - "$k" > "$out/intrinsics_k$k.txt" <<'EOF'
import sys
k = float(sys.argv[1])
print("width: 640\nheight: 480\nfx: %.4f\nfy: %.4f\ncx: 318.6\ncy: 255.3" % (517.3 * k, 516.5 * k))
# Normalised coordinates shrink by 1/k: rescale so that each pixel maps where it did at k = 1.
print("distortion: %.6f %.6f %.6f %.6f %.6f" % (0.2624 * k**2, -0.9531 * k**4, -0.0054 * k, 0.0026 * k, 1.1633 * k**6))
EOF
  ds=$(python3 -c "import sys; print('%.3f' % (5000.0 / float(sys.argv[1])))" "$k")
  echo "k $k: gasp-pairs --intrinsics $out/intrinsics_k$k.txt --depth-scale $ds" >&2
  "$build/bin/gasp-pairs" --tum "$data" --skips 10,30,50,100 --starts-every 20 --method gasp --gt-offset -0.03 \
      --intrinsics "$out/intrinsics_k$k.txt" --depth-scale "$ds" --pairs-csv "$out/pairs_k$k.csv" > "$out/table_k$k.txt" \
      2> "$out/progress_k$k.log" || { echo "error: gasp-pairs failed for k = $k (see $out/progress_k$k.log)" >&2; exit 1; }
done
if [ "${RGB_CHECK:-0}" = 1 ]; then
  for k in "${factors[@]}"; do
    ds=$(python3 -c "import sys; print('%.3f' % (5000.0 / float(sys.argv[1])))" "$k")
    echo "k $k: the rgb check on frames 0-89" >&2
    "$build/bin/gasp-pairs" --tum "$data" --skips 10,30,50 --starts-every 1 --max-pairs 80 --method gasp \
        --rgb-rotation-check --rgb-intrinsics fr1 --intrinsics "$out/intrinsics_k$k.txt" --depth-scale "$ds" \
        --pairs-csv "$out/rgb_k$k.csv" > /dev/null 2> "$out/progress_rgb_k$k.log" \
      || { echo "error: gasp-pairs (rgb check) failed for k = $k (see $out/progress_rgb_k$k.log)" >&2; exit 1; }
  done
fi
python3 - "$out" "${factors[@]}" <<'EOF'
import csv, math, os, statistics, sys
out, factors = sys.argv[1], sys.argv[2:]
print("| k | half | estimates | failures | rotation RMSE [deg] (skips 10 / 30 / 50 / 100) | all skips: rotation [deg] / translation [m] RMSE |")
print("|---|---|---|---|---|---|")
rms = lambda v: math.sqrt(sum(x * x for x in v) / len(v)) if v else float("nan")
for k in factors:
    rows = [r for r in csv.DictReader(open("%s/pairs_k%s.csv" % (out, k))) if r["method"] == "gasp"]
    for half, keep in (("frames < 400", lambda i: i < 400), ("frames >= 400", lambda i: i >= 400)):
        rs = [r for r in rows if keep(int(r["from"]))]
        est = [r for r in rs if r["estimated"] == "1"]
        per = [rms([float(r["r_err_deg"]) for r in est if r["skip"] == s]) for s in ("10", "30", "50", "100")]
        print("| %s | %s | %d | %d | %s | %.3f / %.4f |" % (
            k, half, len(est), len(rs) - len(est), " / ".join("%.2f" % p for p in per),
            rms([float(r["r_err_deg"]) for r in est]), rms([float(r["t_err_m"]) for r in est])))
if all(os.path.exists("%s/rgb_k%s.csv" % (out, k)) for k in factors):
    print()
    print("| k | images vs estimate, frames 0-89 (< 3 deg): median / RMS [deg], skips 10 ; 30 ; 50 | all | motion capture, pairs from frame 100: rotation RMSE, skips 10 / 30 / 50 / 100 | all r [deg] / t [m] |")
    print("|---|---|---|---|---|")
    for k in factors:
        rows = [r for r in csv.DictReader(open("%s/rgb_k%s.csv" % (out, k))) if r["method"] == "gasp" and r["rgb_r_vs_est_deg"] != ""]
        per, every = [], []
        for s in ("10", "30", "50"):
            v = [x for x in (float(r["rgb_r_vs_est_deg"]) for r in rows if r["skip"] == s) if x < 3.0]
            every += v
            per.append("%.2f / %.2f" % (statistics.median(v), rms(v)) if v else "-")
        held = [r for r in csv.DictReader(open("%s/pairs_k%s.csv" % (out, k)))
                if r["method"] == "gasp" and int(r["from"]) >= 100 and r["estimated"] == "1"]
        hp = [rms([float(r["r_err_deg"]) for r in held if r["skip"] == s]) for s in ("10", "30", "50", "100")]
        print("| %s | %s | %.2f / %.2f | %s | %.3f / %.4f |" % (
            k, " ; ".join(per), statistics.median(every), rms(every), " / ".join("%.2f" % p for p in hp),
            rms([float(r["r_err_deg"]) for r in held]), rms([float(r["t_err_m"]) for r in held])))
EOF
