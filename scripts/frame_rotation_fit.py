#!/usr/bin/env python3
"""Whether the reference's camera frame is rotated against the depth camera's: a constant
rotation fitted to the pairs' rotation errors, on each half of the sequence and across halves.

Usage: scripts/frame_rotation_fit.py PAIRS.csv TUM_DIR [GT_OFFSET_S] [METHOD]

PAIRS.csv is a `gasp-pairs --pairs-csv` file of the folder TUM_DIR; the reference is looked up at
the depth stamps + GT_OFFSET_S (default 0; fr1: -0.03). If the reference's camera orientations are
the true ones times a constant rotation Q = exp(delta) (a hand-eye error between the motion
capture body and the optical frame, or a depth image whose frame is turned against the colour
camera's), a perfect estimate R of a pair still differs from the reference's Q^T R Q by
  e = log(R_ref^T R_est) ~ (R^T - I) delta      (source frame, small angles).
The script fits delta by least squares on all pairs, on the pairs starting before the median
start frame and on the rest, then applies each half's delta to the other half: a frame offset
that is real lowers the other half's error too; one fitted to noise does not.
Docs: docs/pipeline.md ("A constant frame rotation"). Standard library only.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import error_vs_velocity as ev  # noqa: E402


def design(r):
    """R^T - I."""
    return [[r[j][i] - (1.0 if i == j else 0.0) for j in range(3)] for i in range(3)]


def fit(pairs):
    ata = [[0.0] * 3 for _ in range(3)]
    atb = [0.0] * 3
    for _, _, r, e in pairs:
        a = design(r)
        for i in range(3):
            atb[i] += sum(a[k][i] * e[k] for k in range(3))
            for j in range(3):
                ata[i][j] += sum(a[k][i] * a[k][j] for k in range(3))
    delta = ev.solve(ata, atb, 1e-12)
    if delta is None:
        sys.exit("error: the pairs' rotations do not fix a frame rotation (all about one axis, or none)")
    return delta


def rms_deg(pairs, delta):
    total = 0.0
    for _, _, r, e in pairs:
        p = ev.mat_vec(design(r), delta)
        total += sum((x - y) ** 2 for x, y in zip(e, p))
    return math.degrees(math.sqrt(total / len(pairs)))


def fmt(delta):
    return "(%.2f, %.2f, %.2f) deg, |%.2f|" % (tuple(math.degrees(x) for x in delta) +
                                             (math.degrees(math.sqrt(sum(x * x for x in delta))),))


def main(argv):
    pairs_path, tum_dir, offset, method = ev.pair_script_args(argv, __doc__)
    _, rotations = ev.estimated_pair_rotations(pairs_path, tum_dir, offset, method)
    pairs = [(i, j, r_ref, e) for i, j, _, _, r_ref, e in rotations]
    if len(pairs) < 20:
        sys.exit("error: %s: %d estimated pairs with ground truth, too few to fit" % (pairs_path, len(pairs)))
    starts = sorted(p[0] for p in pairs)
    split = starts[len(starts) // 2]
    first = [p for p in pairs if p[0] < split]
    second = [p for p in pairs if p[0] >= split]
    if len(first) < 10 or len(second) < 10:
        sys.exit("error: %s: the halves (start frames below / from %d) have %d and %d pairs, too few"
                 % (pairs_path, split, len(first), len(second)))
    zero = [0.0, 0.0, 0.0]
    d_all, d_first, d_second = fit(pairs), fit(first), fit(second)
    print("%d pairs (%s, reference at the depth stamp %+.3f s); halves: start frames below / from %d"
          % (len(pairs), method, offset, split))
    print("| pairs | n | fitted rotation delta (x, y, z) | rotation error RMS [deg]: as is | with its own delta | with the other half's delta |")
    print("|---|---|---|---|---|---|")
    print("| all | %d | %s | %.3f | %.3f | - |" % (len(pairs), fmt(d_all), rms_deg(pairs, zero), rms_deg(pairs, d_all)))
    print("| first half | %d | %s | %.3f | %.3f | %.3f |" % (len(first), fmt(d_first), rms_deg(first, zero),
                                                          rms_deg(first, d_first), rms_deg(first, d_second)))
    print("| second half | %d | %s | %.3f | %.3f | %.3f |" % (len(second), fmt(d_second), rms_deg(second, zero),
                                                           rms_deg(second, d_second), rms_deg(second, d_first)))


if __name__ == "__main__":
    main(sys.argv)
