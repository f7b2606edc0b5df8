#!/usr/bin/python3
"""Registers two frames of a TUM RGB-D folder with GASP and prints the pose error against the
folder's ground truth.

    python3 register_tum_pair.py ../shared/data/tum/fr1_xyz [SOURCE_INDEX TARGET_INDEX]
"""
import sys
import time

import numpy as np

import gasp


def main(argv):
    if len(argv) not in (2, 4):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    folder = gasp.TumFolder(argv[1])
    i, j = (int(argv[2]), int(argv[3])) if len(argv) == 4 else (0, min(30, len(folder) - 1))
    source, target = folder.depth(i), folder.depth(j)
    start = time.perf_counter()
    result = gasp.register(source, target, folder.intrinsics)
    wall_ms = 1000 * (time.perf_counter() - start)
    print("frames %d -> %d: %r" % (i, j, result))
    if not result.estimated:
        print("no estimate: " + result.reason)
        return 1
    np.set_printoptions(precision=4, suppress=True)
    print("T_target_source =\n%s" % result.T_target_source)
    T_world_source, T_world_target = folder.ground_truth(i), folder.ground_truth(j)
    if T_world_source is None or T_world_target is None:
        print("no ground truth for these frames")
        return 0
    truth = np.linalg.inv(T_world_target) @ T_world_source
    t_err, r_err = gasp.pose_error(result.T_target_source, truth)
    print("pose error: %.2f cm, %.3f deg (%d verified associations, %.0f ms)"
          % (100 * t_err, r_err, len(result.verified), wall_ms))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
