#!/usr/bin/env python3
"""Per-step errors of an estimated trajectory against a reference: for each pair of consecutive
poses (same line in both files, e.g. gasp-simulate's groundtruth.txt and gasp-odometry --out over
the same frames), the error of the estimated step in translation [m] and rotation [deg].

  scripts/step_errors.py --gt groundtruth.txt --est odometry.txt [--first 0] [--last N]
                         [--min-m 0.01] [--min-deg 0.3]

Prints the steps whose error reaches either limit, then the sum of the printed errors and the
largest, then the mean step error about the estimate's own axes (rotation as small angles about
x, y, z [deg], translation [m]): a shared sign there is a bias (a LiDAR's pitch is about y) that
a trajectory adds up. Only the Python standard library; the two files must list the same frames
in order.
"""
import argparse
import math


def read_tum(path):
    rows = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            if line.startswith('#') or not line.strip():
                continue
            v = line.split()
            if len(v) != 8:
                raise SystemExit(f'error: {path}:{n}: expected 8 numbers (timestamp tx ty tz qx qy qz qw)')
            rows.append([float(x) for x in v])
    return rows


def pose(v):
    qx, qy, qz, qw = v[4:8]
    R = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
         [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
         [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]
    return R, v[1:4]


def inverse(T):
    R, t = T
    Rt = [[R[j][i] for j in range(3)] for i in range(3)]
    return Rt, [-sum(Rt[i][k] * t[k] for k in range(3)) for i in range(3)]


def compose(A, B):
    (R1, t1), (R2, t2) = A, B
    R = [[sum(R1[i][k] * R2[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return R, [sum(R1[i][k] * t2[k] for k in range(3)) + t1[i] for i in range(3)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--gt', required=True)
    ap.add_argument('--est', required=True)
    ap.add_argument('--first', type=int, default=0)
    ap.add_argument('--last', type=int, default=-1, help='last frame (default: the end)')
    ap.add_argument('--min-m', type=float, default=0.01)
    ap.add_argument('--min-deg', type=float, default=0.3)
    a = ap.parse_args()
    gt, est = read_tum(a.gt), read_tum(a.est)
    if len(gt) != len(est):
        raise SystemExit(f'error: {a.gt} has {len(gt)} poses, {a.est} {len(est)}: the same frames are expected')
    last = len(gt) - 1 if a.last < 0 else min(a.last, len(gt) - 1)
    sum_m = sum_deg = worst_m = worst_deg = 0.0
    mean_rot, mean_t, steps = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], 0
    for i in range(a.first, last):
        g = compose(inverse(pose(gt[i])), pose(gt[i + 1]))
        e = compose(inverse(pose(est[i])), pose(est[i + 1]))
        d = compose(inverse(g), e)
        m = math.sqrt(sum(x * x for x in d[1]))
        c = (d[0][0][0] + d[0][1][1] + d[0][2][2] - 1) / 2
        deg = math.degrees(math.acos(max(-1.0, min(1.0, c))))
        if m >= a.min_m or deg >= a.min_deg:
            print(f'{i} -> {i + 1}: {m:.4f} m, {deg:.3f} deg')
            sum_m, sum_deg = sum_m + m, sum_deg + deg
        worst_m, worst_deg = max(worst_m, m), max(worst_deg, deg)
        R = d[0]  # small angles: the skew part of the error's rotation
        for k, (p, q) in enumerate(((2, 1), (0, 2), (1, 0))):
            mean_rot[k] += math.degrees(0.5 * (R[p][q] - R[q][p]))
            mean_t[k] += d[1][k]
        steps += 1
    print(f'printed steps: {sum_m:.3f} m, {sum_deg:.2f} deg in all; largest step error {worst_m:.4f} m, {worst_deg:.3f} deg')
    if steps:
        r = ', '.join(f'{x / steps:.4f}' for x in mean_rot)
        t = ', '.join(f'{x / steps:.5f}' for x in mean_t)
        print(f'mean step error: rotation about x, y, z ({r}) deg, translation ({t}) m over {steps} steps')


if __name__ == '__main__':
    main()
