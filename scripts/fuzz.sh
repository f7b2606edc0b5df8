#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS] [TARGET ...]
# libFuzzer over GASP's readers (fuzz/, docs/experiments/2026-11-28-fuzzing.md): configures and
# builds build/fuzz with clang (GASP_FUZZ=ON: ASan + UBSan + coverage) if needed, makes the seed
# corpora (fuzz/make_seeds.sh) and runs each target (default: all four, one after the other) for
# SECONDS (default 600). Prints per target the executions, exec/s, corpus size and findings
# (crash-*, leak-*, timeout-*, oom-* files in build/fuzz/artifacts/TARGET/) and exits 1 when any
# target found something in this run.
#   GASP_FUZZ_BUILD  build folder (default build/fuzz); GASP_JOBS: build jobs (default 2)
#   GASP_FUZZ_SKIP_BUILD=1  run the targets of the build folder as they are (no configure/build)
#   GASP_DATA_DIR    real data for the seeds (default ../shared/data)
# The corpus each run grows is kept in BUILD/corpus/TARGET (not committed); the seeds in
# BUILD/seeds/TARGET are remade when that folder is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(fuzz_rawlog fuzz_tum_text fuzz_depth_png fuzz_params)
if ! [[ $seconds =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: scripts/fuzz.sh [SECONDS] [TARGET ...] (SECONDS a positive integer, got '$seconds')" >&2
  exit 2
fi
build=${GASP_FUZZ_BUILD:-build/fuzz}
jobs=${GASP_JOBS:-2}

if [[ ${GASP_FUZZ_SKIP_BUILD:-0} != 1 ]]; then
  if ! grep -qs '^GASP_FUZZ:BOOL=ON' "$build/CMakeCache.txt"; then
    cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DGASP_FUZZ=ON -DGASP_BUILD_TESTS=OFF \
      -DGASP_BUILD_BENCHMARKS=OFF -DGASP_BUILD_BASELINES=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
  fi
  cmake --build "$build" -j"$jobs" --target fuzz_all
fi
build=$(cd "$build" && pwd)

if [[ ! -d $build/seeds/fuzz_params ]]; then
  rm -rf "$build/seeds"
  fuzz/make_seeds.sh "$build" "$build/seeds.tmp"
  mv "$build/seeds.tmp" "$build/seeds"
fi

max_len() {
  case $1 in
    fuzz_rawlog) echo 65536 ;;     # the seeds: 3 frames of 32x24, 5-25 KB plain
    fuzz_tum_text) echo 8192 ;;
    fuzz_depth_png) echo 16384 ;;  # the seeds: 32x24 and 64x48 PNGs, up to ~9 KB
    fuzz_params) echo 16384 ;;     # every key at its default: ~5 KB
    *) echo 4096 ;;
  esac
}

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
found=0
summary=()
for t in "${targets[@]}"; do
  exe=$build/bin/$t
  [[ -x $exe ]] || { echo "fuzz.sh: no $exe" >&2; exit 2; }
  corpus=$build/corpus/$t
  artifacts=$build/artifacts/$t
  log=$build/logs/$t.log
  mkdir -p "$corpus" "$artifacts" "$build/logs"
  before=$(ls "$artifacts" | sort)
  echo "== $t: ${seconds} s (log: $log)"
  set +e
  "$exe" "$corpus" "$build/seeds/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="$(max_len "$t")" -artifact_prefix="$artifacts/" -print_final_stats=1 > "$log" 2>&1
  rc=$?
  set -e
  stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -n 1; }
  execs=$(stat number_of_executed_units)
  rate=$(stat average_exec_per_sec)
  new=$(comm -13 <(echo "$before") <(ls "$artifacts" | sort) | grep -E '^(crash|leak|timeout|oom|slow-unit)-' || true)
  n_new=$(printf '%s' "$new" | grep -c . || true)
  line=$(printf '%-15s %6s s  executions %10s  exec/s %6s  corpus %5d files  findings %d  rc %d' \
    "$t" "$seconds" "${execs:-?}" "${rate:-?}" "$(ls "$corpus" | wc -l)" "$n_new" "$rc")
  echo "$line"
  summary+=("$line")
  if [[ $n_new -gt 0 || $rc -ne 0 ]]; then
    found=1
    for f in $new; do echo "   finding: $artifacts/$f"; done
    grep -m 3 -E '^==[0-9]+==ERROR|runtime error|^SUMMARY|Deadly signal|out-of-memory|timeout' "$log" | sed 's/^/   /' || true
  fi
done
echo "== summary"
printf '%s\n' "${summary[@]}"
exit $found
