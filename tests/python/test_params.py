"""The params file from Python: dicts over the defaults, checked by the C++ reader."""
import math
import os

import pytest

import gasp

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_the_defaults_are_the_params_file_of_defaults():
    p = gasp.default_params()
    assert list(p)[:6] == ["segment", "associate", "hypothesise", "refine", "certify", "retry"]
    assert {"odometry", "loop_closure", "pose_graph", "lidar"} <= set(p)
    assert p == gasp.load_params(os.path.join(REPO, "params", "gasp.yaml"))
    assert p["associate"]["cost_replace"] == math.inf
    assert isinstance(p["segment"]["crease_borders"], bool)
    assert isinstance(p["refine"]["dense_gates_m"], list)


def test_a_dict_is_read_over_the_defaults_and_saved_and_loaded_back(tmp_path):
    change = {"segment": {"target_patch_area_m2": 0.006}, "refine": {"dense_gates_m": [0.2, 0.05]},
              "associate": {"candidate_key": "mean"}}
    path = tmp_path / "p.yaml"
    gasp.save_params(change, path)
    back = gasp.load_params(path)
    expected = gasp.default_params()
    for section, keys in change.items():
        expected[section].update(keys)
    assert back == expected
    assert gasp.load_params(path) == gasp.load_params(str(path))
    assert not [f for f in os.listdir(tmp_path) if f != "p.yaml"]  # no temporary file left
    # the full dict reads back to itself
    assert gasp.load_params(path) == gasp._yaml_dict(gasp.params_yaml(back))


def test_numpy_scalars_are_values():
    import numpy as np
    text = gasp.params_yaml({"segment": {"target_patch_area_m2": np.float64(0.006),
                                         "crease_borders": np.bool_(False), "seed": np.int64(3)}})
    back = gasp._yaml_dict(text)["segment"]
    assert back["target_patch_area_m2"] == 0.006 and back["crease_borders"] is False and back["seed"] == 3


def test_params_change_what_a_function_does():
    import numpy as np
    K = gasp.Intrinsics(fx=525.0, fy=525.0, cx=319.5, cy=239.5, width=640, height=480)
    d = np.full((480, 640), 2.0, np.float32)
    fine, coarse = gasp.segment(d, K), gasp.segment(d, K, params={"segment": {"target_patch_area_m2": 0.016}})
    assert len(coarse) < len(fine) / 2


@pytest.mark.parametrize("params,error,match", [
    ({"segment": {"no_such_key": 1}}, gasp.Error, "no_such_key"),
    ({"no_such_section": {}}, gasp.Error, "no_such_section"),
    ({"segment": {"target_patch_area_m2": -1.0}}, gasp.Error, "target_patch_area_m2"),
    ({"segment": {"min_patch_pixels": 2.5}}, gasp.Error, "min_patch_pixels"),
    ({"segment": {"crease_borders": "maybe"}}, gasp.Error, "crease_borders"),
    ({"associate": {"candidate_key": "x: y"}}, ValueError, "candidate_key"),
    ({"associate": {"candidate_key": "mean\n"}}, ValueError, "candidate_key"),
    ({"segment": 3}, TypeError, "section 'segment' must be a dict"),
    ({"segment": {"seed": object()}}, TypeError, "segment.seed"),
    (42, TypeError, "params: expected None"),
])
def test_a_bad_parameter_is_an_error_naming_it(params, error, match):
    with pytest.raises(error, match=match):
        gasp.params_yaml(params)


def test_a_missing_or_unreadable_params_file_is_an_error_naming_it(tmp_path):
    with pytest.raises(gasp.Error, match="nowhere.yaml"):
        gasp.load_params(tmp_path / "nowhere.yaml")
    with pytest.raises(gasp.Error, match="not a regular file|folder|directory"):
        gasp.load_params(tmp_path)


def test_a_failed_write_is_an_error_and_leaves_nothing(tmp_path):
    with pytest.raises(gasp.Error):
        gasp.save_params({}, tmp_path / "no_folder" / "p.yaml")
    assert not os.listdir(tmp_path)
