"""GASP: appearance-free data association and registration between depth views.

Depth images are numpy arrays: uint16 raw units (``depth_units_per_metre`` per metre; TUM: 5000)
or float32 / float64 metres, 0 where there is no depth. Poses are 4x4 float64 arrays;
``T_target_source`` maps a point of the source camera's frame into the target's.

Parameters (``params=``) are the params file's: ``None`` for the defaults, the path of a params
file, or a dict of sections ``{"segment": {"target_patch_area_m2": 0.006}, ...}`` read over the
defaults. ``default_params()`` lists every key; docs/parameters.md explains each.

The reference: docs/python.md.
"""

import numbers as _numbers
import os as _os
import re as _re

from . import _gasp
from ._gasp import (  # noqa: F401  (the public classes)
    Error,
    Intrinsics,
    Registration,
    SequenceRun,
    Trajectory,
    TumFolder,
    View,
    ate,
)

__all__ = [
    "Error", "Intrinsics", "Registration", "SequenceRun", "Trajectory", "TumFolder", "View",
    "ate", "default_params", "load_params", "save_params", "params_yaml",
    "segment", "register", "odometry", "slam", "pose_error",
]

TUM_DEPTH_UNITS_PER_METRE = 5000.0

# ---- parameters: dicts <-> the params file's YAML text (read and checked by the C++ side)

_NAME = _re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_WORD = _re.compile(r"[A-Za-z0-9_.+-]+")
_INT = _re.compile(r"[+-]?[0-9]+")


def _yaml_value(section, key, value):
    where = "params: %s.%s" % (section, key)
    if isinstance(value, bool) or (type(value).__module__ == "numpy" and type(value).__name__ in ("bool_", "bool")):
        return "true" if value else "false"
    if isinstance(value, _numbers.Integral):  # int, numpy integers
        return str(int(value))
    if isinstance(value, _numbers.Real):  # float, numpy floats
        return repr(float(value))  # the shortest text that reads back to the same double; inf, nan
    if isinstance(value, str):
        if not _WORD.fullmatch(value):
            raise ValueError("%s: %r is not a value (a name such as 'huber')" % (where, value))
        return value
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_yaml_value(section, key, v) for v in value) + "]"
    raise TypeError("%s: a value of type %s; expected bool, int, float, str or a list"
                    % (where, type(value).__name__))


def _dict_yaml(params):
    lines = []
    for section, keys in params.items():
        if not isinstance(section, str) or not _NAME.fullmatch(section):
            raise ValueError("params: %r is not a section name" % (section,))
        if not isinstance(keys, dict):
            raise TypeError("params: section '%s' must be a dict of keys, got %s" % (section, type(keys).__name__))
        lines.append(section + ":")
        for key, value in keys.items():
            if not isinstance(key, str) or not _NAME.fullmatch(key):
                raise ValueError("params: %r in section '%s' is not a key name" % (key, section))
            lines.append("  %s: %s" % (key, _yaml_value(section, key, value)))
    return "\n".join(lines) + "\n"


def _scalar(text):
    if text in ("true", "false"):
        return text == "true"
    if _INT.fullmatch(text):
        return int(text)
    try:
        return float(text)
    except ValueError:
        return text


def _yaml_dict(text):
    """The params file's YAML as GASP writes it (sections of 'key: value' lines) as a dict."""
    out, section = {}, None
    for line in text.splitlines():
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if not line.startswith(" "):
            section = line.rstrip(":").strip()
            out[section] = {}
            continue
        key, _, value = line.strip().partition(":")
        value = value.strip()
        if value.startswith("[") and value.endswith("]"):
            inner = value[1:-1].strip()
            out[section][key] = [_scalar(v.strip()) for v in inner.split(",")] if inner else []
        else:
            out[section][key] = _scalar(value)
    return out


def _params_text(params):
    """The YAML text of `params` (None, a path or a dict); '' for the defaults. The C++ side reads
    and checks it (errors name the key)."""
    if params is None:
        return ""
    if isinstance(params, (str, bytes, _os.PathLike)):
        return _gasp._read_params_file(params)
    if isinstance(params, dict):
        return _dict_yaml(params)
    raise TypeError("params: expected None, a params file's path or a dict of sections, got %s"
                    % type(params).__name__)


def default_params():
    """Every parameter with its default, as a dict of sections (the params file params/gasp.yaml)."""
    return _yaml_dict(_gasp._default_params_yaml())


def load_params(path):
    """The params file at `path` read over the defaults: every parameter, as a dict of sections."""
    return _yaml_dict(_gasp._read_params_file(path))


def params_yaml(params=None):
    """The params file's text of every parameter `params` gives (over the defaults), as programs'
    --print-params writes it; gasp-odometry --params FILE reads it back."""
    return _gasp._effective_params_yaml(_params_text(params))


def save_params(params, path):
    """Writes every parameter (`params` over the defaults) as a params file: a temporary file in
    the same folder, checked, then renamed. Programs read it with --params."""
    _gasp._write_params_file(_params_text(params), path)


# ---- pairs


def segment(depth, intrinsics, params=None, depth_units_per_metre=TUM_DEPTH_UNITS_PER_METRE):
    """Segments a depth image into regularised surface patches: a gasp.View (labels, centroids,
    normals, areas, ...). `depth`: (height, width) uint16 raw units or float metres."""
    return _gasp._segment(depth, intrinsics, _params_text(params), float(depth_units_per_metre))


def register(source, target, intrinsics=None, params=None, depth_units_per_metre=TUM_DEPTH_UNITS_PER_METRE):
    """Registers `source` to `target` without a prior: a gasp.Registration whose T_target_source
    maps the source camera's frame into the target's, with success / partial / reason, the
    information matrix, the degeneracy verdicts and the verified patch associations.
    `source`, `target`: depth arrays (then `intrinsics` is needed) or gasp.View from segment()."""
    return _gasp._register(source, target, intrinsics, _params_text(params), float(depth_units_per_metre))


# ---- sequences


def _run(path, slam, params, first, every, max_frames, sensor, intrinsics, depth_units_per_metre, ground_truth):
    if isinstance(intrinsics, Intrinsics):  # the sequence reader takes a preset or a file: a file of them
        import tempfile
        with tempfile.TemporaryDirectory() as folder:
            written = _os.path.join(folder, "intrinsics.txt")
            intrinsics.save(written)
            return _run(path, slam, params, first, every, max_frames, sensor, written, depth_units_per_metre,
                        ground_truth)
    return _gasp._run_sequence(path, slam, _params_text(params), int(first), int(every), int(max_frames),
                               sensor or "", _os.fsdecode(intrinsics) if intrinsics else "",
                               float(depth_units_per_metre), ground_truth)


def odometry(path, params=None, first=0, every=1, max_frames=0, sensor=None, intrinsics=None,
             depth_units_per_metre=TUM_DEPTH_UNITS_PER_METRE, ground_truth=None):
    """Odometry over a TUM folder or a rawlog (as gasp-odometry): each frame registered to the
    current keyframe, the first frame at the origin. Returns a gasp.SequenceRun (trajectory,
    tracked, keyframe, reasons, ground_truth, ate()). `intrinsics`, for a TUM folder: a
    gasp.Intrinsics, a preset name or an intrinsics file (default: the folder's own); `sensor`: a
    rawlog's sensor label; `ground_truth`: a TUM trajectory file to score against (default: a TUM
    folder's groundtruth.txt)."""
    return _run(path, False, params, first, every, max_frames, sensor, intrinsics, depth_units_per_metre,
                ground_truth)


def slam(path, params=None, first=0, every=1, max_frames=0, sensor=None, intrinsics=None,
         depth_units_per_metre=TUM_DEPTH_UNITS_PER_METRE, ground_truth=None):
    """SLAM over a TUM folder or a rawlog (as gasp-slam with one session): odometry, loop
    closures, the pose graph optimised; the world is the first frame's robot frame (a rawlog's
    first camera sits at its sensorPose). Returns a gasp.SequenceRun with loop_closures. The
    arguments are odometry()'s."""
    return _run(path, True, params, first, every, max_frames, sensor, intrinsics, depth_units_per_metre,
                ground_truth)


def pose_error(T_estimate, T_truth):
    """(translation error [m], rotation error [deg]) between two 4x4 poses."""
    import numpy as np
    E = np.linalg.inv(np.asarray(T_truth, dtype=float)) @ np.asarray(T_estimate, dtype=float)
    cos = np.clip((np.trace(E[:3, :3]) - 1.0) / 2.0, -1.0, 1.0)
    return float(np.linalg.norm(E[:3, 3])), float(np.degrees(np.arccos(cos)))
