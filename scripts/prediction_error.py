#!/usr/bin/env python3
"""How far a constant-velocity prediction lands from the next pose of a trajectory: the
statistic the odometry's scene-change gate tests (docs/odometry.md, "Scenes that change").

  scripts/prediction_error.py TRAJ.txt [--at DEPTH.txt] [--gate M,DEG]

TRAJ.txt is a TUM trajectory (timestamp tx ty tz qx qy qz qw). Each pose i is predicted from
poses i-2 and i-1 with their motion scaled to the time step (constant body twist) and compared
with pose i: the distance of the positions and the angle between the rotations. With --at, the
poses are first interpolated at the timestamps of a TUM list (such as a folder's depth.txt;
stamps outside the trajectory are left out): a reference such as groundtruth.txt at the frames.
Prints the count and the median, 95 % and largest of both, and with --gate how many predictions
lie outside M metres or DEG degrees. Python standard library only."""
import bisect
import math
import sys

from pairs_csv import pop_option
from scene_change_summary import angle_deg, qinv, qmul, qrot, read_tum


def qlog(q):
    x, y, z, w = q
    if w < 0:
        x, y, z, w = -x, -y, -z, -w
    s = math.sqrt(x * x + y * y + z * z)
    a = 2.0 * math.atan2(s, w)
    return (0.0, 0.0, 0.0) if s < 1e-12 else (x / s * a, y / s * a, z / s * a)


def qexp(v):
    a = math.sqrt(sum(c * c for c in v))
    if a < 1e-12:
        return (0.0, 0.0, 0.0, 1.0)
    s = math.sin(a / 2.0) / a
    return (v[0] * s, v[1] * s, v[2] * s, math.cos(a / 2.0))


def stamps_of(path):
    try:
        with open(path) as f:
            lines = [line.split() for line in f if line.strip() and not line.startswith("#")]
    except OSError as e:
        sys.exit("error: cannot read %s: %s" % (path, e.strerror))
    try:
        return [float(v[0]) for v in lines]
    except ValueError:
        sys.exit("error: %s: a line does not start with a timestamp" % path)


def interpolate(poses, times, t):
    """The pose at t (linear in position, slerp in rotation), or None outside the trajectory."""
    k = bisect.bisect_left(times, t)
    if k < len(times) and times[k] == t:
        return poses[times[k]]
    if k == 0 or k == len(times):
        return None
    (pa, qa), (pb, qb) = poses[times[k - 1]], poses[times[k]]
    s = (t - times[k - 1]) / (times[k] - times[k - 1])
    d = qlog(qmul(qinv(qa), qb))
    return [pa[i] * (1 - s) + pb[i] * s for i in range(3)], qmul(qa, qexp([c * s for c in d]))


def percentile(values, p):
    v = sorted(values)
    return v[min(len(v) - 1, int(p / 100.0 * len(v)))]


def main():
    args = sys.argv[1:]
    at = pop_option(args, "--at", None, "a TUM list")
    gate = pop_option(args, "--gate", None, "M,DEG")
    if len(args) != 1:
        sys.exit(__doc__.split("\n\n")[1])
    poses = read_tum(args[0])
    times = sorted(poses)
    if at is not None:
        sequence = [(t, interpolate(poses, times, round(t, 4))) for t in stamps_of(at)]
        sequence = [(t, p) for t, p in sequence if p is not None]
    else:
        sequence = [(t, poses[t]) for t in times]
    if gate is not None:
        try:
            gate_m, gate_deg = (float(x) for x in gate.split(","))
        except ValueError:
            sys.exit("error: --gate needs M,DEG (two numbers), not '%s'" % gate)
    off_m, off_deg = [], []
    for (t0, (p0, q0)), (t1, (p1, q1)), (t2, (p2, q2)) in zip(sequence, sequence[1:], sequence[2:]):
        if not (t1 > t0 and t2 > t1):
            sys.exit("error: timestamps %.6f, %.6f, %.6f are not increasing" % (t0, t1, t2))
        scale = (t2 - t1) / (t1 - t0)
        step_t = qrot(qinv(q0), [p1[k] - p0[k] for k in range(3)])
        step_q = qmul(qinv(q0), q1)
        q_pred = qmul(q1, qexp([c * scale for c in qlog(step_q)]))
        p_pred = [p1[k] + c for k, c in enumerate(qrot(q1, [c * scale for c in step_t]))]
        off_m.append(math.sqrt(sum((p_pred[k] - p2[k]) ** 2 for k in range(3))))
        off_deg.append(angle_deg(qmul(qinv(q_pred), q2)))
    if not off_m:
        sys.exit("error: fewer than three poses%s" % (" at the stamps of " + at if at else ""))
    print("%d predictions: position off median %.4f m, 95 %% %.4f m, largest %.4f m; rotation off median %.2f deg, "
          "95 %% %.2f deg, largest %.2f deg" % (len(off_m), percentile(off_m, 50), percentile(off_m, 95), max(off_m),
                                               percentile(off_deg, 50), percentile(off_deg, 95), max(off_deg)))
    if gate is not None:
        outside = sum(1 for m, d in zip(off_m, off_deg) if m > gate_m or d > gate_deg)
        print("outside %.4f m / %.2f deg: %d" % (gate_m, gate_deg, outside))


if __name__ == "__main__":
    main()
