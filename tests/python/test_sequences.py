"""gasp.odometry() and gasp.slam() over TUM folders and rawlogs; trajectories and the ATE."""
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import gasp


def test_odometry_over_a_simulated_folder_tracks_every_frame(sim_room):
    run = gasp.odometry(sim_room)
    n = len(gasp.TumFolder(sim_room))
    assert len(run.trajectory) == n and run.tracked.all() and run.keyframe[0]
    assert run.trajectory.poses.shape == (n, 4, 4) and np.allclose(run.trajectory.poses[0], np.eye(4))
    assert not run.partial and run.error == "" and len(run.loop_closures) == 0
    assert run.ate()["rmse_m"] < 0.03
    assert run.ate()["matched"] == n


def test_slam_over_a_simulated_folder(sim_room):
    run = gasp.slam(sim_room, max_frames=20)
    assert len(run.trajectory) == 20 and run.tracked.all()
    assert run.loop_closures.shape == (len(run.loop_closures), 2) and run.loop_closures.dtype == np.int64
    assert np.all(run.loop_closures[:, 0] != run.loop_closures[:, 1])
    assert run.ate()["rmse_m"] < 0.03


def run_program(build_dir, *args):
    r = subprocess.run([os.path.join(build_dir, "bin", args[0]), *args[1:]], capture_output=True, text=True)
    assert r.returncode in (0, 3), r.stdout + r.stderr
    return r


@pytest.fixture(scope="module")
def room_rawlog(build_dir, sim_room, tmp_path_factory):
    out = str(tmp_path_factory.mktemp("rawlog") / "room.rawlog")
    run_program(build_dir, "gasp-tum2rawlog", sim_room, out)
    return out


@pytest.mark.parametrize("program", ["gasp-odometry", "gasp-slam"])
@pytest.mark.parametrize("kind", ["tum", "rawlog"])
def test_a_run_gives_the_programs_trajectory(build_dir, sim_room, room_rawlog, tmp_path, program, kind):
    """The same frames, parameters and world frame as the program (gasp-slam: the first robot
    frame, where a rawlog's camera sits at its sensorPose; gasp-odometry: the first frame)."""
    path = sim_room if kind == "tum" else room_rawlog
    out = str(tmp_path / "program.txt")
    run_program(build_dir, program, "--" + kind, path, "--out", out, "--max-frames", "15")
    run = (gasp.slam if program == "gasp-slam" else gasp.odometry)(pathlib.Path(path), max_frames=15)
    expected = gasp.Trajectory.read(out)
    assert np.allclose(run.trajectory.timestamps, expected.timestamps, rtol=0, atol=1e-4)
    assert np.allclose(run.trajectory.poses, expected.poses, rtol=0, atol=1e-5)


def test_a_frame_the_odometry_refuses_ends_a_partial_run(room_rawlog, tmp_path):
    twice = tmp_path / "twice.rawlog"  # the frames again: time goes back at the second copy
    data = open(room_rawlog, "rb").read()
    twice.write_bytes(data + data)
    run = gasp.odometry(twice)
    assert run.partial and "timestamp" in run.error and len(run.trajectory) == 30 and run.tracked.all()


def test_odometry_over_a_lidar_rawlog(sim_lidar):
    rawlog = os.path.join(sim_lidar, "lidar.rawlog")
    assert gasp.odometry(rawlog, max_frames=2).ground_truth is None  # a rawlog's truth is a file of its own
    run = gasp.odometry(rawlog, max_frames=15, ground_truth=os.path.join(sim_lidar, "lidar_groundtruth.txt"))
    assert run.sweeps and len(run.trajectory) == 15 and run.tracked.all()
    assert run.ate()["rmse_m"] < 0.02


def test_intrinsics_are_given_as_an_object_a_file_or_a_preset(sim_room, tmp_path):
    own = gasp.TumFolder(sim_room).intrinsics
    reference = gasp.odometry(sim_room, max_frames=4)
    for given in (own, os.path.join(sim_room, "intrinsics.txt")):
        run = gasp.odometry(sim_room, max_frames=4, intrinsics=given)
        assert np.array_equal(run.trajectory.poses, reference.trajectory.poses)
    other = gasp.odometry(sim_room, max_frames=4, intrinsics="fr1")  # another camera: other poses
    assert not np.array_equal(other.trajectory.poses, reference.trajectory.poses)
    with pytest.raises(gasp.Error, match="nope"):
        gasp.odometry(sim_room, intrinsics="nope")


def test_trajectories_save_read_and_score(sim_room, tmp_path):
    run = gasp.odometry(sim_room, every=2)
    path = tmp_path / "t.txt"
    run.trajectory.save(str(path))
    back = gasp.Trajectory.read(str(path))
    assert np.allclose(back.timestamps, run.trajectory.timestamps)
    assert np.allclose(back.poses, run.trajectory.poses, atol=1e-6)
    mine = gasp.Trajectory(run.trajectory.timestamps, run.trajectory.poses)
    assert gasp.ate(run.ground_truth, mine)["rmse_m"] == pytest.approx(run.ate()["rmse_m"])
    with pytest.raises(ValueError, match="strictly increasing"):
        gasp.Trajectory(run.trajectory.timestamps[::-1].copy(), run.trajectory.poses)
    skewed = np.eye(4)[None].copy()
    skewed[0, 0, 1] = 0.5
    with pytest.raises(ValueError, match="not a rotation"):
        gasp.Trajectory(np.array([0.0]), skewed)
    with pytest.raises(ValueError, match="last row"):
        gasp.Trajectory(np.array([0.0]), np.full((1, 4, 4), 2.0))


def test_bad_input_is_an_error_naming_the_file(tmp_path):
    with pytest.raises(gasp.Error, match="nowhere.rawlog"):
        gasp.odometry(str(tmp_path / "nowhere.rawlog"))
    junk = tmp_path / "junk.rawlog"
    junk.write_bytes(b"not a rawlog at all")
    with pytest.raises(gasp.Error, match="junk.rawlog"):
        gasp.slam(str(junk))
    with pytest.raises(ValueError, match="every"):
        gasp.odometry(str(junk), every=0)


def test_an_input_that_breaks_mid_run_gives_a_partial_run_with_its_error(sim_room, tmp_path):
    folder = tmp_path / "room"
    shutil.copytree(sim_room, folder)
    stamps = [line.split() for line in open(folder / "depth.txt") if not line.startswith("#")]
    os.remove(folder / stamps[10][1])
    run = gasp.odometry(str(folder))
    assert run.partial and stamps[10][1] in run.error and len(run.trajectory) == 10
    assert "partial" in repr(run)


def test_real_odometry_over_fr1_xyz(fr1_xyz):
    run = gasp.odometry(fr1_xyz, max_frames=40)
    assert len(run.trajectory) == 40 and run.tracked.all()
    assert run.ate(offset_s=-0.03)["rmse_m"] < 0.03
