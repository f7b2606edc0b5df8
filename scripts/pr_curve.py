#!/usr/bin/env python3
"""Precision-recall curves of loop detection (gasp-loops --curve-csv) as one SVG picture.

  scripts/pr_curve.py --curve NAME=PR.csv [--curve ...] [--rule within_5cm_2deg] --out pr.svg

Each curve is one gasp-loops run: the points of one correctness rule (the CSV's `rule` column,
within_5cm_2deg by default), recall on x, precision on y, one step per inlier threshold, the
highest threshold first. The loop closer's own threshold (--mark, 40 inliers) is marked on each.
Only the Python standard library.
"""
import argparse
import csv
import html
import os

COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b']


def read_curve(path, rule):
    """The rule's points; none for a run without detections (a CSV of its header only)."""
    points, rows = [], 0
    with open(path) as f:
        for row in csv.DictReader(f):
            rows += 1
            if row['rule'] != rule:
                continue
            points.append((float(row['threshold']), float(row['recall']), float(row['precision'])))
    if rows and not points:
        raise SystemExit(f'error: {path}: no points of rule {rule}')
    points.sort(key=lambda p: -p[0])  # highest threshold first: recall grows
    return points


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--curve', action='append', required=True, help='NAME=PR.csv (gasp-loops --curve-csv)')
    ap.add_argument('--rule', default='within_5cm_2deg', help='within_5cm_2deg or consistent')
    ap.add_argument('--mark', type=float, default=40, help='threshold to mark on each curve [inliers]')
    ap.add_argument('--title', default='Loop detection without odometry: precision and recall')
    ap.add_argument('--out', required=True)
    a = ap.parse_args()

    W, H, L, R, T, B = 640, 460, 70, 190, 40, 60
    pw, ph = W - L - R, H - T - B
    x = lambda r: L + r * pw
    y = lambda p: T + (1 - p) * ph
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{W / 2}" y="22" text-anchor="middle" font-size="14">{a.title}</text>']
    for i in range(11):
        v = i / 10
        out.append(f'<line x1="{x(v)}" y1="{T}" x2="{x(v)}" y2="{T + ph}" stroke="#eee"/>')
        out.append(f'<line x1="{L}" y1="{y(v)}" x2="{L + pw}" y2="{y(v)}" stroke="#eee"/>')
        out.append(f'<text x="{x(v)}" y="{T + ph + 16}" text-anchor="middle">{v:.1f}</text>')
        out.append(f'<text x="{L - 6}" y="{y(v) + 4}" text-anchor="end">{v:.1f}</text>')
    out.append(f'<rect x="{L}" y="{T}" width="{pw}" height="{ph}" fill="none" stroke="black"/>')
    out.append(f'<text x="{L + pw / 2}" y="{H - 20}" text-anchor="middle">recall</text>')
    out.append(f'<text x="18" y="{T + ph / 2}" text-anchor="middle" transform="rotate(-90 18 {T + ph / 2})">precision</text>')
    for k, spec in enumerate(a.curve):
        name, path = spec.split('=', 1)
        colour = COLOURS[k % len(COLOURS)]
        pts = read_curve(path, a.rule)
        name = html.escape(name) + ('' if pts else ' (no detection)')
        # A step curve: from (0, 1), each threshold's point in turn.
        d = f'M {x(0):.1f} {y(1):.1f}'
        for _, r, p in pts:
            d += f' L {x(r):.1f} {y(p):.1f}'
        out.append(f'<path d="{d}" fill="none" stroke="{colour}" stroke-width="2"/>')
        marked = [p for p in pts if p[0] >= a.mark]
        if marked:
            _, r, p = marked[-1]
            out.append(f'<circle cx="{x(r):.1f}" cy="{y(p):.1f}" r="5" fill="none" stroke="{colour}" stroke-width="2"/>')
        ly = T + 20 + 22 * k
        out.append(f'<line x1="{L + pw + 12}" y1="{ly}" x2="{L + pw + 36}" y2="{ly}" stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{L + pw + 42}" y="{ly + 4}">{name}</text>')
    ly = T + 20 + 22 * len(a.curve)
    out.append(f'<circle cx="{L + pw + 24}" cy="{ly}" r="5" fill="none" stroke="black" stroke-width="2"/>')
    out.append(f'<text x="{L + pw + 42}" y="{ly + 4}">at &gt;= {a.mark:.0f} inliers</text>')
    out.append('</svg>')
    with open(a.out + '.tmp', 'w') as f:
        f.write('\n'.join(out) + '\n')
    os.replace(a.out + '.tmp', a.out)


if __name__ == '__main__':
    main()
