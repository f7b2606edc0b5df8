#!/usr/bin/env bash
# The unit tests (the ctest suite) under AddressSanitizer + UndefinedBehaviorSanitizer
# (docs/experiments/2026-11-28-sanitizers.md). Builds every GASP target with
# -DGASP_SANITIZE=address,undefined (RelWithDebInfo, the baselines as CI builds them, no benchmarks)
# in build/asan, runs ctest with every finding fatal and its stack printed, prints the wall time of
# the test run, and exits non-zero on any build error, failed test or sanitizer finding.
#   scripts/sanitize.sh [extra ctest arguments, e.g. -R '^core\.']
# Environment: GASP_SANITIZE_BUILD_DIR (default build/asan), GASP_SANITIZE_JOBS (default nproc),
# GASP_SANITIZE_NO_BUILD=1 to run an existing build, GASP_SANITIZE_EXCLUDE (a ctest -E regex; see
# below), GASP_DATA_DIR as for scripts/run_tests.sh.
# CI does not run this (it runs scripts/run_tests.sh); it is a script anyone can run.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD_DIR=${GASP_SANITIZE_BUILD_DIR:-build/asan}
JOBS=${GASP_SANITIZE_JOBS:-$(nproc)}

# Every finding ends the process with a non-zero exit and a symbolised stack. These options hold
# for the build too: gtest_discover_tests runs each test program when it is built.
# LeakSanitizer: see scripts/lsan.supp for the third-party leaks it is told to ignore.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:exitcode=23:detect_leaks=1:strict_init_order=1:check_initialization_order=1:detect_stack_use_after_return=0:print_summary=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:exitcode=24:print_summary=1"
export LSAN_OPTIONS="suppressions=$ROOT/scripts/lsan.supp:print_suppressions=1:exitcode=23"

if [ -z "${GASP_SANITIZE_NO_BUILD:-}" ]; then
  scripts/install_deps.sh
  BUILD_START=$(date +%s)
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGASP_SANITIZE=address,undefined \
    -DGASP_BUILD_TESTS=ON -DGASP_BUILD_BENCHMARKS=OFF -DGASP_BUILD_BASELINES=ON \
    -DGASP_PYTHON=OFF  # python3 cannot load a module built with ASan unless the runtime is preloaded
  cmake --build "$BUILD_DIR" -j"$JOBS"
  echo "sanitize: build took $(($(date +%s) - BUILD_START)) s"
fi

# Excluded: superpixels.SuperpixelsSynthetic.PatchesRespectSurfaceEdges segments 60 frames of
# each synthetic scene; under ASan it took 1097 s (2-core machine under load), beyond its 600 s
# ctest timeout. It passed then, run directly; the superpixels' other tests (bad input, borders,
# repeatability on real frames) run the same code here. GASP_SANITIZE_EXCLUDE='' runs everything.
EXCLUDE=${GASP_SANITIZE_EXCLUDE-'^superpixels\.SuperpixelsSynthetic\.PatchesRespectSurfaceEdges$'}
cd "$BUILD_DIR"
START=$(date +%s)
rc=0
if [ -n "$EXCLUDE" ]; then
  echo "sanitize: excluded (ctest -E): $EXCLUDE"
  ctest --output-on-failure -j"$JOBS" -E "$EXCLUDE" "$@" || rc=$?
else
  ctest --output-on-failure -j"$JOBS" "$@" || rc=$?
fi
echo "sanitize: test run took $(($(date +%s) - START)) s wall (ctest exit $rc)"
exit $rc
