#!/usr/bin/env python3
"""How far gasp-slam's marginal covariances can be trusted: each frame's position error against
the ground truth beside the 1-sigma its covariance claims, as a table and an SVG.

  scripts/marginals_plot.py --gt groundtruth.txt --run NAME=TRAJ.txt,MARGINALS.csv [--run ...] [--out plot.svg]

TRAJ.txt is gasp-slam's --out (TUM format), MARGINALS.csv its --marginals-csv. A frame's error is
measured as the NEES of gasp-slam is (docs/slam.md "How sure the poses are"): the ground truth is
moved to agree with the estimate at the frame's root (the first frame of its piece of the graph),
T_ref = T_root T_gt_root^-1 T_gt, and the error is e = p_est - p_ref (positions). Its covariance is
the position's, C_p = B C B^T with B = [I, -[p]x] (C over the left perturbation [t r]). The table
gives, per run: frames, the median error and 1-sigma (sqrt of trace C_p), the share of frames with
the error within 1 and 2 sigma (about 61 % and 99 % if C_p were right and isotropic) and the
median position NEES e^T C_p^-1 e (chi-square with 3 degrees of freedom: median 2.37).
Only the Python standard library. Poses are matched to the ground truth by nearest timestamp
within 0.02 s; frames without a match are left out.
"""
import argparse
import bisect
import csv
import math
import sys


def fail(msg):
    print('error: ' + msg, file=sys.stderr)
    sys.exit(1)


def read_tum(path):
    rows = []
    try:
        with open(path) as f:
            for n, line in enumerate(f, 1):
                if line.startswith('#') or not line.strip():
                    continue
                try:
                    v = [float(x) for x in line.split()]
                except ValueError:
                    fail('%s:%d: not a TUM pose line' % (path, n))
                if len(v) != 8:
                    fail('%s:%d: not a TUM pose line' % (path, n))
                rows.append((v[0], pose(v[1:4], v[4:8])))
    except OSError as e:
        fail('cannot read %s (%s)' % (path, e.strerror))
    rows.sort(key=lambda r: r[0])
    return rows


def pose(t, q):
    x, y, z, w = q
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if n == 0:
        fail('a zero quaternion')
    x, y, z, w = x / n, y / n, z / n, w / n
    R = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return (R, list(t))


def mat_vec(R, v):
    return [sum(R[i][k] * v[k] for k in range(3)) for i in range(3)]


def mat_t_vec(R, v):
    return [sum(R[k][i] * v[k] for k in range(3)) for i in range(3)]


def nearest(traj, t, max_dt):
    ts = [r[0] for r in traj]
    i = bisect.bisect_left(ts, t)
    best = None
    for j in (i - 1, i):
        if 0 <= j < len(traj) and abs(traj[j][0] - t) <= max_dt and (best is None or abs(traj[j][0] - t) < abs(traj[best][0] - t)):
            best = j
    return None if best is None else traj[best][1]


def solve3(A, b):
    """A^-1 b for a symmetric 3x3 A (Cramer); None when singular."""
    def det(M):
        return (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
                + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
    d = det(A)
    if abs(d) < 1e-300:
        return None
    out = []
    for c in range(3):
        M = [row[:] for row in A]
        for r in range(3):
            M[r][c] = b[r]
        out.append(det(M) / d)
    return out


def position_covariance(C, p):
    """B C B^T with B = [I, -[p]x]: the covariance of the position p of a pose whose left
    perturbation [t r] has covariance C (Exp(xi) T moves the position by t + r x p)."""
    skew = [[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]]
    B = [[(1.0 if i == k else 0.0) for k in range(3)] + [-skew[i][k] for k in range(3)] for i in range(3)]
    BC = [[sum(B[i][m] * C[m][k] for m in range(6)) for k in range(6)] for i in range(3)]
    return [[sum(BC[i][m] * B[k][m] for m in range(6)) for k in range(3)] for i in range(3)]


def read_run(spec, gt):
    if '=' not in spec or ',' not in spec.split('=', 1)[1]:
        fail("--run needs NAME=TRAJ.txt,MARGINALS.csv, not '%s'" % spec)
    name, files = spec.split('=', 1)
    traj_path, marg_path = files.split(',', 1)
    traj = read_tum(traj_path)
    try:
        f = open(marg_path)
    except OSError as e:
        fail('cannot read %s (%s)' % (marg_path, e.strerror))
    with f:
        reader = csv.DictReader(f)
        need = ['frame', 'timestamp', 'root', 'sigma_t_m'] + ['c%d%d' % (r, c) for r in range(6) for c in range(6)]
        missing = [k for k in need if k not in (reader.fieldnames or [])]
        if missing:
            fail('%s has no column %s (not a gasp-slam --marginals-csv?)' % (marg_path, missing[0]))
        rows = []
        for n, r in enumerate(reader, 2):
            try:
                row = {'frame': int(r['frame']), 'root': int(r['root']), 'timestamp': float(r['timestamp']),
                       'C': [[float(r['c%d%d' % (i, k)]) for k in range(6)] for i in range(6)]}
            except (TypeError, ValueError):
                fail('%s:%d: frame, root, timestamp and c00..c55 must be numbers' % (marg_path, n))
            if not all(math.isfinite(v) for line in row['C'] for v in line) or not math.isfinite(row['timestamp']):
                fail('%s:%d: a covariance entry or the timestamp is not finite' % (marg_path, n))
            rows.append(row)
    stamps = {}
    for r in rows:
        stamps[r['frame']] = r['timestamp']
    points = []
    for r in rows:
        frame, root = r['frame'], r['root']
        if frame == root or root not in stamps:
            continue
        t, t_root = r['timestamp'], stamps[root]
        est, est_root = nearest(traj, t, 1e-4), nearest(traj, t_root, 1e-4)
        g, g_root = nearest(gt, t, 0.02), nearest(gt, t_root, 0.02)
        if None in (est, est_root, g, g_root):
            continue
        # t_ref = R_root R_gt_root^T (t_gt - t_gt_root) + t_root
        d = [g[1][k] - g_root[1][k] for k in range(3)]
        t_ref = [a + b for a, b in zip(mat_vec(est_root[0], mat_t_vec(g_root[0], d)), est_root[1])]
        e = [est[1][k] - t_ref[k] for k in range(3)]
        Cp = position_covariance(r['C'], est[1])
        x = solve3(Cp, e)
        if x is None:
            continue
        nees_t = sum(a * b for a, b in zip(e, x))
        sigma = math.sqrt(max(0.0, Cp[0][0] + Cp[1][1] + Cp[2][2]))
        points.append((t - stamps[min(stamps)], math.sqrt(sum(v * v for v in e)), sigma, nees_t))
    if not points:
        fail('%s: no frame with a covariance matched the ground truth' % name)
    return name, points


def median(v):
    v = sorted(v)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def svg(runs, path):
    W, H, L, B, T, Rm = 760, 320, 60, 40, 20, 150
    t_max = max(p[0] for _, pts in runs for p in pts) or 1.0
    # Log scale from 1 mm to the decade above the largest value: errors and sigmas of runs with
    # and without loop closures differ tenfold.
    y_min = 1e-3
    y_max = 10 ** math.ceil(math.log10(max(y_min * 10, max(max(p[1], p[2]) for _, pts in runs for p in pts))))
    colours = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd']
    sx = lambda t: L + (W - L - Rm) * t / t_max
    sy = lambda y: H - B - (H - B - T) * math.log10(max(y, y_min) / y_min) / math.log10(y_max / y_min)
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">' % (W, H),
           '<rect width="100%" height="100%" fill="white"/>',
           '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, H - B, W - Rm, H - B),
           '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, T, L, H - B),
           '<text x="%d" y="%d" text-anchor="middle">time [s]</text>' % ((L + W - Rm) // 2, H - 8),
           '<text x="14" y="%d" transform="rotate(-90 14 %d)" text-anchor="middle">position [m], log scale</text>' % ((T + H - B) // 2, (T + H - B) // 2)]
    decades = int(round(math.log10(y_max / y_min)))
    for k in range(decades + 1):
        y = y_min * 10 ** k
        out.append('<text x="%d" y="%.1f" text-anchor="end">%g</text>' % (L - 4, sy(y) + 4, y))
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>' % (L, sy(y), W - Rm, sy(y)))
    for k in range(5):
        t = t_max * k / 4
        out.append('<text x="%.1f" y="%d" text-anchor="middle">%.0f</text>' % (sx(t), H - B + 16, t))
    for i, (name, pts) in enumerate(runs):
        c = colours[i % len(colours)]
        err = ' '.join('%.1f,%.1f' % (sx(p[0]), sy(p[1])) for p in pts)
        sig = ' '.join('%.1f,%.1f' % (sx(p[0]), sy(p[2])) for p in pts)
        out.append('<polyline fill="none" stroke="%s" stroke-width="1.2" points="%s"/>' % (c, err))
        out.append('<polyline fill="none" stroke="%s" stroke-width="1.2" stroke-dasharray="5,3" points="%s"/>' % (c, sig))
        y0 = T + 16 + 36 * i
        out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="%s"/>' % (W - Rm + 10, y0, W - Rm + 30, y0, c))
        out.append('<text x="%d" y="%d">%s error</text>' % (W - Rm + 34, y0 + 4, name))
        out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="%s" stroke-dasharray="5,3"/>' % (W - Rm + 10, y0 + 16, W - Rm + 30, y0 + 16, c))
        out.append('<text x="%d" y="%d">%s 1-sigma</text>' % (W - Rm + 34, y0 + 20, name))
    out.append('</svg>')
    try:
        with open(path, 'w') as f:
            f.write('\n'.join(out) + '\n')
    except OSError as e:
        fail('cannot write %s (%s)' % (path, e.strerror))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--gt', required=True)
    ap.add_argument('--run', action='append', required=True, help='NAME=TRAJ.txt,MARGINALS.csv')
    ap.add_argument('--out', help='SVG to write')
    a = ap.parse_args()
    gt = read_tum(a.gt)
    runs = [read_run(spec, gt) for spec in a.run]
    print('| run | frames | median error [m] | median 1-sigma [m] | within 1 sigma | within 2 sigma | median position NEES (chi-square 3: 2.37) |')
    print('|---|---|---|---|---|---|---|')
    for name, pts in runs:
        n = len(pts)
        within1 = sum(1 for p in pts if p[1] <= p[2]) / n
        within2 = sum(1 for p in pts if p[1] <= 2 * p[2]) / n
        print('| %s | %d | %.4f | %.4f | %.0f %% | %.0f %% | %.2f |' % (
            name, n, median([p[1] for p in pts]), median([p[2] for p in pts]), 100 * within1, 100 * within2,
            median([p[3] for p in pts])))
    if a.out:
        svg(runs, a.out)
        print('plot: %s' % a.out)


if __name__ == '__main__':
    main()
