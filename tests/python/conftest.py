"""Fixtures of the Python module's tests: the build's programs (GASP_BUILD_DIR), the shared real
data (GASP_DATA_DIR; tests needing it skip with a message where it is absent) and simulated
sequences with exact ground truth."""
import os
import subprocess

import pytest


def _build_dir():
    return os.environ.get("GASP_BUILD_DIR", "")


@pytest.fixture(scope="session")
def build_dir():
    d = _build_dir()
    if not d or not os.path.isdir(os.path.join(d, "bin")):
        pytest.skip("GASP_BUILD_DIR (the CMake build folder) is not set: run the tests through ctest")
    return d


@pytest.fixture(scope="session")
def fr1_xyz():
    # GASP_DATA_DIR at run time, as the C++ tests read it, else the build's default
    root = os.environ.get("GASP_DATA_DIR") or os.environ.get("GASP_DATA_DIR_DEFAULT", "")
    d = os.path.join(root, "tum", "fr1_xyz")
    if not os.path.isfile(os.path.join(d, "depth.txt")):
        pytest.skip("real data absent: %s (see ../shared/data/README)" % d)
    return d


def _simulate(build_dir, out, *args):
    subprocess.run([os.path.join(build_dir, "bin", "gasp-simulate"), "--out", str(out), *args],
                   check=True, stdout=subprocess.DEVNULL)
    return str(out)


@pytest.fixture(scope="session")
def sim_room(build_dir, tmp_path_factory):
    """A simulated TUM folder: 30 frames of the room at 5 Hz, Kinect-like noise, exact truth."""
    return _simulate(build_dir, tmp_path_factory.mktemp("room"), "--frames", "30", "--rate", "5")


@pytest.fixture(scope="session")
def sim_lidar(build_dir, tmp_path_factory):
    """A simulated folder: lidar.rawlog (60 sweeps of a 16-laser LiDAR at 10 Hz) and
    lidar_groundtruth.txt."""
    return _simulate(build_dir, tmp_path_factory.mktemp("lidar"), "--frames", "60", "--rate", "10",
                     "--sensor", "lidar16")
