"""Writes georeferenced LAS/LAZ test files with laspy (LAZ through lazrs) and dumps what laspy
reads back.

    make_las.py OUT_DIR

Files (deterministic pseudo-random points, UTM-like coordinates around x 500123 m,
y 5400456 m, z 100 m, in a 20 m x 20 m x 5 m box; scale 0.001 m, offsets 500000, 5400000, 0):
  geo_12.las   LAS 1.2, point format 1, 600 points, classes 1-9 and 12 (legacy overlap)
  geo_14.laz   LAS 1.4, point format 6, LAZ, 700 points, classes 0-255 but 12
  geo_13.las   LAS 1.3, point format 3, 50 points, a 300 m wide box (f32 precision test)
Beside each, NAME.json: what laspy reads back (x y z in metres as f64, intensity,
classification, and the header's version, point format, count, scales and offsets).
"""
import json
import sys
from pathlib import Path

import laspy
import numpy as np

CENTRE = np.array([500123.4, 5400456.7, 102.3])


def write(path, version, point_format, n, half_extent, classes, seed):
    rng = np.random.default_rng(seed)
    header = laspy.LasHeader(point_format=point_format, version=version)
    header.scales = np.array([0.001, 0.001, 0.001])
    header.offsets = np.array([500000.0, 5400000.0, 0.0])
    las = laspy.LasData(header)
    half_extent = np.asarray(half_extent, dtype=np.float64)
    xyz = CENTRE + rng.uniform(-half_extent, half_extent, size=(n, 3))
    las.x, las.y, las.z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    las.intensity = rng.integers(0, 65536, size=n, dtype=np.uint16)
    las.classification = rng.choice(classes, size=n).astype(np.uint8)
    las.write(str(path))


def dump(path):
    """What laspy reads back from `path`, as a JSON-ready dict."""
    las = laspy.read(str(path))
    h = las.header
    return {
        "version": f"{h.version.major}.{h.version.minor}",
        "point_format": int(h.point_format.id),
        "count": int(h.point_count),
        "scales": [float(v) for v in h.scales],
        "offsets": [float(v) for v in h.offsets],
        "x": [float(v) for v in np.asarray(las.x, dtype=np.float64)],
        "y": [float(v) for v in np.asarray(las.y, dtype=np.float64)],
        "z": [float(v) for v in np.asarray(las.z, dtype=np.float64)],
        "intensity": [int(v) for v in las.intensity],
        "classification": [int(v) for v in las.classification],
    }


def main():
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    legacy = list(range(1, 10)) + [12]
    extended = [c for c in range(256) if c != 12]
    write(out / "geo_12.las", "1.2", 1, 600, [10, 10, 2.5], legacy, 12)
    write(out / "geo_14.laz", "1.4", 6, 700, [10, 10, 2.5], extended, 14)
    write(out / "geo_13.las", "1.3", 3, 50, [150, 150, 10], legacy, 13)
    for name in ["geo_12.las", "geo_14.laz", "geo_13.las"]:
        (out / (name + ".json")).write_text(json.dumps(dump(out / name)))


if __name__ == "__main__":
    main()
