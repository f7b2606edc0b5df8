#!/usr/bin/env python3
"""Odometry through scenes that change: reads what scripts/scene_change_odometry.sh writes
(docs/odometry.md, "Scenes that change").

  scripts/scene_change_summary.py OUT_DIR

For every run (a folder NAME_M with NAME_M.on.csv / .on.txt / .on.log and the same for `off`,
the run with --no-scene-change) it reads the frames CSV, the trajectory and the program's
summary (tracked, graph_components, ate_rmse_m), and scores every tracked step (a frame against
its reference) against the folder's groundtruth.txt. Per case (NAME) and variant: runs, frames
not tracked, runs whose graph is in more than one piece and the pieces in all, frames taken
through a scene change, the largest step errors of those (translation and rotation, each its own
largest), the same over all steps and how many steps are beyond 2 cm or 1 deg, and the largest
ATE. Then every scene-change step with its
error. Python standard library only."""
import csv
import glob
import math
import os
import re
import sys

BEYOND_T_M, BEYOND_R_DEG = 0.02, 1.0


def qmul(a, b):
    x1, y1, z1, w1 = a
    x2, y2, z2, w2 = b
    return (w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2)


def qinv(q):
    return (-q[0], -q[1], -q[2], q[3])


def qrot(q, v):
    return qmul(qmul(q, (v[0], v[1], v[2], 0.0)), qinv(q))[:3]


def angle_deg(q):
    w = min(1.0, abs(q[3]) / math.sqrt(sum(c * c for c in q)))
    return math.degrees(2.0 * math.acos(w))


def relative(pa, pb):
    """Pose b in frame a; poses are (position, quaternion xyzw)."""
    (ta, qa), (tb, qb) = pa, pb
    return qrot(qinv(qa), [tb[k] - ta[k] for k in range(3)]), qmul(qinv(qa), qb)


def step_error(est_a, est_b, gt_a, gt_b):
    """(m, deg) between the estimated and the true motion from a to b."""
    (te, qe), (tg, qg) = relative(est_a, est_b), relative(gt_a, gt_b)
    d = qrot(qinv(qg), [te[k] - tg[k] for k in range(3)])
    return math.sqrt(sum(c * c for c in d)), angle_deg(qmul(qinv(qg), qe))


def read_tum(path):
    """{timestamp: (position, quaternion)}; exits naming the file when it cannot be read."""
    poses = {}
    try:
        with open(path) as f:
            for n, line in enumerate(f, 1):
                if not line.strip() or line.startswith("#"):
                    continue
                v = line.split()
                try:
                    x = [float(c) for c in v[:8]]
                except ValueError:
                    sys.exit("error: %s line %d: not a number" % (path, n))
                if len(x) != 8:
                    sys.exit("error: %s line %d: a TUM pose needs 8 values" % (path, n))
                poses[round(x[0], 4)] = (x[1:4], tuple(x[4:8]))
    except OSError as e:
        sys.exit("error: cannot read %s: %s" % (path, e.strerror))
    return poses


def read_summary(path):
    """tracked, graph_components and ate_rmse_m from a gasp-odometry output."""
    try:
        text = open(path).read()
    except OSError as e:
        sys.exit("error: cannot read %s: %s" % (path, e.strerror))
    found = {}
    for key in ("tracked", "graph_components", "ate_rmse_m"):
        m = re.search(r"^%s: ([0-9.]+)" % key, text, re.M)
        if not m:
            sys.exit("error: %s has no '%s:' line (not a gasp-odometry output)" % (path, key))
        found[key] = float(m.group(1))
    return found


def read_frames(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit("error: cannot read %s: %s" % (path, e.strerror))
    if rows and "scene_change" not in rows[0]:
        sys.exit("error: %s has no scene_change column (a gasp-odometry --frames-csv file of an older GASP?)" % path)
    return rows


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.split("\n\n")[1])
    out = sys.argv[1]
    folders = sorted(p[:-len(".on.csv")] for p in glob.glob(os.path.join(out, "*.on.csv")))
    if not folders:
        sys.exit("error: %s holds no *.on.csv (run scripts/scene_change_odometry.sh first)" % out)
    table, taken = {}, []
    for folder in folders:
        name = re.sub(r"_\d+$", "", os.path.basename(folder))
        gt = read_tum(os.path.join(folder, "groundtruth.txt"))
        for variant in ("on", "off"):
            summary = read_summary("%s.%s.log" % (folder, variant))
            est = read_tum("%s.%s.txt" % (folder, variant))
            frames = read_frames("%s.%s.csv" % (folder, variant))
            stamp = {int(r["index"]): round(float(r["timestamp"]), 4) for r in frames}
            t = table.setdefault((name, variant), {"runs": 0, "lost": 0, "broken": 0, "pieces": 0, "taken": 0,
                                                   "taken_worst": (0.0, 0.0), "worst": (0.0, 0.0), "beyond": 0,
                                                   "steps": 0, "ate": 0.0})
            t["runs"] += 1
            t["lost"] += len(frames) - int(summary["tracked"])
            t["pieces"] += int(summary["graph_components"])
            t["broken"] += summary["graph_components"] > 1
            t["ate"] = max(t["ate"], summary["ate_rmse_m"])
            for r in frames:
                i, ref = int(r["index"]), int(r["reference"])
                if r["tracked"] != "1" or ref == i:
                    continue
                a, b = stamp[ref], stamp[i]
                if a not in gt or b not in gt or a not in est or b not in est:
                    sys.exit("error: %s: frame %d or %d has no pose in the trajectory or the groundtruth" % (folder, ref, i))
                e = step_error(est[a], est[b], gt[a], gt[b])
                t["steps"] += 1
                t["worst"] = (max(t["worst"][0], e[0]), max(t["worst"][1], e[1]))
                t["beyond"] += e[0] > BEYOND_T_M or e[1] > BEYOND_R_DEG
                if r["scene_change"] == "1":
                    t["taken"] += 1
                    t["taken_worst"] = (max(t["taken_worst"][0], e[0]), max(t["taken_worst"][1], e[1]))
                    taken.append((os.path.basename(folder), ref, i, e, r["reason"].split("scene change: ")[-1]))
    print("case | variant | runs | frames not tracked | runs in pieces (pieces) | scene-change frames "
          "| their largest step errors [m / deg] | largest step errors [m / deg] | steps beyond 2 cm or 1 deg | largest ATE [m]")
    for (name, variant), t in table.items():
        print("%s | %s | %d | %d | %d (%d) | %d | %.3f / %.2f | %.3f / %.2f | %d of %d | %.4f" % (
            name, variant, t["runs"], t["lost"], t["broken"], t["pieces"], t["taken"], t["taken_worst"][0],
            t["taken_worst"][1], t["worst"][0], t["worst"][1], t["beyond"], t["steps"], t["ate"]))
    for v in ("on", "off"):
        rows = [t for (n, var), t in table.items() if var == v]
        print("all | %s | %d | %d | %d (%d) | %d | %.3f / %.2f | %.3f / %.2f | %d of %d | %.4f" % (
            v, sum(t["runs"] for t in rows), sum(t["lost"] for t in rows), sum(t["broken"] for t in rows),
            sum(t["pieces"] for t in rows), sum(t["taken"] for t in rows), max(t["taken_worst"][0] for t in rows),
            max(t["taken_worst"][1] for t in rows), max(t["worst"][0] for t in rows),
            max(t["worst"][1] for t in rows), sum(t["beyond"] for t in rows), sum(t["steps"] for t in rows),
            max(t["ate"] for t in rows)))
    print("\nscene-change steps (run, from, to, error, what was measured):")
    for run, a, b, e, why in taken:
        print("%s %d -> %d: %.3f m / %.2f deg; %s" % (run, a, b, e[0], e[1], why))


if __name__ == "__main__":
    main()
