#!/usr/bin/env python3
"""Whether the rotation errors of a set of pairs are one orientation offset per frame, and which.

Usage: scripts/keyframe_offsets.py PAIRS.csv TUM_DIR [GT_OFFSET_S] [METHOD]

PAIRS.csv is a `gasp-pairs --pairs-csv` file of the folder TUM_DIR. For each pair i -> j with an
estimate of METHOD (default gasp) it takes the rotation error as a vector in the target camera's
frame (as scripts/error_vs_velocity.py does: the reference looked up at the depth stamps +
GT_OFFSET_S). It then fits one offset o_k per frame so that e(i -> j) ~ o_j - o_i (small angles;
least squares per axis, the offsets of each connected set of frames with mean zero), and prints
the error RMS per axis, the RMS left after the fit, and the offsets frame by frame with the step
from the frame before.

Reading it: errors that are the reference's, a per-frame orientation error of the ground truth,
fit exactly. So do errors of estimates that close loops, whoever is wrong; what the fit adds is
the shape of the offsets: noise on each frame, a drift, or steps between runs of frames.
Docs: docs/association.md ("Over every pair of the benchmark"). Standard library only.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import error_vs_velocity as ev  # noqa: E402


def main(argv):
    pairs_path, tum_dir, offset, method = ev.pair_script_args(argv, __doc__)
    _, rotations = ev.estimated_pair_rotations(pairs_path, tum_dir, offset, method)
    # The error in the target camera's frame, in degrees.
    pairs = [(i, j, [math.degrees(x) for x in ev.mat_vec(r_ref, e)]) for i, j, _, _, r_ref, e in rotations]
    frames = sorted({f for i, j, _ in pairs for f in (i, j)})
    if len(pairs) < len(frames):
        sys.exit("error: %s: %d estimated pairs with ground truth over %d frames, too few to fit an offset per "
                 "frame" % (pairs_path, len(pairs), len(frames)))
    index = {f: k for k, f in enumerate(frames)}
    n = len(frames)
    # Normal equations of e_ij = o_j - o_i (the graph Laplacian), with a tiny ridge that fixes the
    # free offset of each connected set of frames at mean zero.
    lap = [[0.0] * n for _ in range(n)]
    for i, j, _ in pairs:
        a, b = index[i], index[j]
        lap[a][a] += 1
        lap[b][b] += 1
        lap[a][b] -= 1
        lap[b][a] -= 1
    for k in range(n):
        lap[k][k] += 1e-9
    offsets = []
    for axis in range(3):
        rhs = [0.0] * n
        for i, j, e in pairs:
            rhs[index[j]] += e[axis]
            rhs[index[i]] -= e[axis]
        offsets.append(ev.solve(lap, rhs))
    rms = [math.sqrt(sum(e[a] ** 2 for _, _, e in pairs) / len(pairs)) for a in range(3)]
    left = [math.sqrt(sum((e[a] - (offsets[a][index[j]] - offsets[a][index[i]])) ** 2 for i, j, e in pairs)
                      / len(pairs)) for a in range(3)]
    print("%d pairs over %d frames (%s, reference at the depth stamp %+.3f s)" % (len(pairs), n, method, offset))
    print("rotation error RMS per axis x / y / z [deg]: %.3f / %.3f / %.3f" % tuple(rms))
    print("left after one offset per frame [deg]: %.3f / %.3f / %.3f" % tuple(left))
    print("| frame | offset x (pitch) | y (yaw) | z (roll) | step from the frame before [deg] |")
    print("|---|---|---|---|---|")
    for k, f in enumerate(frames):
        o = [offsets[a][k] for a in range(3)]
        step = math.sqrt(sum((offsets[a][k] - offsets[a][k - 1]) ** 2 for a in range(3))) if k else 0.0
        print("| %d | %.2f | %.2f | %.2f | %s |" % (f, o[0], o[1], o[2], "%.2f" % step if k else "-"))


if __name__ == "__main__":
    main(sys.argv)
