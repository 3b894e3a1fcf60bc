"""Reading speed and peak memory: semsim against the reference Python readers, same files, same run.

Writes a LAZ file (laspy + lazrs) and an E57 file (pye57) of N points (default 10 M), then reads
each with
  * the reference: laspy.read (coordinates scaled to f64 arrays) / pye57 read_scan_raw,
  * semsim: `semsim info FILE` (reads every point into memory, then describes the cloud),
each in its own process under /usr/bin/time (wall seconds, peak resident memory), best of R runs.
The points' own size is what semsim keeps per point: xyz as 3 x f32, intensity f32 and (LAS)
the classification byte. Results: bench/results/read_formats.json and .md.
"""
import argparse, json, os, subprocess, sys, time

import numpy as np


def timed(cmd):
    out = subprocess.run(["/usr/bin/time", "-f", "%e %M"] + cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{out.stdout}\n{out.stderr}")
    wall_s, kib = out.stderr.strip().splitlines()[-1].split()
    return float(wall_s), int(kib) * 1024


def best_interleaved(a, b, runs):
    """Best wall time and largest peak of two commands run alternately (a, b, a, b, ...), so
    that a change in the machine's load during the run affects both alike."""
    ra, rb = [], []
    for _ in range(runs):
        ra.append(timed(a))
        rb.append(timed(b))
    pick = lambda rs: (min(r[0] for r in rs), max(r[1] for r in rs))
    return pick(ra), pick(rb)


def make_points(n, seed=7):
    rng = np.random.default_rng(seed)
    # A georeferenced-looking block: 200 m x 150 m x 20 m around UTM-like coordinates.
    x = 500000.0 + rng.uniform(0, 200, n)
    y = 5400000.0 + rng.uniform(0, 150, n)
    z = 100.0 + rng.uniform(0, 20, n)
    intensity = rng.integers(0, 65535, n, dtype=np.uint16)
    classification = rng.integers(0, 10, n, dtype=np.uint8)
    return x, y, z, intensity, classification


def write_laz(path, n):
    import laspy
    x, y, z, intensity, classification = make_points(n)
    header = laspy.LasHeader(point_format=6, version="1.4")
    header.scales = [0.001, 0.001, 0.001]
    header.offsets = [500000.0, 5400000.0, 0.0]
    las = laspy.LasData(header)
    las.x, las.y, las.z = x, y, z
    las.intensity = intensity
    las.classification = classification
    las.write(path)


def write_e57(path, n):
    import pye57
    x, y, z, intensity, _ = make_points(n)
    e57 = pye57.E57(path, mode="w")
    e57.write_scan_raw({
        "cartesianX": x - 500000.0, "cartesianY": y - 5400000.0, "cartesianZ": z,
        "intensity": intensity.astype(np.float64) / 65535.0,
    }, name="bench")
    e57.close()


READ_LAZ = """
import laspy, sys
las = laspy.read(sys.argv[1])
x, y, z = las.x.array, las.y.array, las.z.array  # scaled to f64 by laspy
sx, sy, sz = las.x, las.y, las.z
print(len(las.points), float(sx[0]), int(las.intensity[0]))
"""

READ_E57 = """
import pye57, sys
e57 = pye57.E57(sys.argv[1])
data = e57.read_scan_raw(0)
print(len(data["cartesianX"]), float(data["cartesianX"][0]))
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=10_000_000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--semsim", default="target/release/semsim")
    ap.add_argument("--work", default="bench/work/read_formats")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    py = sys.executable
    rows = []
    for fmt, writer, reader, per_point in [
        ("laz", write_laz, READ_LAZ, 12 + 4 + 1),
        ("e57", write_e57, READ_E57, 12 + 4),
    ]:
        path = os.path.join(a.work, f"bench_{a.points}.{fmt}")
        if not os.path.exists(path):
            t0 = time.time()
            writer(path + ".tmp." + fmt, a.points)
            os.replace(path + ".tmp." + fmt, path)
            print(f"wrote {path} in {time.time() - t0:.1f} s", flush=True)
        (ref_s, ref_rss), (ours_s, ours_rss) = best_interleaved(
            [py, "-c", reader, path], [a.semsim, "info", path], a.runs)
        own = a.points * per_point
        row = {
            "format": fmt, "points": a.points, "file_bytes": os.path.getsize(path),
            "reference": "laspy 2.7 + lazrs" if fmt == "laz" else "pye57 0.4",
            "reference_s": ref_s, "reference_peak_bytes": ref_rss,
            "semsim_s": ours_s, "semsim_peak_bytes": ours_rss,
            "speed_ratio_reference_over_semsim": ref_s / ours_s,
            "points_own_bytes": own, "semsim_peak_over_points": ours_rss / own,
        }
        rows.append(row)
        print(json.dumps(row), flush=True)
    os.makedirs("bench/results", exist_ok=True)
    with open("bench/results/read_formats.json", "w") as f:
        json.dump(rows, f, indent=2)
    with open("bench/results/read_formats.md", "w") as f:
        f.write("# Reading speed and peak memory (`bash bench/read_formats.sh`)\n\n")
        f.write(f"{a.points:,} points, best of {a.runs} runs each, the two readers alternating, each in its own process.\n\n")
        f.write("| format | reference | reference s | semsim s | ratio (ref/semsim) | semsim peak MB | peak / points' size |\n|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['format']} | {r['reference']} | {r['reference_s']:.2f} | {r['semsim_s']:.2f} | {r['speed_ratio_reference_over_semsim']:.2f} | {r['semsim_peak_bytes']/1e6:.0f} | {r['semsim_peak_over_points']:.2f} |\n")


if __name__ == "__main__":
    main()
