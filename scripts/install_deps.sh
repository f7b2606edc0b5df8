#!/usr/bin/env bash
# Installs the Debian 12 packages GASP needs to build, test and run -- only those missing.
# Why each is needed: docs/dependencies.md.
set -euo pipefail

PACKAGES=(
  cmake g++ make pkg-config         # toolchain
  libeigen3-dev                     # geometry, poses, alignment
  libopencv-dev                     # images: PNG/JPEG I/O, image processing
  libmrpt-dev mrpt-apps mrpt-common # rawlogs and observations; rawlog-edit; MRPT's sample RGB-D rawlog
  libceres-dev                      # pose refinement (point-to-plane)
  libnanoflann-dev                  # KD-trees
  libpcl-dev                        # baselines of the pair benchmark: FPFH, SHOT, colour SHOT
  libopenmpi-dev openmpi-bin        # gasp-slam --mpi: a map-building job over MPI processes
  libtbb-dev                        # parallel loops
  libcli11-dev                      # command-line parsing of the programs
  zlib1g-dev                        # rawlogs' gzip streams checked to their end
  libgtest-dev libgmock-dev         # tests
  libbenchmark-dev                  # benchmarks
  python3                           # the summary scripts (scripts/*.py) and their test
  pybind11-dev python3-dev          # the Python module gasp (GASP_PYTHON)
  python3-numpy python3-pytest      # its arrays, and its tests
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install_deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
