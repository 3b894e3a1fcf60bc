"""Writes a multi-scan E57 with pye57 (libE57Format), as a terrestrial scanner's software would:
one data3D per scan, its points in the scan frame and its pose (rotation quaternion w,x,y,z and
translation) in the file.

usage: scans_to_e57.py OUT.e57 NAME XYZ_FILE POSE [NAME XYZ_FILE POSE ...]
  XYZ_FILE: `x y z [intensity]` lines (as `semsim convert` writes .xyz)
  POSE: 16 comma-separated numbers, the row-major 4x4 world_from_scan
"""
import sys

import numpy as np
import pye57


def quaternion_wxyz(r):
    """The unit quaternion (w, x, y, z) of a rotation matrix."""
    t = np.trace(r)
    if t > 0:
        s = np.sqrt(t + 1.0) * 2
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    else:
        i = int(np.argmax(np.diag(r)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = np.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k]) * 2
        q = [0.0, 0.0, 0.0, 0.0]
        q[0] = (r[k, j] - r[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (r[j, i] + r[i, j]) / s
        q[1 + k] = (r[k, i] + r[i, k]) / s
    q = np.array(q)
    return q / np.linalg.norm(q)


def main():
    args = sys.argv[1:]
    if len(args) < 4 or (len(args) - 1) % 3:
        sys.exit(__doc__)
    out = pye57.E57(args[0], mode="w")
    for name, xyz_file, pose in zip(args[1::3], args[2::3], args[3::3]):
        m = np.array([float(v) for v in pose.split(",")]).reshape(4, 4)
        pts = np.loadtxt(xyz_file, ndmin=2)
        data = {"cartesianX": pts[:, 0], "cartesianY": pts[:, 1], "cartesianZ": pts[:, 2]}
        if pts.shape[1] > 3:
            data["intensity"] = pts[:, 3]
        out.write_scan_raw(data, name=name, rotation=quaternion_wxyz(m[:3, :3]), translation=m[:3, 3])
    out.close()


if __name__ == "__main__":
    main()
