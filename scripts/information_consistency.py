#!/usr/bin/env python3
"""How far a gasp-pairs --pairs-csv file's claimed information can be trusted (docs/pipeline.md,
"How far the information can be trusted").

  scripts/information_consistency.py PAIRS.csv [METHOD]

Per skip, over the pairs with an estimate and a NEES (GASP with ground truth): the median NEES of
the error under the edge information (columns nees, nees_t, nees_r: PairResult::edge_information,
the refinement's information with the model error added) and under the refinement's own
(nees_refinement), each divided by the chi-square median of its degrees of freedom (6 for the
whole pose, 3 for its translation and rotation parts): 1 = as certain as the errors allow, above 1 =
too certain by that factor in variance, below 1 = too cautious. And the share of pairs whose NEES is
within the chi-square (6) 95 % quantile (95 % if the information were right).
The reference's own error counts as estimation error here: against an imperfect reference the
factors are upper bounds.
With the pairs' true motion (columns motion_t_m, motion_r_deg), a second table splits all the
estimates into quarters by translation: median motion, RMS error and the median NEES ratios of
the parts, so that an error that grows with the baseline shows (the model error does not grow).
Python standard library only."""
import math
import statistics
import sys

from pairs_csv import read_pairs_csv

CHI2_6_MEDIAN = 5.348120627
CHI2_3_MEDIAN = 2.365973884
CHI2_6_Q95 = 12.591587243


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    method = sys.argv[2] if len(sys.argv) > 2 else "gasp"
    path = sys.argv[1]
    rows = read_pairs_csv(path, method, {"skip", "method", "estimated", "nees", "nees_t", "nees_r", "nees_refinement"},
                          "NEES columns")
    by_skip = {}
    for row in rows:
        if row["estimated"] == "1" and row["nees"] != "" and row["nees_refinement"] != "":
            by_skip.setdefault(int(row["skip"]), []).append(row)
    if not by_skip:
        sys.exit("error: %s: no estimated pair of method %s with a NEES (GASP methods with ground truth only)"
                 % (path, method))
    print("| skip | pairs | edge information: median NEES / chi2 median (pose, translation, rotation) "
          "| within the 95 % quantile | refinement's information: median NEES / chi2 median | within the 95 % quantile |")
    print("|---|---|---|---|---|---|")
    for skip in sorted(by_skip):
        rs = by_skip[skip]
        med = lambda name: statistics.median(float(r[name]) for r in rs)
        share = lambda name: sum(float(r[name]) <= CHI2_6_Q95 for r in rs) / len(rs)
        print("| %d | %d | %.3g (%.3g, %.3g) | %.0f %% | %.3g | %.0f %% |" % (
            skip, len(rs), med("nees") / CHI2_6_MEDIAN, med("nees_t") / CHI2_3_MEDIAN, med("nees_r") / CHI2_3_MEDIAN,
            100 * share("nees"), med("nees_refinement") / CHI2_6_MEDIAN, 100 * share("nees_refinement")))
    every = sorted((r for rs in by_skip.values() for r in rs if r.get("motion_t_m", "") != ""),
                   key=lambda r: float(r["motion_t_m"]))
    if len(every) >= 4:
        print()
        print("| quarter by motion | pairs | median motion t [m] / r [deg] | RMS error t [m] / r [deg] "
              "| median NEES / chi2 median: translation, rotation |")
        print("|---|---|---|---|---|")
        n = len(every)
        for q in range(4):
            rs = every[q * n // 4:(q + 1) * n // 4]
            med = lambda name: statistics.median(float(r[name]) for r in rs)
            rms = lambda name: math.sqrt(sum(float(r[name]) ** 2 for r in rs) / len(rs))
            print("| %d | %d | %.3f / %.1f | %.4f / %.2f | %.3g, %.3g |" % (
                q + 1, len(rs), med("motion_t_m"), med("motion_r_deg"), rms("t_err_m"), rms("r_err_deg"),
                med("nees_t") / CHI2_3_MEDIAN, med("nees_r") / CHI2_3_MEDIAN))


if __name__ == "__main__":
    main()
