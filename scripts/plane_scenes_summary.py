#!/usr/bin/env python3
"""Counts of the pairs of gasp-pairs --pairs-csv files (scripts/plane_scenes.sh): per file and
skip, the pairs, the full poses within 5 cm and 2 deg of the truth (right) and beyond (wrong), the
partial poses (a `partial` column of 1, when the CSV has one) right and wrong by the same limits
in their observed directions (`observed_t_err_m`, `observed_r_err_deg`; a partial pose without
them counts as wrong), and the pairs without an estimate, with the most common reason for those.
Prints a Markdown table.

Usage: plane_scenes_summary.py PATH [PATH ...]   (PATH: a CSV, or PREFIX of PREFIX.pairs.csv)
"""
import collections
import csv
import os
import sys

RIGHT_T_M, RIGHT_R_DEG = 0.05, 2.0


def fail(message):
    print("error: " + message, file=sys.stderr)
    sys.exit(1)


def rows_of(path):
    csv_path = path if os.path.isfile(path) else path + ".pairs.csv"
    if not os.path.isfile(csv_path):
        fail(f"no file {csv_path}")
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    needed = {"skip", "method", "estimated", "t_err_m", "r_err_deg", "reason"}
    if not rows or not needed <= set(rows[0]):
        fail(f"{csv_path}: not a gasp-pairs --pairs-csv file (needs {', '.join(sorted(needed))})")
    return os.path.basename(csv_path).removesuffix(".pairs.csv"), rows


def short_reason(reason):
    """The reason's kind: what comes before its first ':' (e.g. 'degenerate scene')."""
    return reason.split(":")[0].strip() or "-"


def within(t_err_m, r_err_deg):
    """Whether both errors are given and within the limits."""
    if not t_err_m or not r_err_deg:
        return False
    return float(t_err_m) <= RIGHT_T_M and float(r_err_deg) <= RIGHT_R_DEG


def main(paths):
    if not paths:
        fail("give at least one --pairs-csv file")
    files = [rows_of(path) for path in paths]  # every file checked before anything is printed
    print("| scene | skip | pairs | full right | full wrong | partial right | partial wrong | no estimate |"
          " most common reason |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, rows in files:
        by_skip = collections.defaultdict(list)
        for row in rows:
            if row["method"] == "gasp":
                by_skip[int(row["skip"])].append(row)
        for skip in sorted(by_skip):
            right = wrong = partial_right = partial_wrong = none = 0
            reasons = collections.Counter()
            for row in by_skip[skip]:
                if row.get("partial") == "1":
                    if within(row.get("observed_t_err_m"), row.get("observed_r_err_deg")):
                        partial_right += 1
                    else:
                        partial_wrong += 1
                elif row["estimated"] != "1":
                    none += 1
                    reasons[short_reason(row["reason"])] += 1
                elif within(row["t_err_m"], row["r_err_deg"]):
                    right += 1
                else:
                    wrong += 1
            reason = "%s (%d)" % reasons.most_common(1)[0] if reasons else "-"
            print(f"| {name} | {skip} | {len(by_skip[skip])} | {right} | {wrong} | {partial_right} | {partial_wrong} |"
                  f" {none} | {reason} |")


if __name__ == "__main__":
    main(sys.argv[1:])
