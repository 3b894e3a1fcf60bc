"""Compares registered poses of 3DTK's corridor with slam6d's 2009 frames and checks the
scans' floors and ceilings agree. Usage: registration_3dtk.py DATA_DIR NAME=poses.txt ...
Writes Markdown to stdout."""
import sys

import numpy as np

# 3DTK's left-handed, y-up, centimetre frame to semsim's right-handed, z-up metres
# (cloud::io::threedtk documents the same map).
P = np.array([[0, 0, 1], [-1, 0, 0], [0, 1, 0]], float)


def load_scan(data, k):
    a = np.loadtxt(f"{data}/scan{k:03d}.3d", usecols=(0, 1, 2))
    p = (P @ a.T).T / 100.0
    r = np.linalg.norm(p, axis=1)
    return p[(r < 32.0) & (r > 0.3)]  # no-echo readings sit at 32.767 m


def slam6d(data, k):
    rows = [l.split() for l in open(f"{data}/frames_2009/scan{k:03d}.frames") if l.strip()]
    m = np.array([float(x) for x in rows[-1][:16]]).reshape(4, 4).T  # column-major
    t = np.eye(4)
    t[:3, :3] = P @ m[:3, :3] @ P.T
    t[:3, 3] = P @ m[:3, 3] / 100.0
    return t


def semsim_poses(path):
    out = {}
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        f = line.split()
        out[f[0]] = np.array([float(x) for x in f[1:17]]).reshape(4, 4)
    return [out[f"scan{k:03d}"] for k in range(3)]


def plane(pts):
    c = pts.mean(0)
    n = np.linalg.svd(pts - c, full_matrices=False)[2][2]
    return (n if n[2] > 0 else -n), c


def slab(p, below):
    """The floor (below the sensor) or ceiling plane within 8 m: the densest 2 cm height bin,
    refined by three plane fits to the points within 4 cm."""
    sel = p[np.hypot(p[:, 0], p[:, 1]) < 8]
    z = sel[:, 2]
    zs = z[z < -0.2] if below else z[z > 0.2]
    hist, edges = np.histogram(zs, bins=np.arange(zs.min(), zs.max() + 0.02, 0.02))
    z0 = (edges[hist.argmax()] + edges[hist.argmax() + 1]) / 2
    pts = sel[np.abs(z - z0) < 0.06]
    for _ in range(3):
        n, c = plane(pts)
        pts = sel[np.abs((sel - c) @ n) < 0.04]
    return plane(pts)[0]


def angle_deg(r):
    return np.degrees(np.arccos(np.clip((np.trace(r) - 1) / 2, -1, 1)))


def main():
    data = sys.argv[1]
    runs = [a.rsplit("=", 1) for a in sys.argv[2:]]
    scans = [load_scan(data, k) for k in range(3)]
    floors = [slab(s, True) for s in scans]
    ceilings = [slab(s, False) for s in scans]
    sets = [("slam6d 2009 (reference)", [slam6d(data, k) for k in range(3)])]
    sets += [(name, semsim_poses(path)) for name, path in runs]
    ref = sets[0][1]
    print("# 3DTK corridor: registration against slam6d 2009, and floor agreement\n")
    print("Command: `bash bench/registration_3dtk.sh`. Scans 1 and 2 relative to scan 0. "
          "'floor'/'ceiling': angle between the scan's plane normal (fitted in its own "
          "frame, moved by the poses) and scan 0's; a flat floor under a correct "
          "registration gives about 0.\n")
    print("| poses | scan | vs slam6d (cm) | vs slam6d (deg) | floor (deg) | ceiling (deg) |")
    print("|---|---|---|---|---|---|")
    for name, t in sets:
        for k in (1, 2):
            rel = np.linalg.inv(t[0]) @ t[k]
            r = rel[:3, :3]
            a = np.linalg.inv(ref[0]) @ ref[k]
            d_cm = np.linalg.norm(a[:3, 3] - rel[:3, 3]) * 100
            d_deg = angle_deg(np.linalg.inv(a)[:3, :3] @ r)
            fl = np.degrees(np.arccos(np.clip((r @ floors[k]) @ floors[0], -1, 1)))
            ce = np.degrees(np.arccos(np.clip((r @ ceilings[k]) @ ceilings[0], -1, 1)))
            print(f"| {name} | {k} | {d_cm:.1f} | {d_deg:.2f} | {fl:.2f} | {ce:.2f} |")


main()
