#!/usr/bin/env python3
"""Plots trajectories aligned to a ground truth (gasp-eval ate --aligned) as an SVG: a top view
(x-y) and the position error over time.

  scripts/plot_trajectories.py --gt groundtruth.txt --est NAME=aligned.txt [--est ...] --out plot.svg

Only the Python standard library; the estimates must already be aligned (gasp-eval ate --aligned).
Poses are matched to the ground truth by nearest timestamp within 0.02 s, as gasp-eval does.
"""
import argparse
import bisect
import math


def read_tum(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith('#') or not line.strip():
                continue
            v = [float(x) for x in line.split()]
            rows.append((v[0], v[1], v[2], v[3]))
    rows.sort()
    return rows


def nearest(gt, t, max_dt=0.02):
    ts = [r[0] for r in gt]
    i = bisect.bisect_left(ts, t)
    best = None
    for j in (i - 1, i):
        if 0 <= j < len(gt) and abs(gt[j][0] - t) <= max_dt and (best is None or abs(gt[j][0] - t) < abs(gt[best][0] - t)):
            best = j
    return None if best is None else gt[best]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--gt', required=True)
    ap.add_argument('--est', action='append', required=True, help='NAME=aligned TUM file')
    ap.add_argument('--out', required=True)
    ap.add_argument('--title', default='')
    a = ap.parse_args()
    gt = read_tum(a.gt)
    ests = []
    for spec in a.est:
        name, path = spec.split('=', 1)
        ests.append((name, read_tum(path)))
    colours = ['#d62728', '#1f77b4', '#2ca02c', '#9467bd']
    t0 = min(e[0][0] for _, e in ests)
    # Panel geometry.
    W, H, pad = 1000, 460, 50
    pw = (W - 3 * pad) / 2
    ph = H - 2 * pad - 20
    # Top view extents: the ground truth over the estimates' time span.
    t_end = max(e[-1][0] for _, e in ests)
    g = [r for r in gt if t0 - 0.1 <= r[0] <= t_end + 0.1]
    xs = [r[1] for r in g] + [p[1] for _, e in ests for p in e]
    ys = [r[2] for r in g] + [p[2] for _, e in ests for p in e]
    span = max(max(xs) - min(xs), max(ys) - min(ys)) * 1.05
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2

    def top(x, y):
        return pad + (x - cx + span / 2) / span * pw, pad + 20 + (cy + span / 2 - y) / span * ph

    errs = []
    for name, e in ests:
        pts = []
        for r in e:
            m = nearest(gt, r[0])
            if m:
                pts.append((r[0] - t0, math.dist(r[1:], m[1:])))
        errs.append((name, pts))
    emax = max(p[1] for _, pts in errs for p in pts) * 1.1
    tmax = max(p[0] for _, pts in errs for p in pts)

    def err(t, v):
        return 2 * pad + pw + t / tmax * pw, pad + 20 + ph - v / emax * ph

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="13">',
           '<rect width="100%" height="100%" fill="white"/>',
           f'<text x="{W/2}" y="20" text-anchor="middle" font-size="15">{a.title}</text>']
    for x0 in (pad, 2 * pad + pw):
        out.append(f'<rect x="{x0}" y="{pad+20}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>')
    out.append(f'<text x="{pad + pw/2}" y="{H-10}" text-anchor="middle">top view (x, y), square {span:.2f} m wide</text>')
    out.append(f'<text x="{2*pad + 1.5*pw}" y="{H-10}" text-anchor="middle">position error [m] over time [s] (0 to {tmax:.0f} s)</text>')
    for k in range(5):
        v = emax * k / 4
        x, y = err(0, v)
        out.append(f'<text x="{x-4}" y="{y+4}" text-anchor="end" font-size="11">{v:.3f}</text>')
    path = ' '.join('%.1f,%.1f' % top(r[1], r[2]) for r in g)
    out.append(f'<polyline points="{path}" fill="none" stroke="black" stroke-width="1.5"/>')
    legend = [('ground truth', 'black')]
    for (name, e), (_, pts), c in zip(ests, errs, colours):
        path = ' '.join('%.1f,%.1f' % top(r[1], r[2]) for r in e)
        out.append(f'<polyline points="{path}" fill="none" stroke="{c}" stroke-width="1"/>')
        path = ' '.join('%.1f,%.1f' % err(t, v) for t, v in pts)
        out.append(f'<polyline points="{path}" fill="none" stroke="{c}" stroke-width="1"/>')
        rms = math.sqrt(sum(v * v for _, v in pts) / len(pts))
        legend.append((f'{name} (RMS {rms:.4f} m)', c))
    for i, (text, c) in enumerate(legend):
        y = pad + 40 + 18 * i
        out.append(f'<line x1="{2*pad+pw+10}" y1="{y-4}" x2="{2*pad+pw+30}" y2="{y-4}" stroke="{c}" stroke-width="2"/>')
        out.append(f'<text x="{2*pad+pw+36}" y="{y}">{text}</text>')
    out.append('</svg>')
    with open(a.out, 'w') as f:
        f.write('\n'.join(out) + '\n')


if __name__ == '__main__':
    main()
