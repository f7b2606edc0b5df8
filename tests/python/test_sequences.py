"""gasp.odometry() and gasp.slam() over TUM folders and rawlogs; trajectories and the ATE."""
import os
import shutil

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
    assert run.loop_closures.shape[1] == 2
    assert run.ate()["rmse_m"] < 0.03


def test_odometry_over_a_lidar_rawlog(sim_lidar):
    rawlog = os.path.join(sim_lidar, "lidar.rawlog")
    assert gasp.odometry(rawlog, max_frames=2).ground_truth is None  # a rawlog's truth is a file of its own
    run = gasp.odometry(rawlog, max_frames=15, ground_truth=os.path.join(sim_lidar, "lidar_groundtruth.txt"))
    assert run.sweeps and len(run.trajectory) == 15 and run.tracked.all()
    assert run.ate()["rmse_m"] < 0.02


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
