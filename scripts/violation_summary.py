#!/usr/bin/env python3
"""The visibility check's violation ratios of right and wrong estimates in gasp-pairs --pairs-csv
files (docs/pipeline.md, "Violations seen from both views").

  scripts/violation_summary.py PAIRS.csv [PAIRS.csv ...] [--method gasp]

An estimate is wrong when it is more than 0.10 m or 5 deg from the reference. Per file and over
all files: pairs, estimates, wrong estimates, pairs declined by the two-way violation limit (the
reason says "seen from both views", at the default scale or in the finer-scale retry), and the
largest violation ratio of the right estimates in the worse direction (violation_ratio) and in
the lesser one (violation_ratio_lesser), with the pair; then every wrong estimate with its error
and both ratios. A numeric field that is not a number is an error naming the file, pair and
column. Python standard library only."""
import os
import sys

from pairs_csv import read_pairs_csv

WRONG_T_M, WRONG_R_DEG = 0.10, 5.0
NUMBERS = ["violation_ratio", "violation_ratio_lesser"]  # every row; the errors too with an estimate
BLOB = "violation_blob_share_lesser"  # optional (files from before it have no such column)
COMPACT_FROM = 0.008  # the right estimates' region share is reported above this lesser ratio
NEEDED = ["skip", "from", "to", "estimated", "t_err_m", "r_err_deg", "reason"] + NUMBERS


def pair_name(r):
    return "skip %s %s -> %s" % (r["skip"], r["from"], r["to"])


def read_rows(path, method):
    """The rows of `method`, their numeric columns as floats; exits naming the file, pair and
    column when one is not a number."""
    rows = read_pairs_csv(path, method, NEEDED, "violation columns")
    for r in rows:
        optional = [BLOB] if BLOB in r else []
        for column in NUMBERS + optional + (["t_err_m", "r_err_deg"] if r["estimated"] == "1" else []):
            try:
                r[column] = float(r[column])
            except ValueError:
                sys.exit("error: %s: %s: column %s is not a number ('%s')"
                         % (path, pair_name(r), column, r[column]))
    return rows


def is_wrong(r):
    return r["t_err_m"] > WRONG_T_M or r["r_err_deg"] > WRONG_R_DEG


def summary_row(label, rows):
    est = [r for r in rows if r["estimated"] == "1"]
    wrong = [r for r in est if is_wrong(r)]
    right = [r for r in est if not is_wrong(r)]
    both = sum(1 for r in rows if r["estimated"] != "1" and "seen from both views" in r["reason"])
    cells = [label, str(len(rows)), str(len(est)), str(len(wrong)), str(both)]
    for column in NUMBERS:
        worst = max(right, key=lambda r: r[column]) if right else None
        cells.append("-" if worst is None else "%.3f (%s)" % (worst[column], pair_name(worst)))
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
    files = [(os.path.basename(path), read_rows(path, method)) for path in paths]
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
    with_blob = all(BLOB in r for r in everything)
    if with_blob:
        shares = [r[BLOB] for r in everything if r["estimated"] == "1" and not is_wrong(r)
                  and r["violation_ratio_lesser"] > COMPACT_FROM]
        print("right estimates with a lesser-direction ratio above %.3f: %d%s" % (
            COMPACT_FROM, len(shares), ", share of its violations in the largest connected region %.2f-%.2f"
            % (min(shares), max(shares)) if shares else ""))
    print("wrong estimates: %d" % len(wrong_all))
    for label, r in wrong_all:
        print("  %s %s: %.3f m / %.1f deg off, violations %.3f, lesser direction %.3f%s"
              % (label, pair_name(r), r["t_err_m"], r["r_err_deg"], r["violation_ratio"],
                 r["violation_ratio_lesser"], " (largest region %.2f)" % r[BLOB] if with_blob else ""))


if __name__ == "__main__":
    main(sys.argv)
