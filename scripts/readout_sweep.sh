#!/usr/bin/env bash
# Sweep the rolling-shutter readout time (gasp-pairs --rolling-shutter, velocity from each frame's
# neighbours) and score each value where it was not chosen (docs/pipeline.md, "Rolling shutter"):
#   - fr1_xyz, pairs from every 20th frame at skips 10 / 30 / 50 / 100, split in two halves (pairs
#     starting before / from frame 400), the reference looked up 30 ms earlier (fr1's lag);
#   - fr3_cabinet_kf, every keyframe pair at skips 1 and 2 (another sequence and another Kinect;
#     its neighbours are keyframes, about 20 frames apart, so its velocity is a coarse average).
# With RGB_CHECK=1 it also asks the colour images (no motion capture): for each readout, the
# rotation of fr1_xyz's pairs among the first 90 frames (the ones with rgb; skips 10, 30, 50,
# every start) from the images alone against GASP's.
#
# Usage: [RGB_CHECK=1] scripts/readout_sweep.sh [BUILD_DIR] [DATA_DIR] [OUT_DIR] [READOUTS...]
#   defaults: build/ci, ../shared/data/tum, a temporary directory, 0 0.01 0.02 0.03 0.04 0.05
set -euo pipefail
build=${1:-build/ci}
data=${2:-../shared/data/tum}
out=${3:-$(mktemp -d)}
shift $(( $# < 3 ? $# : 3 ))
readouts=("$@")
[ ${#readouts[@]} -gt 0 ] || readouts=(0 0.01 0.02 0.03 0.04 0.05)
[ -x "$build/bin/gasp-pairs" ] || { echo "error: $build/bin/gasp-pairs not built" >&2; exit 1; }
for d in fr1_xyz fr3_cabinet_kf; do [ -d "$data/$d" ] || { echo "error: no data folder $data/$d" >&2; exit 1; }; done
mkdir -p "$out"
pairs() {  # name, log, gasp-pairs arguments...
  local name=$1 log=$2
  shift 2
  "$build/bin/gasp-pairs" "$@" > "$out/table_$name.txt" 2> "$out/$log" \
    || { echo "error: gasp-pairs failed for $name (see $out/$log)" >&2; exit 1; }
}
for t in "${readouts[@]}"; do
  echo "readout $t s: fr1_xyz, fr3_cabinet_kf" >&2
  pairs "fr1_$t" "progress_fr1_$t.log" --tum "$data/fr1_xyz" --skips 10,30,50,100 --starts-every 20 --method gasp \
      --gt-offset -0.03 --rolling-shutter "$t" --pairs-csv "$out/fr1_$t.csv"
  pairs "cabinet_$t" "progress_cabinet_$t.log" --tum "$data/fr3_cabinet_kf" --skips 1,2 --starts-every 1 --method gasp \
      --rolling-shutter "$t" --pairs-csv "$out/cabinet_$t.csv"
  if [ "${RGB_CHECK:-0}" = 1 ]; then
    echo "readout $t s: the rgb check on fr1_xyz frames 0-89" >&2
    pairs "rgb_$t" "progress_rgb_$t.log" --tum "$data/fr1_xyz" --skips 10,30,50 --starts-every 1 --max-pairs 80 \
        --method gasp --rgb-rotation-check --rolling-shutter "$t" --pairs-csv "$out/rgb_$t.csv"
  fi
done
python3 - "$out" "${readouts[@]}" <<'PY'
import csv, math, os, statistics, sys
out, readouts = sys.argv[1], sys.argv[2:]
rms = lambda v: math.sqrt(sum(x * x for x in v) / len(v)) if v else float("nan")
def rows(path):
    return [r for r in csv.DictReader(open(path)) if r["method"] == "gasp"]
def cell(rs, skips):
    est = [r for r in rs if r["estimated"] == "1"]
    per = [rms([float(r["r_err_deg"]) for r in est if r["skip"] == s]) for s in skips]
    return "%d | %s | %.3f / %.4f" % (len(rs) - len(est), " / ".join("%.3f" % p for p in per),
                                      rms([float(r["r_err_deg"]) for r in est]), rms([float(r["t_err_m"]) for r in est]))
print("| readout [s] | part | failures | rotation RMSE [deg] per skip | all skips: rotation [deg] / translation [m] RMSE |")
print("|---|---|---|---|---|")
for t in readouts:
    fr1 = rows("%s/fr1_%s.csv" % (out, t))
    print("| %s | fr1_xyz frames < 400 (skips 10/30/50/100) | %s |" % (t, cell([r for r in fr1 if int(r["from"]) < 400], ("10", "30", "50", "100"))))
    print("| %s | fr1_xyz frames >= 400 | %s |" % (t, cell([r for r in fr1 if int(r["from"]) >= 400], ("10", "30", "50", "100"))))
    print("| %s | fr3_cabinet_kf (skips 1/2) | %s |" % (t, cell(rows("%s/cabinet_%s.csv" % (out, t)), ("1", "2"))))
if all(os.path.exists("%s/rgb_%s.csv" % (out, t)) for t in readouts):
    print()
    print("| readout [s] | images vs estimate, fr1_xyz frames 0-89 (< 3 deg): median / RMS [deg], skips 10 ; 30 ; 50 | all |")
    print("|---|---|---|")
    for t in readouts:
        rs = [r for r in rows("%s/rgb_%s.csv" % (out, t)) if r["rgb_r_vs_est_deg"] != ""]
        per, every = [], []
        for s in ("10", "30", "50"):
            v = [x for x in (float(r["rgb_r_vs_est_deg"]) for r in rs if r["skip"] == s) if x < 3.0]
            every += v
            per.append("%.2f / %.2f" % (statistics.median(v), rms(v)) if v else "-")
        print("| %s | %s | %.2f / %.2f |" % (t, " ; ".join(per), statistics.median(every), rms(every)))
PY
