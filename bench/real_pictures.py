"""Pictures of a `semsim run` on real scans: what a person sees in the scans beside the map.

    python bench/real_pictures.py RUN_DIR OUT_PREFIX

RUN_DIR is a `semsim run --out` folder; writes OUT_PREFIX-scans.png (the registered cloud from
above and obliquely, coloured by height, the ceiling left out so that the inside shows) and
OUT_PREFIX-map.png (the semantic map from above at the same scale: the floor where it was seen,
walls, door leaves with their swing, openings, obstacles, columns and beams, and the robot's
simulated path in red). Reads map/labels.pcd (binary PCD, the registered points in the input
frame), map/semantic_map.json and simulation/trajectory.csv. Needs numpy only; PNGs are written
with zlib.
"""

import csv
import json
import math
import struct
import sys
import zlib

import numpy as np

# Class colours as semsim's own pictures (crates/semantic/src/render.rs, `class_color`).
COLORS = {
    "floor": (225, 225, 225),
    "ceiling": (200, 220, 240),
    "wall": (30, 30, 30),
    "wall_above_door": (60, 60, 170),
    "door": (170, 90, 20),
    "free_space_for_door": (110, 200, 110),
    "stairs": (235, 150, 40),
    "obstacle": (150, 40, 120),
    "column": (90, 90, 90),
    "beam": (120, 120, 60),
}
PX_PER_M = 30.0
MAX_SIDE_PX = 1000


def read_pcd_xyz(path):
    """x, y, z of a binary PCD written by semsim (fields x y z label class)."""
    data = open(path, "rb").read()
    head_end = data.index(b"DATA binary\n") + len(b"DATA binary\n")
    header = data[:head_end].decode("ascii").splitlines()
    fields = sizes = types = None
    for line in header:
        key, *rest = line.split()
        if key == "FIELDS":
            fields = rest
        elif key == "SIZE":
            sizes = [int(v) for v in rest]
        elif key == "TYPE":
            types = rest
    fmt = {("F", 4): "f4", ("U", 4): "u4", ("U", 1): "u1", ("I", 4): "i4"}
    dtype = np.dtype([(f, "<" + fmt[(t, s)]) for f, s, t in zip(fields, sizes, types)])
    n = (len(data) - head_end) // dtype.itemsize
    rec = np.frombuffer(data, dtype=dtype, count=n, offset=head_end)
    xyz = np.stack([rec["x"], rec["y"], rec["z"]], axis=1).astype(np.float64)
    return xyz[np.isfinite(xyz).all(axis=1)]


def write_png(path, img):
    h, w, _ = img.shape
    raw = b"".join(b"\x00" + img[y].tobytes() for y in range(h))

    def chunk(tag, body):
        return (
            struct.pack(">I", len(body))
            + tag
            + body
            + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF)
        )

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(png)


def height_colors(z, lo, hi):
    """Blue (low) to green to red (high)."""
    t = np.clip((z - lo) / max(hi - lo, 1e-6), 0.0, 1.0)
    r = np.clip(2 * t, 0, 1)
    g = 1 - np.abs(2 * t - 1)
    b = np.clip(2 * (1 - t), 0, 1)
    return (np.stack([r, g, b], axis=1) * 220).astype(np.uint8)


def box_corners(g):
    c, s = math.cos(math.radians(g["yaw_deg"])), math.sin(math.radians(g["yaw_deg"]))
    hx, hy = g["size_m"][0] / 2, g["size_m"][1] / 2
    cx, cy = g["center_m"][0], g["center_m"][1]
    return [(cx + c * u - s * v, cy + s * u + c * v) for u, v in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]


class Canvas:
    """A top view: map metres to pixels (north up)."""

    def __init__(self, lo, hi, px_per_m):
        self.lo, self.hi, self.k = lo, hi, px_per_m
        self.w = int(math.ceil((hi[0] - lo[0]) * px_per_m)) + 1
        self.h = int(math.ceil((hi[1] - lo[1]) * px_per_m)) + 1
        self.img = np.full((self.h, self.w, 3), 255, np.uint8)

    def px(self, x, y):
        return (x - self.lo[0]) * self.k, (self.hi[1] - y) * self.k

    def fill_polygon(self, pts, color):
        p = np.array([self.px(x, y) for x, y in pts])
        x0, y0 = np.floor(p.min(axis=0)).astype(int)
        x1, y1 = np.ceil(p.max(axis=0)).astype(int)
        x0, y0, x1, y1 = max(x0, 0), max(y0, 0), min(x1, self.w - 1), min(y1, self.h - 1)
        if x1 < x0 or y1 < y0:
            return
        xs, ys = np.meshgrid(np.arange(x0, x1 + 1) + 0.5, np.arange(y0, y1 + 1) + 0.5)
        inside = np.ones(xs.shape, bool)
        n = len(p)
        area = sum(p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1] for i in range(n))
        sign = 1.0 if area >= 0 else -1.0
        for i in range(n):
            a, b = p[i], p[(i + 1) % n]
            cross = (b[0] - a[0]) * (ys - a[1]) - (b[1] - a[1]) * (xs - a[0])
            inside &= sign * cross >= -0.5 * math.hypot(b[0] - a[0], b[1] - a[1])
        self.img[y0 : y1 + 1, x0 : x1 + 1][inside] = color

    def line(self, a, b, color, width=1):
        (x0, y0), (x1, y1) = self.px(*a), self.px(*b)
        n = int(max(abs(x1 - x0), abs(y1 - y0))) + 1
        for t in np.linspace(0, 1, n + 1):
            x, y = x0 + (x1 - x0) * t, y0 + (y1 - y0) * t
            for dx in range(-(width // 2), width // 2 + 1):
                for dy in range(-(width // 2), width // 2 + 1):
                    i, j = int(x) + dx, int(y) + dy
                    if 0 <= i < self.w and 0 <= j < self.h:
                        self.img[j, i] = color


def map_view(m, traj, lo, hi, k):
    cv = Canvas(lo, hi, k)
    ents = m["entities"]
    order = ["floor", "free_space_for_door", "stairs", "obstacle", "column", "beam", "wall", "wall_above_door", "door"]
    for cls in order:
        for e in (e for e in ents if e["class"] == cls):
            if cls == "floor":
                for part in (e.get("floor") or {}).get("parts") or [e["geometry"]]:
                    cv.fill_polygon(box_corners(part), COLORS["floor"])
            elif cls == "wall":
                for b in (e.get("wall") or {}).get("solid_boxes") or [e["geometry"]]:
                    cv.fill_polygon(box_corners(b), COLORS["wall"])
            elif cls == "door" and e.get("door"):
                d, g = e["door"], e["geometry"]
                w = g["size_m"][0]
                yaw = math.radians(g["yaw_deg"])
                along = (math.cos(yaw), math.sin(yaw))
                if d["hinge_edge"] == "end":
                    along = (-along[0], -along[1])
                side = 1.0 if d["swing"] == "left" else -1.0
                normal = (-math.sin(yaw) * side, math.cos(yaw) * side)
                h = d["hinge_m"]
                a = math.radians(d["observed_open_deg"])
                tip = (h[0] + w * (along[0] * math.cos(a) + normal[0] * math.sin(a)),
                       h[1] + w * (along[1] * math.cos(a) + normal[1] * math.sin(a)))
                cv.line((h[0], h[1]), tip, COLORS["door"], 3)
                steps = 24
                for i in range(steps):
                    t0, t1 = (i / steps) * math.pi / 2, ((i + 1) / steps) * math.pi / 2
                    p0 = (h[0] + w * (along[0] * math.cos(t0) + normal[0] * math.sin(t0)),
                          h[1] + w * (along[1] * math.cos(t0) + normal[1] * math.sin(t0)))
                    p1 = (h[0] + w * (along[0] * math.cos(t1) + normal[0] * math.sin(t1)),
                          h[1] + w * (along[1] * math.cos(t1) + normal[1] * math.sin(t1)))
                    if i % 2 == 0:
                        cv.line(p0, p1, COLORS["door"], 1)
            elif cls != "wall_above_door":
                cv.fill_polygon(box_corners(e["geometry"]), COLORS[cls])
    for a, b in zip(traj, traj[1:]):
        cv.line(a, b, (220, 30, 30), 3)
    if traj:
        cv.line(traj[0], traj[0], (20, 160, 20), 9)
    return cv.img


def scans_view(pts, floor_z, ceiling_z, lo, hi, k):
    """Top view (points below the ceiling band, the highest on top) above an oblique view."""
    keep = pts[:, 2] < ceiling_z - 0.3
    p = pts[keep]
    zlo, zhi = floor_z, ceiling_z - 0.3
    cv = Canvas(lo, hi, k)
    order = np.argsort(p[:, 2])
    q = p[order]
    cols = height_colors(q[:, 2], zlo, zhi)
    ix = ((q[:, 0] - lo[0]) * k).astype(int)
    iy = ((hi[1] - q[:, 1]) * k).astype(int)
    ok = (ix >= 0) & (ix < cv.w) & (iy >= 0) & (iy < cv.h)
    cv.img[iy[ok], ix[ok]] = cols[ok]
    # Oblique: seen from the south (-y), 40 degrees down; nearer points drawn last.
    tilt = math.radians(40.0)
    depth = p[:, 1] * math.cos(tilt) - (p[:, 2] - zlo) * math.sin(tilt)
    sx = (p[:, 0] - lo[0]) * k
    sy = -(p[:, 1] * math.sin(tilt) + (p[:, 2] - zlo) * math.cos(tilt)) * k
    sy -= sy.min()
    h2 = int(sy.max()) + 2
    ob = np.full((h2, cv.w, 3), 255, np.uint8)
    order = np.argsort(-depth)
    cols2 = height_colors(p[order, 2], zlo, zhi)
    ix2, iy2 = sx[order].astype(int), sy[order].astype(int)
    ok2 = (ix2 >= 0) & (ix2 < cv.w) & (iy2 >= 0) & (iy2 < h2)
    ob[iy2[ok2], ix2[ok2]] = cols2[ok2]
    gap = np.full((6, cv.w, 3), 255, np.uint8)
    return np.concatenate([cv.img, gap, ob], axis=0)


def main():
    run, prefix = sys.argv[1], sys.argv[2]
    m = json.load(open(f"{run}/map/semantic_map.json"))
    a = np.array(m["input_from_map"]).reshape(4, 4)
    pts = read_pcd_xyz(f"{run}/map/labels.pcd") @ a[:3, :3]  # map = R^T input
    floors = [e for e in m["entities"] if e["class"] == "floor"]
    ceils = [e for e in m["entities"] if e["class"] == "ceiling"]
    top = lambda g: g["center_m"][2] + g["size_m"][2] / 2
    bottom = lambda g: g["center_m"][2] - g["size_m"][2] / 2
    floor_z = top(floors[0]["geometry"]) if floors else float(np.quantile(pts[:, 2], 0.01))
    ceiling_z = bottom(ceils[0]["geometry"]) if ceils else float(np.quantile(pts[:, 2], 0.99))
    traj = []
    try:
        with open(f"{run}/simulation/trajectory.csv") as f:
            traj = [(float(r["x_m"]), float(r["y_m"])) for r in csv.DictReader(f)]
    except FileNotFoundError:
        pass
    # The extent: the points' robust extent (0.2 %-99.8 %) and the map's, plus a margin.
    lo = np.quantile(pts[:, :2], 0.002, axis=0) - 1.0
    hi = np.quantile(pts[:, :2], 0.998, axis=0) + 1.0
    k = min(PX_PER_M, MAX_SIDE_PX / max(hi - lo))
    write_png(f"{prefix}-scans.png", scans_view(pts, floor_z, ceiling_z, lo, hi, k))
    write_png(f"{prefix}-map.png", map_view(m, traj, lo, hi, k))


if __name__ == "__main__":
    main()
