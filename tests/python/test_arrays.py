"""Depth arrays in, patches out: gasp.segment() and the checks on what Python hands it."""
import numpy as np
import pytest

import gasp

K = gasp.Intrinsics(fx=525.0, fy=525.0, cx=319.5, cy=239.5, width=640, height=480)


def wall_and_box():
    """A wall 2 m ahead with a box face 0.5 m in front of it (metres, float32)."""
    d = np.full((480, 640), 2.0, dtype=np.float32)
    d[150:330, 220:420] = 1.5
    return d


def test_a_wall_and_a_box_give_patches_on_them():
    v = gasp.segment(wall_and_box(), K)
    n = len(v)
    assert n > 20
    assert v.labels.shape == (480, 640) and v.labels.dtype == np.int32
    assert v.labels.min() >= -1 and v.labels.max() == n - 1
    assert v.centroids.shape == (n, 3) and v.normals.shape == (n, 3)
    assert np.all((v.centroids[:, 2] > 1.45) & (v.centroids[:, 2] < 2.05))
    assert np.allclose(np.linalg.norm(v.normals, axis=1), 1.0, atol=1e-6)
    assert np.all(v.normals[:, 2] < -0.99)  # facing the camera (z ahead)
    assert np.all(v.areas > 0) and v.areas.shape == (n,)
    assert v.pixel_counts.sum() == np.count_nonzero(v.labels >= 0)
    assert len(v.adjacency) == n
    # a patch's centroid is the mean of its pixels' points
    i = int(v.labels[240, 320])
    assert abs(v.centroids[i, 2] - 1.5) < 1e-3


def test_uint16_units_and_float_metres_give_the_same_patches():
    d = wall_and_box()
    raw = np.round(d * 5000).astype(np.uint16)
    a, b, c = gasp.segment(d, K), gasp.segment(raw, K), gasp.segment(d.astype(np.float64), K)
    assert np.array_equal(a.labels, b.labels) and np.array_equal(a.labels, c.labels)
    # another scale: the same image in millimetres (float rounding may move a few k-means borders)
    mm = gasp.segment(np.round(d * 1000).astype(np.uint16), K, depth_units_per_metre=1000)
    assert np.allclose(mm.depth, d, rtol=0, atol=1e-6) and len(mm) == len(a)


def test_an_array_through_pickle_keeps_its_dtype():
    import pickle
    d = np.round(wall_and_box() * 5000).astype(np.uint16)
    back = pickle.loads(pickle.dumps(d))  # its dtype is another object, an equivalent one
    assert np.array_equal(gasp.segment(back, K).labels, gasp.segment(d, K).labels)


def test_a_strided_array_is_read_as_its_values():
    big = np.zeros((480, 1280), dtype=np.float32)
    big[:, ::2] = wall_and_box()
    assert np.array_equal(gasp.segment(big[:, ::2], K).labels, gasp.segment(wall_and_box(), K).labels)


def test_no_depth_gives_no_patches():
    v = gasp.segment(np.zeros((480, 640), np.float32), K)
    assert len(v) == 0 and np.all(v.labels == -1) and v.centroids.shape == (0, 3)


@pytest.mark.parametrize("dtype", [np.int32, np.float16, np.uint8, np.bool_, np.complex64])
def test_a_wrong_dtype_is_a_type_error_naming_it(dtype):
    with pytest.raises(TypeError, match="depth: dtype .*; expected uint16"):
        gasp.segment(np.ones((480, 640), dtype=dtype), K)


@pytest.mark.parametrize("shape", [(640, 480), (480, 640, 1), (480,), (0, 0)])
def test_a_wrong_shape_is_a_value_error_naming_it(shape):
    with pytest.raises(ValueError, match=r"depth: .*shape"):
        gasp.segment(np.ones(shape, dtype=np.float32), K)


@pytest.mark.parametrize("bad,word", [(np.nan, "NaN"), (np.inf, "infinite"), (-1.0, "negative")])
def test_nan_infinite_or_negative_depth_is_a_value_error(bad, word):
    d = wall_and_box()
    d[10, 10] = bad
    d[20, 20] = bad
    with pytest.raises(ValueError, match="depth: 2 %s value" % word):
        gasp.segment(d, K)


def test_not_an_array_is_a_type_error():
    with pytest.raises(TypeError, match="depth: expected a numpy array, got list"):
        gasp.segment([[1.0]], K)


def test_a_bad_scale_is_a_value_error():
    with pytest.raises(ValueError, match="depth_units_per_metre"):
        gasp.segment(np.ones((480, 640), np.uint16), K, depth_units_per_metre=0)
    with pytest.raises(ValueError, match="beyond float32"):
        gasp.segment(np.ones((480, 640), np.uint16), K, depth_units_per_metre=1e-40)


def test_intrinsics_are_checked_and_presets_load():
    with pytest.raises(gasp.Error):
        gasp.Intrinsics(fx=-1, fy=525, cx=319.5, cy=239.5, width=640, height=480)
    fr1 = gasp.Intrinsics.preset("fr1")
    assert (fr1.width, fr1.height) == (640, 480) and fr1.fx == pytest.approx(517.3)
    assert fr1.K.shape == (3, 3)
    with pytest.raises(gasp.Error, match="nope"):
        gasp.Intrinsics.preset("nope")
    assert fr1 == gasp.Intrinsics.preset("fr1") and fr1 != K and fr1 != None and None not in [fr1]  # noqa: E711
