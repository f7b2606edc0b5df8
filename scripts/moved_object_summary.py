#!/usr/bin/env python3
"""What registration gives across a moved object: reads the folders and pairs CSVs that
scripts/moved_object_pairs.sh writes (docs/pipeline.md, "Objects that moved").

  scripts/moved_object_summary.py OUT_DIR [--method gasp]

A pair straddles a move when it runs from before the move's frame (scene.txt, `move: ...@M`) to
M or later. Per case (the folder name without its `_M`), for the straddling and the static pairs:
pairs, right estimates (within 0.10 m and 5 deg of the reference), wrong estimates and no
estimate, with how many of those the two-way violation limit declined (the reason says "seen from
both views"), and the largest violation ratio in the lesser direction of the right straddling
estimates (what the two-way limit would have to allow); then, per skip, how many straddling and
static pairs gave no estimate (the move's share of the failures, apart from the skip's own); how
compact the violations of the right straddling estimates are (the smaller of the two directions'
shares of violations in their largest connected region, over those whose lesser ratio is above
0.01); then every wrong estimate. A numeric field that is not a number is an error naming the
file, pair and column. Python standard library only."""
import glob
import os
import re
import sys

from pairs_csv import pop_option, read_pairs_csv

WRONG_T_M, WRONG_R_DEG = 0.10, 5.0
NEEDED = ["skip", "from", "to", "estimated", "t_err_m", "r_err_deg", "violation_ratio", "violation_ratio_lesser",
          "violation_blob_share_lesser", "reason"]
COMPACT_FROM = 0.01  # the right straddling estimates' region share is reported above this lesser ratio


def move_frames(folder):
    """The frames of the moves in folder/scene.txt; exits naming the file when there is none."""
    path = os.path.join(folder, "scene.txt")
    try:
        with open(path) as f:
            frames = [int(m.group(1)) for m in (re.match(r"move: .*@(\d+)$", line.strip()) for line in f) if m]
    except OSError as e:
        sys.exit("error: cannot read %s: %s" % (path, e.strerror))
    if not frames:
        sys.exit("error: %s lists no move (not a folder of scripts/moved_object_pairs.sh)" % path)
    return frames


def tally():
    return {"pairs": 0, "right": 0, "wrong": 0, "none": 0, "two_way": 0, "lesser": 0.0}


def main():
    args = sys.argv[1:]
    method = pop_option(args, "--method", "gasp", "a name")
    if len(args) != 1:
        sys.exit(__doc__.split("\n\n")[1])
    out = args[0]
    csvs = sorted(glob.glob(os.path.join(out, "*.pairs.csv")))
    if not csvs:
        sys.exit("error: %s holds no *.pairs.csv (run scripts/moved_object_pairs.sh first)" % out)
    cases, wrong, by_skip, shares = {}, [], {}, []
    for path in csvs:
        folder = path[:-len(".pairs.csv")]
        frames = move_frames(folder)
        case = re.sub(r"_\d+$", "", os.path.basename(folder))
        c = cases.setdefault(case, {"straddling": tally(), "static": tally()})
        for r in read_pairs_csv(path, method, NEEDED, "visibility columns"):
            pair = "%s -> %s" % (r["from"], r["to"])
            numbers = ["skip", "from", "to", "violation_ratio", "violation_ratio_lesser", "violation_blob_share_lesser"]
            for column in numbers + (["t_err_m", "r_err_deg"] if r["estimated"] == "1" else []):
                try:
                    r[column] = (int if column in ("skip", "from", "to") else float)(r[column])
                except ValueError:
                    sys.exit("error: %s: pair %s: column %s is not a number ('%s')" % (path, pair, column, r[column]))
            i, j = r["from"], r["to"]
            kind = "straddling" if any(i < m <= j for m in frames) else "static"
            t = c[kind]
            t["pairs"] += 1
            k = by_skip.setdefault(r["skip"], {"straddling": [0, 0], "static": [0, 0]})[kind]
            k[0] += 1
            k[1] += r["estimated"] != "1"
            if r["estimated"] != "1":
                t["none"] += 1
                t["two_way"] += "seen from both views" in r["reason"]
                continue
            t_err, r_err = r["t_err_m"], r["r_err_deg"]
            if t_err > WRONG_T_M or r_err > WRONG_R_DEG:
                t["wrong"] += 1
                wrong.append("%s %s: %s -> %s (skip %d): %.3f m / %.1f deg off, violations %.3f, lesser direction %.3f"
                             % (os.path.basename(folder), kind, i, j, r["skip"], t_err, r_err,
                                r["violation_ratio"], r["violation_ratio_lesser"]))
            else:
                t["right"] += 1
                t["lesser"] = max(t["lesser"], r["violation_ratio_lesser"])
                if kind == "straddling" and r["violation_ratio_lesser"] > COMPACT_FROM:
                    shares.append(r["violation_blob_share_lesser"])
    print("| case | straddling pairs | right | wrong | no estimate (two-way limit) | right: largest lesser ratio | "
          "static pairs | right | wrong | no estimate |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    total = {"straddling": tally(), "static": tally()}
    for case, c in list(cases.items()) + [("all", total)]:
        s, st = c["straddling"], c["static"]
        if case != "all":
            for kind in total:
                for key in ("pairs", "right", "wrong", "none", "two_way"):
                    total[kind][key] += c[kind][key]
                total[kind]["lesser"] = max(total[kind]["lesser"], c[kind]["lesser"])
        print("| %s | %d | %d | %d | %d (%d) | %.3f | %d | %d | %d | %d |"
              % (case, s["pairs"], s["right"], s["wrong"], s["none"], s["two_way"], s["lesser"], st["pairs"],
                 st["right"], st["wrong"], st["none"]))
    print("\nno estimate by skip (straddling, static): " + ", ".join(
        "%d: %d/%d, %d/%d" % (skip, k["straddling"][1], k["straddling"][0], k["static"][1], k["static"][0])
        for skip, k in sorted(by_skip.items())))
    print("right straddling estimates with a lesser-direction ratio above %.2f: %d%s" % (
        COMPACT_FROM, len(shares), ", share of its violations in the largest connected region %.2f-%.2f, %d of them "
        ">= 0.5" % (min(shares), max(shares), sum(x >= 0.5 for x in shares)) if shares else ""))
    print("\nwrong estimates: %d" % len(wrong))
    for w in wrong:
        print("  " + w)


if __name__ == "__main__":
    main()
