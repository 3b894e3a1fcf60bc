"""Writes E57 test files with libE57Format (through pye57) and dumps what pye57 reads back.

    make_e57.py OUT_DIR

OUT_DIR/scans.e57 holds three scans of deterministic pseudo-random points:
  0 "scan-a":    400 unorganised cartesian points (float64), float intensity, a pose
  1 "scan-b":    an organised 6 x 9 grid (rowIndex/columnIndex) of which 52 cells are stored,
                 7 of them with cartesianInvalidState 2, integer intensity, a pose
  2 "spherical": 120 spherical points (float64), sphericalInvalidState 0, 1 (direction
                 only) and 2 (invalid), no intensity, no pose
OUT_DIR/scans.json is what pye57 reads back: per scan the name, pose (rotation w x y z,
translation), the raw fields, and cartesian x y z (pye57's own conversion for the spherical
scan), each point's validity (invalid state 0) and intensity, row and column where present.

Also: read_reference.py reads any E57/LAS/LAZ file back the same way.
"""
import json
import sys
from pathlib import Path

import numpy as np
import pye57
from pye57 import libe57
from pye57.utils import convert_spherical_to_cartesian


def float_node(imf, values):
    low, high = float(np.min(values)), float(np.max(values))
    return libe57.FloatNode(imf, low, libe57.FloatPrecision.E57_DOUBLE, low, high)


def add_scan(e57, name, fields, pose=None):
    """Appends a scan node whose prototype holds `fields` (name -> (numpy array, node))."""
    imf = e57.image_file
    scan = libe57.StructureNode(imf)
    scan.set("guid", libe57.StringNode(imf, "{semsim-oracle-%s}" % name))
    scan.set("name", libe57.StringNode(imf, name))
    if pose is not None:
        (w, x, y, z), (tx, ty, tz) = pose
        pose_node = libe57.StructureNode(imf)
        rotation = libe57.StructureNode(imf)
        for key, value in zip("wxyz", (w, x, y, z)):
            rotation.set(key, libe57.FloatNode(imf, float(value)))
        translation = libe57.StructureNode(imf)
        for key, value in zip("xyz", (tx, ty, tz)):
            translation.set(key, libe57.FloatNode(imf, float(value)))
        pose_node.set("rotation", rotation)
        pose_node.set("translation", translation)
        scan.set("pose", pose_node)
    prototype = libe57.StructureNode(imf)
    for field, (_, node) in fields.items():
        prototype.set(field, node)
    codecs = libe57.VectorNode(imf, True)
    points = libe57.CompressedVectorNode(imf, prototype, codecs)
    scan.set("points", points)
    e57.data3d.append(scan)
    buffers = libe57.VectorSourceDestBuffer()
    n = None
    for field, (array, _) in fields.items():
        array = np.ascontiguousarray(array)
        fields[field] = (array, None)
        n = len(array)
        buffers.append(libe57.SourceDestBuffer(imf, field, array, n, True, True))
    writer = points.writer(buffers)
    writer.write(n)
    writer.close()


def unit_quaternion(rng):
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    if q[0] < 0:
        q = -q
    return q


def write(path):
    rng = np.random.default_rng(57)
    e57 = pye57.E57(str(path), mode="w")
    imf = e57.image_file

    n = 400
    xyz = rng.uniform([-8, -6, -1], [8, 6, 3], size=(n, 3))
    intensity = rng.uniform(0, 4095, size=n)
    add_scan(e57, "scan-a", {
        "cartesianX": (xyz[:, 0], float_node(imf, xyz[:, 0])),
        "cartesianY": (xyz[:, 1], float_node(imf, xyz[:, 1])),
        "cartesianZ": (xyz[:, 2], float_node(imf, xyz[:, 2])),
        "intensity": (intensity, float_node(imf, intensity)),
    }, pose=(unit_quaternion(rng), (12.5, -3.25, 1.5)))

    rows, cols = 6, 9
    cells = [(r, c) for r in range(rows) for c in range(cols)]
    omitted = {5, 31}
    cells = [cell for i, cell in enumerate(cells) if i not in omitted]
    m = len(cells)
    # Integer fields go through libE57Format buffers as int8 / int16 / uint16 (int64 arrays do not).
    row = np.array([r for r, _ in cells], dtype=np.uint16)
    col = np.array([c for _, c in cells], dtype=np.uint16)
    xyz = rng.uniform(-20, 20, size=(m, 3))
    state = np.zeros(m, dtype=np.int8)
    state[rng.choice(m, size=7, replace=False)] = 2
    xyz[state == 2] = 0.0
    counts = rng.integers(0, 2048, size=m).astype(np.int16)
    yaw = np.radians(30.0)
    add_scan(e57, "scan-b", {
        "cartesianX": (xyz[:, 0], float_node(imf, xyz[:, 0])),
        "cartesianY": (xyz[:, 1], float_node(imf, xyz[:, 1])),
        "cartesianZ": (xyz[:, 2], float_node(imf, xyz[:, 2])),
        "cartesianInvalidState": (state, libe57.IntegerNode(imf, 0, 0, 2)),
        "rowIndex": (row, libe57.IntegerNode(imf, 0, 0, rows - 1)),
        "columnIndex": (col, libe57.IntegerNode(imf, 0, 0, cols - 1)),
        "intensity": (counts, libe57.IntegerNode(imf, 0, 0, 2047)),
    }, pose=((np.cos(yaw / 2), 0.0, 0.0, np.sin(yaw / 2)), (-4.0, 7.0, 0.25)))

    k = 120
    rng_ = rng.uniform(0.5, 30.0, size=k)
    azimuth = rng.uniform(-np.pi, np.pi, size=k)
    elevation = rng.uniform(-np.pi / 2, np.pi / 2, size=k)
    sstate = np.zeros(k, dtype=np.int8)
    picks = rng.choice(k, size=8, replace=False)
    sstate[picks[:5]] = 2
    sstate[picks[5:]] = 1
    add_scan(e57, "spherical", {
        "sphericalRange": (rng_, float_node(imf, rng_)),
        "sphericalAzimuth": (azimuth, float_node(imf, azimuth)),
        "sphericalElevation": (elevation, float_node(imf, elevation)),
        "sphericalInvalidState": (sstate, libe57.IntegerNode(imf, 0, 0, 2)),
    })
    e57.close()


def as_list(values):
    return [None if not np.isfinite(v) else float(v) for v in np.asarray(values, dtype=np.float64)]


def dump(path):
    """What pye57 reads back from `path`, as a JSON-ready dict."""
    e57 = pye57.E57(str(path))
    scans = []
    for i in range(e57.scan_count):
        header = e57.get_header(i)
        node = header.node
        raw = e57.read_scan_raw(i)
        if "cartesianX" in raw:
            x, y, z = raw["cartesianX"], raw["cartesianY"], raw["cartesianZ"]
            state = raw.get("cartesianInvalidState", np.zeros(len(x)))
        else:
            rae = np.array([raw["sphericalRange"], raw["sphericalAzimuth"],
                            raw["sphericalElevation"]]).T
            xyz = convert_spherical_to_cartesian(rae)
            x, y, z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
            state = raw.get("sphericalInvalidState", np.zeros(len(x)))
        if node.isDefined("pose"):
            rot = node["pose"]["rotation"]
            tr = node["pose"]["translation"]
            rotation = [rot[k].value() for k in "wxyz"]
            translation = [tr[k].value() for k in "xyz"]
        else:
            rotation, translation = [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
        scans.append({
            "name": node["name"].value() if node.isDefined("name") else None,
            "rotation_wxyz": rotation,
            "translation": translation,
            "x": as_list(x), "y": as_list(y), "z": as_list(z),
            "valid": [bool(s == 0) for s in state],
            "intensity": as_list(raw["intensity"]) if "intensity" in raw else None,
            "row": [int(v) for v in raw["rowIndex"]] if "rowIndex" in raw else None,
            "col": [int(v) for v in raw["columnIndex"]] if "columnIndex" in raw else None,
        })
    e57.close()
    return {"scans": scans}


def main():
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    write(out / "scans.e57")
    (out / "scans.json").write_text(json.dumps(dump(out / "scans.e57")))


if __name__ == "__main__":
    main()
