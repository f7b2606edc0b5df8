#!/usr/bin/env bash
# The test command (README.md; .ci/run runs exactly this): installs what is missing, builds
# everything with warnings as errors, runs the whole GoogleTest suite through ctest.
# Real-data tests read ../shared/data (or $GASP_DATA_DIR) and skip with a message when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
BUILD_DIR=${GASP_TEST_BUILD_DIR:-build/ci}
JOBS=$(nproc)
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DGASP_WARNINGS_AS_ERRORS=ON -DGASP_BUILD_TESTS=ON -DGASP_BUILD_BASELINES=ON -DGASP_WITH_MPI=ON -DGASP_PYTHON=ON
cmake --build "$BUILD_DIR" -j"$JOBS"
cd "$BUILD_DIR"
ctest --output-on-failure -j"$JOBS"
