#!/usr/bin/env bash
# fuzz/make_seeds.sh BUILD_DIR OUT_DIR
# Seed corpora of the fuzz targets, made from the TUM folders of the shared data ($GASP_DATA_DIR,
# default ../shared/data beside the repository) and from the simulator, into OUT_DIR/<target>/:
#   fuzz_rawlog     gasp-tum2rawlog over 3 frames of each TUM folder and of a simulated sequence,
#                   shrunk to 32x24 (fuzz_seed_tum), format #2 and #1, with and without rgb;
#                   each gzip-compressed (as written) and plain (gzip -dc: the fuzzer's mutations
#                   of compressed data mostly die at the CRC, so it needs the plain ones)
#   fuzz_tum_text   first byte 0..3 (the reader, see fuzz_tum_text.cpp) + the files' first lines
#   fuzz_depth_png  the shrunk depth and rgb PNGs (32x24, 64x48)
#   fuzz_params     every key at its default (fuzz_seed_params), gasp-graphslam.ini, small inis,
#                   the params file of defaults (params/gasp.yaml) and a small one
# BUILD_DIR is a GASP_FUZZ build; the programs used are built there if missing. The corpora are not
# committed (only crash inputs, as regression tests).
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 BUILD_DIR OUT_DIR" >&2
  exit 2
fi
build=$(cd "$1" && pwd)
out=$2
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/.." && pwd)
data=${GASP_DATA_DIR:-$repo/../shared/data}
tum=$data/tum
bin=$build/bin

need=()
for p in gasp-simulate gasp-tum2rawlog fuzz_seed_tum fuzz_seed_params; do
  [[ -x $bin/$p ]] || need+=("$p")
done
if [[ ${#need[@]} -gt 0 ]]; then
  cmake --build "$build" -j"${GASP_JOBS:-2}" --target "${need[@]}"
fi

mkdir -p "$out"/{fuzz_rawlog,fuzz_tum_text,fuzz_depth_png,fuzz_params}
work=$(mktemp -d "${TMPDIR:-/tmp}/gasp_seeds.XXXXXX")
trap 'rm -rf "$work"' EXIT

# ---- small TUM folders: the real ones and a simulated one, 3 frames shrunk
sources=()
for name in fr1_desk9 fr3_cabinet_kf fr1_xyz; do
  if [[ -f $tum/$name/depth.txt ]]; then
    sources+=("$name:$tum/$name")
  else
    echo "make_seeds: no $tum/$name (GASP_DATA_DIR), skipped" >&2
  fi
done
"$bin/gasp-simulate" --frames 8 --seed 3 --out "$work/sim" > /dev/null
sources+=("sim:$work/sim")

for entry in "${sources[@]}"; do
  name=${entry%%:*}
  src=${entry#*:}
  for size in "32 24" "64 48"; do
    set -- $size
    tiny=$work/${name}_$1x$2
    "$bin/fuzz_seed_tum" "$src" "$tiny" 3 "$1" "$2"
  done
  tiny=$work/${name}_32x24
  r=$out/fuzz_rawlog
  "$bin/gasp-tum2rawlog" "$tiny" "$r/${name}_f2.rawlog" > /dev/null
  "$bin/gasp-tum2rawlog" "$tiny" "$r/${name}_f1.rawlog" --format 1 > /dev/null
  "$bin/gasp-tum2rawlog" "$tiny" "$r/${name}_f2_norgb.rawlog" --no-rgb --max-frames 2 > /dev/null
  for f in "$r/${name}"_f*.rawlog; do
    gzip -dc < "$f" > "${f%.rawlog}_plain.rawlog"
  done
  rm -f "$r"/*_groundtruth.txt  # gasp-tum2rawlog's OUT_groundtruth.txt: not a rawlog

  p=$out/fuzz_depth_png
  for t in "$work/${name}_32x24" "$work/${name}_64x48"; do
    base=$(basename "$t")
    cp "$t/depth/$(ls "$t/depth" | head -n 1)" "$p/${base}_depth.png"
    if [[ -n $(ls "$t/rgb") ]]; then cp "$t/rgb/$(ls "$t/rgb" | head -n 1)" "$p/${base}_rgb.png"; fi
  done

  x=$out/fuzz_tum_text
  { printf '\x00'; head -n 12 "$src/depth.txt"; } > "$x/${name}_depth_list"
  if [[ -f $src/rgb.txt ]]; then { printf '\x00'; head -n 12 "$src/rgb.txt"; } > "$x/${name}_rgb_list"; fi
  if [[ -f $src/groundtruth.txt ]]; then
    { printf '\x01'; head -n 25 "$src/groundtruth.txt"; } > "$x/${name}_groundtruth"
  fi
  { printf '\x02'; cat "$tiny/intrinsics.txt"; } > "$x/${name}_intrinsics"
  # a whole folder: depth.txt %% rgb.txt %% groundtruth.txt %% intrinsics.txt (the shrunk one's)
  {
    printf '\x03'; cat "$tiny/depth.txt"; echo '%%'; cat "$tiny/rgb.txt"; echo '%%'
    if [[ -f $tiny/groundtruth.txt ]]; then cat "$tiny/groundtruth.txt"; fi
    echo '%%'; cat "$tiny/intrinsics.txt"
  } > "$x/${name}_folder"
done

# ---- params / ini
q=$out/fuzz_params
"$bin/fuzz_seed_params" "$q"
cp "$repo/rawlog_tools/gasp-graphslam/gasp-graphslam.ini" "$q/gasp-graphslam.ini"
cp "$repo/params/gasp.yaml" "$q/params_defaults.yaml"
printf 'associate:\n  lambda: 0.6  # a comment\n  candidate_key: mean\nrefine:\n  dense_gates_m: [0.1, 0.03]\n  dense_loss: "cauchy"\ncertify:\n  model_error_t_m:\n    - 0.01\npose_graph: {}\n' > "$q/params_small.yaml"
printf '[M_superpixelMap_00_creationOpts]\ntarget_patch_area_m2 = 0.004\nseed = 7\ncrease_borders = false\n[M_superpixelMap_00_likelihoodOpts]\nsigma_m = 0.02\nmax_distance_m = 0.10\ncandidate_key = mean\n[M_superpixelMap_00_renderOpts]\nstyle = points\npoint_step_px = 4\n' > "$q/plugin_map_small.ini"
printf '[GaspAligner]\ncandidates = 30\nrefinement_loss = huber\ndense_gates_m = 0.2, 0.05, 0.02\ncost_replace = inf\nmutual_check = yes\n' > "$q/plugin_aligner_small.ini"
printf '[CGaspOdometryNRD]\nkeyframe_distance_m = 0.2\nsensor_label = KINECT\nscene_change = 0\n[CGaspLoopClosureERD]\nsearch_radius_m = 0.8\nmax_candidates = 4\nenabled = 0\n[CGaspPoseGraphGSO]\nmax_iterations = 7\ndrop_chi2 = 0\n' > "$q/graphslam_small.ini"

for t in fuzz_rawlog fuzz_tum_text fuzz_depth_png fuzz_params; do
  printf 'make_seeds: %-15s %3d files, %7d bytes\n' "$t" "$(ls "$out/$t" | wc -l)" "$(cat "$out/$t"/* | wc -c)"
done
