#!/usr/bin/env python3
"""A TUM folder (depth.txt, groundtruth.txt) and a pairs CSV whose rotation errors depend on the
camera's velocity in a known way, for scripts/error_vs_velocity.py's test:
  pitch and roll errors are linear in v_j - v_i (R^2 1 on either fit),
  the yaw error is pseudo-random, independent of the motion (R^2 low on both fits).
Also offset_pairs.csv, for scripts/keyframe_offsets.py: errors that are one offset per frame,
with one step (below).
And frame_pairs.csv, for scripts/frame_rotation_fit.py: errors of a reference turned by a constant
rotation (below).
Usage: make_velocity_fixture.py OUT_DIR"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))
import error_vs_velocity as ev  # noqa: E402

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
t0 = 1000.0
with open(os.path.join(out, "groundtruth.txt"), "w") as f:
    f.write("# timestamp tx ty tz qx qy qz qw\n")
    for k in range(600):  # 6 s at 100 Hz: a camera swinging on three axes
        t = k * 0.01
        p = (0.3 * math.sin(1.3 * t), 0.2 * math.sin(2.1 * t + 1), 0.25 * math.sin(0.9 * t + 2))
        yaw, pitch = 0.3 * math.sin(1.1 * t), 0.2 * math.sin(1.7 * t + 0.5)
        q = (math.sin(pitch / 2) * math.cos(yaw / 2), math.cos(pitch / 2) * math.sin(yaw / 2),
             -math.sin(pitch / 2) * math.sin(yaw / 2), math.cos(pitch / 2) * math.cos(yaw / 2))
        f.write("%.4f %.6f %.6f %.6f %.8f %.8f %.8f %.8f\n" % ((t0 + t,) + p + q))
stamps = [t0 + 0.2 + 0.0333 * k for k in range(160)]
with open(os.path.join(out, "depth.txt"), "w") as f:
    f.write("# timestamp filename\n")
    for s in stamps:
        f.write("%.6f depth/%.6f.png\n" % (s, s))


def exp_rotation(v):
    a = math.sqrt(sum(x * x for x in v))
    if a < 1e-15:
        return [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    k = [x / a for x in v]
    c, s = math.cos(a), math.sin(a)
    kx = [[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]
    kk = ev.mat_mul(kx, kx)
    return [[(1 if i == j else 0) + s * kx[i][j] + (1 - c) * kk[i][j] for j in range(3)] for i in range(3)]


def matrix_to_quat(r):
    w = math.sqrt(max(0.0, 1 + r[0][0] + r[1][1] + r[2][2])) / 2
    return ((r[2][1] - r[1][2]) / (4 * w), (r[0][2] - r[2][0]) / (4 * w), (r[1][0] - r[0][1]) / (4 * w), w)


gt = ev.Trajectory(os.path.join(out, "groundtruth.txt"))
state = 12345


def uniform():  # a fixed linear congruential sequence in [-0.5, 0.5)
    global state
    state = (1103515245 * state + 12345) % 2**31
    return state / 2**31 - 0.5


with open(os.path.join(out, "pairs.csv"), "w") as f:
    f.write("skip,method,from,to,estimated,qx,qy,qz,qw\n")
    for i in range(0, 140, 2):
        j = i + 10
        (ri, _), (rj, _) = gt.pose(stamps[i]), gt.pose(stamps[j])
        (vi, _), (vj, _) = gt.velocity(stamps[i]), gt.velocity(stamps[j])
        dv = [b - a for a, b in zip(vi, vj)]
        e_deg = [1.1 * dv[1] - 0.8 * dv[2], uniform(), 0.7 * dv[0]]  # target frame
        r_true = ev.mat_mul(ev.transpose(rj), ri)
        e_local = ev.mat_vec(ev.transpose(r_true), [math.radians(x) for x in e_deg])
        q = matrix_to_quat(ev.mat_mul(r_true, exp_rotation(e_local)))
        f.write("10,gasp,%d,%d,1,%.12f,%.12f,%.12f,%.12f\n" % ((i, j) + q))
    f.write("10,shot,0,10,1,0,0,0,1\n")  # another method: not read
    f.write("10,gasp,1,11,0,,,,\n")  # no estimate: not read

# For scripts/keyframe_offsets.py: pairs (i, i + 1) and (i, i + 2) over frames 0-40 whose errors
# are exactly o_j - o_i (target frame), with one offset for frames 0-14 and another from frame 15
# on: the fit leaves nothing and shows one step, at frame 15, of |(-1, 0.3, 2)| = 2.26 deg.
def frame_offset(k):
    return [0.5, 0.0, -1.0] if k < 15 else [-0.5, 0.3, 1.0]


with open(os.path.join(out, "offset_pairs.csv"), "w") as f:
    f.write("skip,method,from,to,estimated,qx,qy,qz,qw\n")
    for skip in (1, 2):
        for i in range(0, 41 - skip):
            j = i + skip
            (ri, _), (rj, _) = gt.pose(stamps[i]), gt.pose(stamps[j])
            e_deg = [b - a for a, b in zip(frame_offset(i), frame_offset(j))]
            r_true = ev.mat_mul(ev.transpose(rj), ri)
            e_local = ev.mat_vec(ev.transpose(r_true), [math.radians(x) for x in e_deg])
            q = matrix_to_quat(ev.mat_mul(r_true, exp_rotation(e_local)))
            f.write("%d,gasp,%d,%d,1,%.12f,%.12f,%.12f,%.12f\n" % ((skip, i, j) + q))

# For scripts/frame_rotation_fit.py: pairs (i, i + 10) whose errors are exactly those of a
# reference turned by a constant delta = (2, 0, -1) deg: e = (R^T - I) delta (source frame), so
# the fit finds delta on all pairs and on either half, and leaves nothing.
delta = [math.radians(2.0), 0.0, math.radians(-1.0)]
with open(os.path.join(out, "frame_pairs.csv"), "w") as f:
    f.write("skip,method,from,to,estimated,qx,qy,qz,qw\n")
    for i in range(0, 140, 2):
        j = i + 10
        (ri, _), (rj, _) = gt.pose(stamps[i]), gt.pose(stamps[j])
        r_ref = ev.mat_mul(ev.transpose(rj), ri)
        a = [[r_ref[c][r] - (1.0 if r == c else 0.0) for c in range(3)] for r in range(3)]  # R^T - I
        e = ev.mat_vec(a, delta)
        q = matrix_to_quat(ev.mat_mul(r_ref, exp_rotation(e)))
        f.write("10,gasp,%d,%d,1,%.12f,%.12f,%.12f,%.12f\n" % ((i, j) + q))
