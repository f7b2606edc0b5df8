#!/usr/bin/env python3
"""How much of each pair's rotation error the camera's motion at the two frames explains.

Usage: scripts/error_vs_velocity.py PAIRS.csv TUM_DIR [GT_OFFSET_S] [METHOD]

PAIRS.csv is a `gasp-pairs --pairs-csv` file of the folder TUM_DIR. For each pair i -> j with an
estimate of METHOD (default gasp) it takes the rotation error as a vector (axis x angle, in the
target camera's frame: log(R_true^T R_est) rotated into it) and the camera's linear and angular
velocity at both frames, from the folder's groundtruth.txt looked up at the depth stamps +
GT_OFFSET_S (default 0; fr1: -0.03), interpolated, by central differences over +-20 ms, in each
camera's own frame. It fits each error component by least squares on
  (a) the 12 velocities (v_i, v_j, w_i, w_j) and a constant, and
  (b) the difference of the linear velocities v_j - v_i and a constant,
and prints the share of the component's variance each fit explains (R^2). A rolling shutter
ties rotation errors to linear velocities (rows exposed at different times see the scene from
places a few millimetres apart); a timing offset ties them to angular velocities.
Docs: docs/pipeline.md, "Rolling shutter". Standard library only.
"""
import bisect
import math
import sys

from pairs_csv import read_pairs_csv


def quat_to_matrix(x, y, z, w):
    n = math.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / n, y / n, z / n, w / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def mat_vec(a, v):
    return [sum(a[i][k] * v[k] for k in range(3)) for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def log_rotation(r):
    c = max(-1.0, min(1.0, (r[0][0] + r[1][1] + r[2][2] - 1) / 2))
    angle = math.acos(c)
    if angle < 1e-12:
        return [0.0, 0.0, 0.0]
    s = angle / (2 * math.sin(angle))
    return [s * (r[2][1] - r[1][2]), s * (r[0][2] - r[2][0]), s * (r[1][0] - r[0][1])]


def read_tum_list(path):
    rows = []
    try:
        with open(path) as f:
            for line in f:
                if line.strip() and not line.startswith("#"):
                    rows.append(line.split())
    except OSError as e:
        sys.exit("error: cannot read %s: %s" % (path, e.strerror))
    return rows


class Trajectory:
    def __init__(self, path):
        rows = read_tum_list(path)
        if len(rows) < 2:
            sys.exit("error: %s: fewer than two poses" % path)
        self.t = [float(r[0]) for r in rows]
        self.p = [[float(v) for v in r[1:4]] for r in rows]
        self.q = [[float(v) for v in r[4:8]] for r in rows]

    def pose(self, t):
        """(R, p) at time t, interpolated (normalised linear blend of the quaternions)."""
        i = min(max(bisect.bisect_left(self.t, t), 1), len(self.t) - 1)
        if t < self.t[0] - 0.05 or t > self.t[-1] + 0.05:
            return None
        u = (t - self.t[i - 1]) / (self.t[i] - self.t[i - 1])
        qa, qb = self.q[i - 1], self.q[i]
        if sum(a * b for a, b in zip(qa, qb)) < 0:
            qb = [-v for v in qb]
        q = [a * (1 - u) + b * u for a, b in zip(qa, qb)]
        p = [a * (1 - u) + b * u for a, b in zip(self.p[i - 1], self.p[i])]
        return quat_to_matrix(*q), p

    def velocity(self, t, h=0.02):
        """Linear [m/s] and angular [rad/s] velocity at t in the camera's own frame."""
        before, now, after = self.pose(t - h), self.pose(t), self.pose(t + h)
        if not (before and now and after):
            return None
        r = now[0]
        v = mat_vec(transpose(r), [(b - a) / (2 * h) for a, b in zip(before[1], after[1])])
        w = [x / (2 * h) for x in log_rotation(mat_mul(transpose(before[0]), after[0]))]
        return v, w


def solve(a, b, min_pivot=0.0):
    """Solves a x = b (small, square) by Gaussian elimination with partial pivoting; None when a
    pivot is below min_pivot in magnitude (singular)."""
    n = len(a)
    m = [row[:] + [v] for row, v in zip(a, b)]
    for c in range(n):
        p = max(range(c, n), key=lambda k: abs(m[k][c]))
        m[c], m[p] = m[p], m[c]
        if abs(m[c][c]) <= min_pivot:
            return None
        for k in range(c + 1, n):
            f = m[k][c] / m[c][c]
            if f != 0.0:
                for col in range(c, n + 1):
                    m[k][col] -= f * m[c][col]
    x = [0.0] * n
    for c in range(n - 1, -1, -1):
        x[c] = (m[c][n] - sum(m[c][k] * x[k] for k in range(c + 1, n))) / m[c][c]
    return x


def least_squares_r2(x_rows, y):
    """R^2 of the least-squares fit y ~ x (x_rows include the constant column)."""
    n = len(x_rows[0])
    ata = [[sum(r[i] * r[j] for r in x_rows) for j in range(n)] for i in range(n)]
    aty = [sum(r[i] * yy for r, yy in zip(x_rows, y)) for i in range(n)]
    coef = solve(ata, aty, 1e-12)
    if coef is None:
        return float("nan")
    mean = sum(y) / len(y)
    ss_tot = sum((yy - mean) ** 2 for yy in y)
    ss_res = sum((yy - sum(c * x for c, x in zip(coef, r))) ** 2 for r, yy in zip(x_rows, y))
    return 1 - ss_res / ss_tot if ss_tot > 0 else float("nan")


def pair_script_args(argv, doc):
    """The arguments PAIRS.csv TUM_DIR [GT_OFFSET_S] [METHOD] of the pair scripts."""
    if len(argv) < 3:
        sys.exit(doc)
    try:
        offset = float(argv[3]) if len(argv) > 3 else 0.0
    except ValueError:
        sys.exit("error: GT_OFFSET_S must be a number of seconds, not '%s'" % argv[3])
    return argv[1], argv[2], offset, argv[4] if len(argv) > 4 else "gasp"


def estimated_pair_rotations(pairs_path, tum_dir, offset, method, extra_columns=()):
    """The folder's reference trajectory, and for each pair i -> j of `method` with an estimate and
    the reference at both frames: (i, j, t_i, t_j, R_ref, e) with t the depth stamps + offset,
    R_ref = R_j_i of the reference and e = log(R_ref^T R_est) (source frame, radians)."""
    stamps = [float(r[0]) for r in read_tum_list(tum_dir + "/depth.txt")]
    gt = Trajectory(tum_dir + "/groundtruth.txt")
    rows = read_pairs_csv(pairs_path, method, list(extra_columns) + ["from", "to", "estimated", "qx", "qy", "qz", "qw"],
                          "estimated poses")
    pairs = []
    for r in rows:
        if r["estimated"] != "1":
            continue
        i, j = int(r["from"]), int(r["to"])
        if max(i, j) >= len(stamps):
            sys.exit("error: %s: frame %d is not in %s/depth.txt" % (pairs_path, max(i, j), tum_dir))
        ti, tj = stamps[i] + offset, stamps[j] + offset
        pi, pj = gt.pose(ti), gt.pose(tj)
        if not (pi and pj):
            continue
        r_ref = mat_mul(transpose(pj[0]), pi[0])  # R_j_i: source i into target j
        r_est = quat_to_matrix(*(float(r[c]) for c in ("qx", "qy", "qz", "qw")))
        pairs.append((i, j, ti, tj, r_ref, log_rotation(mat_mul(transpose(r_ref), r_est))))
    return gt, pairs


def main(argv):
    pairs_path, tum_dir, offset, method = pair_script_args(argv, __doc__)
    gt, pairs = estimated_pair_rotations(pairs_path, tum_dir, offset, method, ["skip"])
    full, diff, errors = [], [], []
    speeds, rates = [], []
    for i, j, ti, tj, r_true, e_source in pairs:
        vel_i, vel_j = gt.velocity(ti), gt.velocity(tj)
        if not (vel_i and vel_j):
            continue
        e = mat_vec(r_true, e_source)
        errors.append([math.degrees(x) for x in e])
        (vi, wi), (vj, wj) = vel_i, vel_j
        full.append(vi + vj + wi + wj + [1.0])
        diff.append([b - a for a, b in zip(vi, vj)] + [1.0])
        speeds += [math.sqrt(sum(x * x for x in vi)), math.sqrt(sum(x * x for x in vj))]
        rates += [math.degrees(math.sqrt(sum(x * x for x in wi))), math.degrees(math.sqrt(sum(x * x for x in wj)))]
    if len(errors) < 20:
        sys.exit("error: %s: %d estimated pairs with ground truth, too few to fit" % (pairs_path, len(errors)))
    rms = math.sqrt(sum(sum(x * x for x in e) for e in errors) / len(errors))
    speeds.sort()
    rates.sort()
    print("%d pairs (%s, reference at the depth stamp %+.3f s); rotation error RMS %.3f deg; camera speed "
          "median %.2f m/s, rate median %.1f deg/s" % (len(errors), method, offset, rms,
                                                      speeds[len(speeds) // 2], rates[len(rates) // 2]))
    print("| error component (camera axis) | RMS [deg] | R^2 on v_i, v_j, w_i, w_j | R^2 on v_j - v_i |")
    print("|---|---|---|---|")
    for k, name in enumerate(("x (pitch)", "y (yaw)", "z (roll)")):
        y = [e[k] for e in errors]
        print("| %s | %.3f | %.2f | %.2f |" % (name, math.sqrt(sum(v * v for v in y) / len(y)),
                                              least_squares_r2(full, y), least_squares_r2(diff, y)))


if __name__ == "__main__":
    main(sys.argv)
