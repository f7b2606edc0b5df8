#!/usr/bin/env python3
"""The visibility check's violation ratios of right and wrong estimates in gasp-pairs --pairs-csv
files (docs/pipeline.md, "Violations seen from both views").

  scripts/violation_summary.py PAIRS.csv [PAIRS.csv ...] [--method gasp]

An estimate is wrong when it is more than 0.10 m or 5 deg from the reference. Per file and over
all files: pairs, estimates, wrong estimates, pairs declined by the two-way violation limit (the
reason says "seen from both views", at the default scale or in the finer-scale retry), and the largest violation ratio of the right estimates in the worse direction
(violation_ratio) and in the lesser one (violation_ratio_lesser), with the pair; then every wrong
estimate with its error and both ratios. Python standard library only."""
import sys

from pairs_csv import read_pairs_csv

WRONG_T_M, WRONG_R_DEG = 0.10, 5.0
NEEDED = ["skip", "from", "to", "estimated", "t_err_m", "r_err_deg", "violation_ratio",
          "violation_ratio_lesser", "reason"]


def is_wrong(r):
    return float(r["t_err_m"]) > WRONG_T_M or float(r["r_err_deg"]) > WRONG_R_DEG


def largest(rows, column):
    """(value, row) of the largest `column` among rows, or (None, None)."""
    if not rows:
        return None, None
    best = max(rows, key=lambda r: float(r[column]))
    return float(best[column]), best


def pair_name(r):
    return "skip %s %s -> %s" % (r["skip"], r["from"], r["to"])


def summary_row(label, rows):
    est = [r for r in rows if r["estimated"] == "1"]
    wrong = [r for r in est if is_wrong(r)]
    right = [r for r in est if not is_wrong(r)]
    both = sum(1 for r in rows if r["estimated"] != "1" and "seen from both views" in r["reason"])
    cells = [label, str(len(rows)), str(len(est)), str(len(wrong)), str(both)]
    for column in ("violation_ratio", "violation_ratio_lesser"):
        value, row = largest(right, column)
        cells.append("-" if row is None else "%.3f (%s)" % (value, pair_name(row)))
    return "| " + " | ".join(cells) + " |", wrong


def main(argv):
    method = "gasp"
    paths = []
    i = 1
    while i < len(argv):
        if argv[i] == "--method" and i + 1 < len(argv):
            method = argv[i + 1]
            i += 2
            continue
        paths.append(argv[i])
        i += 1
    if not paths:
        sys.exit(__doc__.split("\n\n")[1])
    files = [(path.split("/")[-1], read_pairs_csv(path, method, NEEDED, "violation columns")) for path in paths]
    everything = [r for _, rows in files for r in rows]
    if not everything:
        sys.exit("error: no pair of method %s in %s" % (method, ", ".join(paths)))
    print("| file | pairs | estimates | wrong (> %.2f m or %.0f deg) | declined by the two-way limit |"
          " right: largest violation ratio | right: largest in the lesser direction |"
          % (WRONG_T_M, WRONG_R_DEG))
    print("|---|---|---|---|---|---|---|")
    wrong_all = []
    for label, rows in files:
        line, wrong = summary_row(label, rows)
        print(line)
        wrong_all += [(label, r) for r in wrong]
    if len(files) > 1:
        print(summary_row("all", everything)[0])
    print()
    print("wrong estimates: %d" % len(wrong_all))
    for label, r in wrong_all:
        print("  %s %s: %.3f m / %.1f deg off, violations %.3f, lesser direction %.3f"
              % (label, pair_name(r), float(r["t_err_m"]), float(r["r_err_deg"]),
                 float(r["violation_ratio"]), float(r["violation_ratio_lesser"])))


if __name__ == "__main__":
    main(sys.argv)
