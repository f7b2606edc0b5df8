#!/usr/bin/env python3
"""Per-skip summary of a gasp-pairs --pairs-csv file (docs/association.md, docs/pipeline.md).

  scripts/pair_association_summary.py PAIRS.csv [METHOD]

1. Association quality over every pair with an estimate: the free associations' precision and
   the verified associations' precision and density (median, mean, share of pairs at >= 0.8 and
   >= 0.9), and the median pose error.
2. How well the estimate and the ground truth explain the depth (the agreement columns: share of
   samples within a tight gate of the other view's surface) and on how many pairs each is the
   better by more than 0.02.
3. The pairs without an estimate, with their true motion and the reason; the pairs the
   finer-scale retry registered (column finer_scale), with their motion and error; the largest
   true motion among the pairs with an estimate.
4. Loop closure of the estimates: for every i with estimates i -> i+s, i+s -> i+2s and i -> i+2s
   (skips s and 2s both in the file), the motion left by (i -> i+2s)^-1 (i+s -> i+2s) (i -> i+s).
5. With gasp-pairs --polish-reference: an independent check by PCL's GICP, run from the reference
   pose and from the estimate. Per skip: how far GICP moves the reference and the estimate
   (median), how far apart the two GICP results end (median), and the RMSE of the estimate against
   the reference and against the GICP-polished reference; the verified associations' precision
   against each; and the GICP-polished reference scored like an estimate against the reference
   (RMSE per skip, every pair GICP ran on): what the reference can certify.
Python standard library only."""
import math
import statistics
import sys

from pairs_csv import read_pairs_csv


def qmul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def qrot(q, v):
    p = qmul(qmul(q, (v[0], v[1], v[2], 0.0)), (-q[0], -q[1], -q[2], q[3]))
    return p[:3]


def compose(a, b):  # a * b, poses as (t, q)
    r = qrot(a[1], b[0])
    return ((a[0][0] + r[0], a[0][1] + r[1], a[0][2] + r[2]), qmul(a[1], b[1]))


def inverse(a):
    qi = (-a[1][0], -a[1][1], -a[1][2], a[1][3])
    r = qrot(qi, a[0])
    return ((-r[0], -r[1], -r[2]), qi)


def pose_of(row):
    q = tuple(float(row[k]) for k in ("qx", "qy", "qz", "qw"))
    n = math.sqrt(sum(x * x for x in q))
    return (tuple(float(row[k]) for k in ("tx", "ty", "tz")), tuple(x / n for x in q))


def size(pose):
    return math.sqrt(sum(x * x for x in pose[0])), math.degrees(2.0 * math.acos(min(1.0, abs(pose[1][3]))))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    method = sys.argv[2] if len(sys.argv) > 2 else "gasp"
    path = sys.argv[1]
    rows = read_pairs_csv(path, method, {"skip", "method", "from", "to", "estimated", "t_err_m", "r_err_deg",
                                         "precision", "verified_precision", "verified_density", "agreement",
                                         "agreement_truth"}, "association columns")
    by_skip = {}
    for row in rows:
        if row["estimated"] == "1" and row.get("verified_precision", "") != "":
            by_skip.setdefault(int(row["skip"]), []).append(row)
    if not by_skip:
        sys.exit("error: %s: no estimated pair of method %s with association scores (they exist for GASP methods only)" % (path, method))
    print("| skip | pairs with an estimate | free precision: median | verified precision: median / mean "
          "| pairs >= 0.8 / >= 0.9 | verified density: median | pose error: median t [m] / r [deg] |")
    print("|---|---|---|---|---|---|---|")
    for skip in sorted(by_skip):
        rs = by_skip[skip]
        col = lambda name: [float(r[name]) for r in rs]
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
        rs = by_skip[skip]
        est = [float(r["agreement"]) for r in rs]
        gt = [float(r["agreement_truth"]) for r in rs]
        print("| %d | %d | %.3f | %.3f | %d | %d |" % (
            skip, len(rs), statistics.median(est), statistics.median(gt),
            sum(e > g + 0.02 for e, g in zip(est, gt)), sum(g > e + 0.02 for e, g in zip(est, gt))))
    failed = [r for r in rows if r["estimated"] != "1"]
    if failed and "motion_r_deg" in failed[0]:
        print()
        print("| skip | pair | true motion t [m] / r [deg] | reason |")
        print("|---|---|---|---|")
        for r in sorted(failed, key=lambda r: (int(r["skip"]), int(r["from"]))):
            print("| %s | %s -> %s | %.2f / %.1f | %s |" % (r["skip"], r["from"], r["to"], float(r["motion_t_m"]),
                                                        float(r["motion_r_deg"]), r["reason"][:90]))
    retried = [r for r in rows if r.get("finer_scale", "") == "1"]
    if retried:
        print()
        print("| skip | pair registered by the finer-scale retry | true motion t [m] / r [deg] | error t [m] / r [deg] |")
        print("|---|---|---|---|")
        for r in sorted(retried, key=lambda r: (int(r["skip"]), int(r["from"]))):
            print("| %s | %s -> %s | %.2f / %.1f | %.4f / %.2f |" % (
                r["skip"], r["from"], r["to"], float(r["motion_t_m"]), float(r["motion_r_deg"]),
                float(r["t_err_m"]), float(r["r_err_deg"])))
    done = [r for r in rows if r["estimated"] == "1" and r.get("motion_r_deg", "") != ""]
    if done:
        print()
        print("| skip | pairs with an estimate | their largest true motion: t [m] / r [deg] |")
        print("|---|---|---|")
        for skip in sorted({int(r["skip"]) for r in done}):
            ds = [r for r in done if int(r["skip"]) == skip]
            print("| %d | %d | %.2f / %.1f |" % (skip, len(ds), max(float(r["motion_t_m"]) for r in ds),
                                               max(float(r["motion_r_deg"]) for r in ds)))
    est = {(int(r["from"]), int(r["to"])): pose_of(r) for r in rows if r["estimated"] == "1" and r.get("qw", "") != ""}
    skips = sorted({int(r["skip"]) for r in rows})
    loops = []
    for s in skips:
        if 2 * s not in skips:
            continue
        for (i, j) in sorted(est):
            if j - i == s and (j, j + s) in est and (i, i + 2 * s) in est:
                left = compose(inverse(est[(i, i + 2 * s)]), compose(est[(j, j + s)], est[(i, j)]))
                loops.append((s, i) + size(left))
    if loops:
        print()
        print("| loop (skip s, 2s) | loops | residual t [m]: median / max | residual r [deg]: median / max | first loop (i = %d): t / r |"
              % loops[0][1])
        print("|---|---|---|---|---|")
        for s in sorted({l[0] for l in loops}):
            ls = [l for l in loops if l[0] == s]
            print("| %d, %d | %d | %.4f / %.4f | %.2f / %.2f | %.4f / %.2f |" % (
                s, 2 * s, len(ls), statistics.median(l[2] for l in ls), max(l[2] for l in ls),
                statistics.median(l[3] for l in ls), max(l[3] for l in ls), ls[0][2], ls[0][3]))
    polished = [r for r in rows if r["estimated"] == "1" and r.get("est_vs_ref_icp_r_deg", "") != ""]
    if polished:
        rms = lambda v: math.sqrt(sum(x * x for x in v) / len(v))
        print()
        print("| skip | pairs | GICP moves the reference: median t [m] / r [deg] | GICP moves the estimate: median t / r "
              "| GICP from each: apart, median t / r | estimate vs reference: RMSE t / r | estimate vs GICP-polished "
              "reference: RMSE t / r | verified precision, median: against the reference / the polished one |")
        print("|---|---|---|---|---|---|---|---|")
        for skip in sorted({int(r["skip"]) for r in polished}):
            rs = [r for r in polished if int(r["skip"]) == skip]
            col = lambda name: [float(r[name]) for r in rs if r.get(name, "") != ""]
            vp_icp = col("verified_precision_ref_icp")
            print("| %d | %d | %.4f / %.2f | %.4f / %.2f | %.4f / %.2f | %.4f / %.2f | %.4f / %.2f | %.3f / %s |" % (
                skip, len(rs), statistics.median(col("ref_icp_t_m")), statistics.median(col("ref_icp_r_deg")),
                statistics.median(col("est_icp_t_m")), statistics.median(col("est_icp_r_deg")),
                statistics.median(col("icp_est_vs_ref_icp_t_m")), statistics.median(col("icp_est_vs_ref_icp_r_deg")),
                rms(col("t_err_m")), rms(col("r_err_deg")),
                rms(col("est_vs_ref_icp_t_m")), rms(col("est_vs_ref_icp_r_deg")),
                statistics.median(col("verified_precision")),
                "%.3f" % statistics.median(vp_icp) if vp_icp else "-"))
        # The GICP-polished reference scored like an estimate against the reference, over every pair
        # GICP ran on (estimated or not): what the reference can certify (docs/pipeline.md).
        every = [r for r in rows if r.get("ref_icp_r_deg", "") != ""]
        print()
        print("| skip | pairs | GICP-polished reference vs reference: RMSE t [m] / r [deg] |")
        print("|---|---|---|")
        for skip in sorted({int(r["skip"]) for r in every}):
            rs = [r for r in every if int(r["skip"]) == skip]
            print("| %d | %d | %.4f / %.2f |" % (skip, len(rs), rms([float(r["ref_icp_t_m"]) for r in rs]),
                                                rms([float(r["ref_icp_r_deg"]) for r in rs])))


if __name__ == "__main__":
    main()
