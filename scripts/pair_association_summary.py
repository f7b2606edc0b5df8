#!/usr/bin/env python3
"""Association quality over every pair of a gasp-pairs --pairs-csv file (docs/association.md).

  scripts/pair_association_summary.py PAIRS.csv [METHOD]

Per skip: pairs with an estimate, the free associations' precision and the verified
associations' precision and density (median, mean, share of pairs at >= 0.8 and >= 0.9), and
the median pose error of the estimates; then how well the estimate and the ground truth explain
the depth (the agreement columns: share of samples within a tight gate of the other view's
surface) and on how many pairs each is the better by more than 0.02. Python standard library
only."""
import csv
import statistics
import sys


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    method = sys.argv[2] if len(sys.argv) > 2 else "gasp"
    by_skip = {}
    with open(sys.argv[1], newline="") as f:
        for row in csv.DictReader(f):
            if row["method"] != method or row["estimated"] != "1" or row.get("verified_precision", "") == "":
                continue
            by_skip.setdefault(int(row["skip"]), []).append(row)
    if not by_skip:
        sys.exit("no estimated pairs of method %s with association columns" % method)
    print("| skip | pairs with an estimate | free precision: median | verified precision: median / mean "
          "| pairs >= 0.8 / >= 0.9 | verified density: median | pose error: median t [m] / r [deg] |")
    print("|---|---|---|---|---|---|---|")
    for skip in sorted(by_skip):
        rows = by_skip[skip]
        col = lambda name: [float(r[name]) for r in rows]
        vp = col("verified_precision")
        n = len(vp)
        print("| %d | %d | %.3f | %.3f / %.3f | %.0f %% / %.0f %% | %.3f | %.4f / %.2f |" % (
            skip, n, statistics.median(col("precision")), statistics.median(vp), statistics.mean(vp),
            100.0 * sum(v >= 0.8 for v in vp) / n, 100.0 * sum(v >= 0.9 for v in vp) / n,
            statistics.median(col("verified_density")), statistics.median(col("t_err_m")),
            statistics.median(col("r_err_deg"))))
    print()
    print("| skip | pairs | agreement, estimate: median | agreement, ground truth: median | estimate better | ground truth better |")
    print("|---|---|---|---|---|---|")
    for skip in sorted(by_skip):
        rows = by_skip[skip]
        est = [float(r["agreement"]) for r in rows]
        gt = [float(r["agreement_truth"]) for r in rows]
        print("| %d | %d | %.3f | %.3f | %d | %d |" % (
            skip, len(rows), statistics.median(est), statistics.median(gt),
            sum(e > g + 0.02 for e, g in zip(est, gt)), sum(g > e + 0.02 for e, g in zip(est, gt))))


if __name__ == "__main__":
    main()
