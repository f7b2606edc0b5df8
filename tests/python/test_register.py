"""gasp.register(): the pose and its frames against the simulator's exact truth, and real frames."""
import numpy as np
import pytest

import gasp


def truth(folder, i, j):
    """T_target_source of source frame i and target frame j."""
    return np.linalg.inv(folder.ground_truth(j)) @ folder.ground_truth(i)


def test_a_simulated_pair_registers_to_the_exact_truth_in_both_directions(sim_room):
    room = gasp.TumFolder(sim_room)
    assert len(room) == 30 and room.timestamps.shape == (30,)
    a, b = room.depth(0), room.depth(3)
    r = gasp.register(a, b, room.intrinsics)
    assert r.success, r.reason
    t, deg = gasp.pose_error(r.T_target_source, truth(room, 0, 3))
    assert t < 0.02 and deg < 1.0
    back = gasp.register(b, a, room.intrinsics)
    assert back.success, back.reason
    t, deg = gasp.pose_error(back.T_target_source, truth(room, 3, 0))
    assert t < 0.02 and deg < 1.0


def test_the_result_carries_the_certificate_and_the_associations(sim_room):
    room = gasp.TumFolder(sim_room)
    source, target = gasp.segment(room.depth(0), room.intrinsics), gasp.segment(room.depth(3), room.intrinsics)
    r = gasp.register(source, target)  # views: no intrinsics needed
    assert r.success and r.estimated and not r.partial and not r.degenerate and r.reason == ""
    info = r.information
    assert info.shape == (6, 6) and np.allclose(info, info.T) and np.all(np.linalg.eigvalsh(info) > 0)
    assert r.edge_information.shape == (6, 6)
    assert r.unobservable_directions.shape[0] == 6 and r.unobservable_directions.shape[1] == 0
    assert r.free_space["passed"] and r.free_space["consistent"] > 0
    v = r.verified
    assert v.dtype == np.int32 and v.shape[1] == 2 and len(v) >= 20
    assert r.associations.shape[1] == 2 and r.inliers > 0
    # verified associations join patches that the pose brings together
    src, tgt = r.source.centroids[v[:, 0]], r.target.centroids[v[:, 1]]
    moved = src @ r.T_target_source[:3, :3].T + r.T_target_source[:3, 3]
    assert np.median(np.linalg.norm(moved - tgt, axis=1)) < 0.05
    assert r.timings["total_ms"] > 0


def test_views_without_overlap_give_no_estimate_not_an_error():
    K = gasp.Intrinsics(fx=525.0, fy=525.0, cx=319.5, cy=239.5, width=640, height=480)
    empty = np.zeros((480, 640), np.float32)
    wall = np.full((480, 640), 2.0, np.float32)
    r = gasp.register(empty, wall, K)
    assert not r.estimated and r.reason
    r = gasp.register(wall, wall, K)  # a plane leaves directions free: never a full pose
    assert not r.success


def test_arrays_need_intrinsics_and_the_same_shape(sim_room):
    room = gasp.TumFolder(sim_room)
    with pytest.raises(ValueError, match="source: a depth array needs intrinsics"):
        gasp.register(room.depth(0), room.depth(1))
    with pytest.raises(ValueError, match="target depth: shape"):
        gasp.register(room.depth(0), room.depth(1)[:100], room.intrinsics)


def test_a_missing_folder_is_an_error_naming_it(tmp_path):
    with pytest.raises(gasp.Error, match="nowhere"):
        gasp.TumFolder(str(tmp_path / "nowhere"))


def test_two_real_frames_register_as_the_program_does(fr1_xyz):
    folder = gasp.TumFolder(fr1_xyz)
    r = gasp.register(folder.depth(0), folder.depth(30), folder.intrinsics)
    assert r.success, r.reason
    t, deg = gasp.pose_error(r.T_target_source, truth(folder, 0, 30))
    assert t < 0.03 and deg < 2.0
