#!/usr/bin/env python3
"""Summarise gasp-pairs --rgb-rotation-check: whose rotation error is whose.

Usage: scripts/rgb_rotation_check_summary.py PAIRS.csv [METHOD] [CUT_DEG] [--svg FIGURE.svg]

PAIRS.csv is a `gasp-pairs --pairs-csv ... --rgb-rotation-check` file. Per skip, over the pairs
where the colour images gave a rotation and METHOD (default gasp) an estimate, it prints the three
pairwise rotation differences -- images vs reference (rgb_r_vs_ref_deg), images vs estimate
(rgb_r_vs_est_deg), estimate vs reference (r_err_deg) -- as medians and RMS, and splits them with
the three-cornered hat: for three measurements a, b, c of the same rotation with independent
errors, E|a - b|^2 = s_a^2 + s_b^2, so s_a^2 = (d_ab^2 + d_ac^2 - d_bc^2) / 2. A negative value
(printed with a minus sign) means the independence assumption or the sample does not hold up.
The 90 % intervals come from a block bootstrap (blocks of 10 pairs in start-frame order, since
pairs from neighbouring start frames share frames; 2000 resamples, fixed seed).
Triples with any difference above CUT_DEG (default 3) are left out and counted: a failed
essential matrix (e.g. motion blur) is not an error of the other two. With --polish-reference
columns, a second table does the same with the GICP-polished reference in place of the estimate.
With --svg it also draws, one panel per skip, each pair as a point: x = images vs reference,
y = images vs estimate [deg]. Points above the diagonal are pairs where the images side with the
reference, below it with the estimate.
Docs: docs/pipeline.md, "A depth-free check".
"""
import math
import random
import statistics
import sys

from pairs_csv import pop_option, read_pairs_csv

BLOCK = 10        # pairs per bootstrap block (pairs from neighbouring start frames overlap)
RESAMPLES = 2000  # bootstrap resamples


def hat(triples):
    """Three-cornered hat of (a-b, a-c, b-c) differences: the shares (s_a^2, s_b^2, s_c^2)."""
    ms = [sum(t[i] ** 2 for t in triples) / len(triples) for i in range(3)]
    return ((ms[0] + ms[1] - ms[2]) / 2, (ms[1] + ms[2] - ms[0]) / 2, (ms[0] + ms[2] - ms[1]) / 2)


def interval(triples, which):
    """5 %% / 95 %% of share `which` over a block bootstrap (blocks of BLOCK pairs in start order)."""
    blocks = [triples[i:i + BLOCK] for i in range(0, len(triples), BLOCK)]
    rng = random.Random(1)
    values = []
    for _ in range(RESAMPLES):
        sample = [t for _ in blocks for t in rng.choice(blocks)]
        values.append(signed_sqrt(hat(sample)[which]))
    values.sort()
    return values[int(0.05 * len(values))], values[int(0.95 * len(values)) - 1]


def signed_sqrt(v):
    return math.copysign(math.sqrt(abs(v)), v)


def write_svg(path, panels, cut, title):
    """panels: [(skip, [(x, y), ...])]; a scatter per skip with the diagonal, axes 0..cut deg."""
    size, pad, gap = 260, 44, 24
    width = pad + len(panels) * (size + gap) + 10
    height = size + 2 * pad + 20
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">' % (width, height),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="%d" y="18" font-size="14">%s</text>' % (pad, title)]
    for n, (skip, points) in enumerate(panels):
        x0, y0 = pad + n * (size + gap), pad
        to_x = lambda v: x0 + size * v / cut
        to_y = lambda v: y0 + size - size * v / cut
        out.append('<rect x="%d" y="%d" width="%d" height="%d" fill="none" stroke="black"/>' % (x0, y0, size, size))
        out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="grey" stroke-dasharray="4,3"/>' % (
            to_x(0), to_y(0), to_x(cut), to_y(cut)))
        for tick in range(int(cut) + 1):
            out.append('<text x="%.1f" y="%d" text-anchor="middle">%d</text>' % (to_x(tick), y0 + size + 16, tick))
            out.append('<text x="%d" y="%.1f" text-anchor="end">%d</text>' % (x0 - 4, to_y(tick) + 4, tick))
        above = sum(1 for x, y in points if y > x)
        for x, y in points:
            colour = "#c0392b" if y > x else "#2874a6"
            out.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s" fill-opacity="0.7"/>' % (to_x(x), to_y(y), colour))
        out.append('<text x="%d" y="%d">skip %d: %d of %d above the diagonal</text>' % (x0 + 4, y0 - 6, skip, above, len(points)))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">images vs reference [deg]</text>' % (x0 + size / 2, y0 + size + 32))
    out.append('<text transform="translate(12,%d) rotate(-90)" text-anchor="middle">images vs estimate [deg]</text>' % (pad + size / 2))
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    args = sys.argv[1:]
    svg = pop_option(args, "--svg", None, "a file name")
    if len(args) < 1:
        sys.exit(__doc__)
    path = args[0]
    method = args[1] if len(args) > 1 else "gasp"
    try:
        cut = float(args[2]) if len(args) > 2 else 3.0
    except ValueError:
        sys.exit("error: CUT_DEG must be a number of degrees, not '%s'" % args[2])
    if not cut > 0:
        sys.exit("error: CUT_DEG must be > 0, not %s" % args[2])
    panels = []
    rows = read_pairs_csv(path, method, {"skip", "method", "estimated", "r_err_deg", "rgb_inliers", "rgb_r_vs_ref_deg",
                                         "rgb_r_vs_est_deg"}, "rgb_* columns")
    skips = sorted({int(r["skip"]) for r in rows})
    print("| skip | pairs with rgb | images gave a rotation | triples used (all < %g deg) | median images-ref / images-est / est-ref [deg] "
          "| RMS images-ref / images-est / est-ref [deg] | three-cornered hat: images / estimate / reference [deg] "
          "(90 %% block-bootstrap interval) |" % cut)
    print("|---|---|---|---|---|---|---|")
    printed = 0
    for skip in skips:
        rs = [r for r in rows if int(r["skip"]) == skip]
        with_rgb = [r for r in rs if r["rgb_inliers"] != ""]
        rotated = [r for r in rs if r["rgb_r_vs_ref_deg"] != ""]
        rotated.sort(key=lambda r: int(r["from"]))
        triples = [(float(r["rgb_r_vs_ref_deg"]), float(r["rgb_r_vs_est_deg"]), float(r["r_err_deg"]))
                   for r in rotated if r["estimated"] == "1" and r["rgb_r_vs_est_deg"] != ""]
        kept = [t for t in triples if max(t) < cut]
        if not kept:
            continue
        ms = [sum(t[i] ** 2 for t in kept) / len(kept) for i in range(3)]
        shares = [signed_sqrt(v) for v in hat(kept)]
        med = [statistics.median(t[i] for t in kept) for i in range(3)]
        ci = [interval(kept, i) for i in range(3)]
        panels.append((skip, [(t[0], t[1]) for t in kept]))
        print("| %d | %d | %d | %d of %d | %.2f / %.2f / %.2f | %.2f / %.2f / %.2f | %s |" % (
            skip, len(with_rgb), len(rotated), len(kept), len(triples), med[0], med[1], med[2],
            math.sqrt(ms[0]), math.sqrt(ms[1]), math.sqrt(ms[2]),
            " / ".join("%.2f (%.2f..%.2f)" % (v, lo, hi) for v, (lo, hi) in zip(shares, ci))))
        printed += 1
    if not printed:
        sys.exit("error: %s: no pair of method %s with a rotation from the images and an estimate" % (path, method))
    if svg:
        write_svg(svg, panels, cut, "%s: each pair's rotation from the colour images against the reference's (x) and %s's (y)"
                  % (path.split("/")[-1], method))
    # With --polish-reference: the same split with the GICP-polished reference in place of the
    # estimate (images vs polished: rgb_r_vs_ref_icp_deg; polished vs reference: ref_icp_r_deg).
    polished = [r for r in sorted(rows, key=lambda r: int(r["from"])) if r.get("rgb_r_vs_ref_icp_deg", "") != "" and r.get("ref_icp_r_deg", "") != ""
                and r["rgb_r_vs_ref_deg"] != ""]
    if not polished:
        return
    print()
    print("| skip | triples used (all < %g deg) | three-cornered hat: images / GICP-polished reference / reference [deg] |" % cut)
    print("|---|---|---|")
    for skip in skips:
        triples = [(float(r["rgb_r_vs_ref_deg"]), float(r["rgb_r_vs_ref_icp_deg"]), float(r["ref_icp_r_deg"]))
                   for r in polished if int(r["skip"]) == skip]
        kept = [t for t in triples if max(t) < cut]
        if not kept:
            continue
        # (images-ref, images-polished, polished-ref): shares of images, polished, reference.
        a, b, c = hat([(t[0], t[1], t[2]) for t in kept])
        print("| %d | %d of %d | %.2f / %.2f / %.2f |" % (
            skip, len(kept), len(triples), signed_sqrt(a), signed_sqrt(b), signed_sqrt(c)))


if __name__ == "__main__":
    main()
