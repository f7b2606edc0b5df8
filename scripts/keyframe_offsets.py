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
from pairs_csv import read_pairs_csv  # noqa: E402


def solve(a, b):
    """Solves a x = b (a symmetric positive definite, small) by Gaussian elimination."""
    n = len(a)
    m = [row[:] + [v] for row, v in zip(a, b)]
    for c in range(n):
        p = max(range(c, n), key=lambda k: abs(m[k][c]))
        m[c], m[p] = m[p], m[c]
        for k in range(c + 1, n):
            f = m[k][c] / m[c][c]
            if f != 0.0:
                for col in range(c, n + 1):
                    m[k][col] -= f * m[c][col]
    x = [0.0] * n
    for c in range(n - 1, -1, -1):
        x[c] = (m[c][n] - sum(m[c][k] * x[k] for k in range(c + 1, n))) / m[c][c]
    return x


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    pairs_path, tum_dir = argv[1], argv[2]
    try:
        offset = float(argv[3]) if len(argv) > 3 else 0.0
    except ValueError:
        sys.exit("error: GT_OFFSET_S must be a number of seconds, not '%s'" % argv[3])
    method = argv[4] if len(argv) > 4 else "gasp"
    stamps = [float(r[0]) for r in ev.read_tum_list(tum_dir + "/depth.txt")]
    gt = ev.Trajectory(tum_dir + "/groundtruth.txt")
    rows = read_pairs_csv(pairs_path, method, ["from", "to", "estimated", "qx", "qy", "qz", "qw"], "estimated poses")
    pairs = []
    for r in rows:
        if r["estimated"] != "1":
            continue
        i, j = int(r["from"]), int(r["to"])
        if max(i, j) >= len(stamps):
            sys.exit("error: %s: frame %d is not in %s/depth.txt" % (pairs_path, max(i, j), tum_dir))
        pi, pj = gt.pose(stamps[i] + offset), gt.pose(stamps[j] + offset)
        if not (pi and pj):
            continue
        r_true = ev.mat_mul(ev.transpose(pj[0]), pi[0])
        r_est = ev.quat_to_matrix(*(float(r[k]) for k in ("qx", "qy", "qz", "qw")))
        e = ev.mat_vec(r_true, ev.log_rotation(ev.mat_mul(ev.transpose(r_true), r_est)))
        pairs.append((i, j, [math.degrees(x) for x in e]))
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
        offsets.append(solve(lap, rhs))
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
