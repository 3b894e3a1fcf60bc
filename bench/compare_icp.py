#!/usr/bin/env python3
"""ICP comparison: semsim vs Open3D 0.20 vs small_gicp 1.x on the same pairs, pinned to 2 cores.

Run from the repository root:  bash bench/compare_icp.sh   (sets up bench/.venv, builds semsim, runs this)

Pairs:
  (a) two full-resolution 541 x 301 virtual-laser scans of the default building, 1 m and 5 degrees apart, 1 cm noise
  (b) the same, voxel-downsampled to 5 cm
  (c) small_gicp's real outdoor pair (../shared/data/real/small-gicp) with its reference transform
Synthetic pairs start 0.3 m / 5 degrees off the truth; the real pair starts from identity.
Writes bench/results/icp_compare.csv and icp_compare.md.
"""
import csv, json, os, subprocess, sys, time
from pathlib import Path

import numpy as np
import open3d as o3d
import small_gicp

ROOT = Path(__file__).resolve().parent.parent
SEMSIM = ROOT / "target" / "release" / "semsim"
WORK = ROOT / "bench" / "work"
RESULTS = ROOT / "bench" / "results"
REAL = ROOT.parent / "shared" / "data" / "real"
GATE_M = 0.5
THREADS = 2


def sh(*args):
    out = subprocess.run([str(a) for a in args], check=True, capture_output=True, text=True)
    return out.stdout


def read_poses(path):
    poses = {}
    for line in Path(path).read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            f = line.split()
            poses[f[0]] = np.array([float(v) for v in f[1:]]).reshape(4, 4)
    return poses


def rot(axis, deg):
    a = np.radians(deg)
    c, s = np.cos(a), np.sin(a)
    x, y, z = np.array(axis, float) / np.linalg.norm(axis)
    R = np.array([[c + x*x*(1-c), x*y*(1-c) - z*s, x*z*(1-c) + y*s],
                  [y*x*(1-c) + z*s, c + y*y*(1-c), y*z*(1-c) - x*s],
                  [z*x*(1-c) - y*s, z*y*(1-c) + x*s, c + z*z*(1-c)]])
    return R


def perturbed(T, dist_m=0.3, deg=5.0):
    P = np.eye(4)
    P[:3, :3] = rot([0.3, -0.2, 1.0], deg)
    d = np.array([1.0, 0.6, 0.2])
    P[:3, 3] = dist_m * d / np.linalg.norm(d)
    return T @ P


def errors(T, truth):
    D = np.linalg.inv(truth) @ T
    ang = np.degrees(np.arccos(np.clip((np.trace(D[:3, :3]) - 1) / 2, -1, 1)))
    return float(np.linalg.norm(D[:3, 3])), float(ang)


def load_xyz(path):
    pts = np.asarray(o3d.io.read_point_cloud(str(path)).points, dtype=np.float64)
    return pts[np.isfinite(pts).all(axis=1)]


def make_pairs():
    WORK.mkdir(parents=True, exist_ok=True)
    scans = WORK / "scans"
    sh(SEMSIM, "scan", "--building", ROOT / "crates/scanner/data/default_building.toml",
       "--pose", "6.5,0.0,0.0", "--pose", "7.3,0.6,5.0", "--out", scans)
    poses = read_poses(scans / "poses.txt")
    truth = np.linalg.inv(poses["scan000"]) @ poses["scan001"]  # target_from_source: source = scan001
    pairs = []
    for tag, voxel in (("a_full_162841", None), ("b_voxel_5cm", 0.05)):
        files = []
        for name in ("scan001", "scan000"):
            out = WORK / f"{name}_{tag}.ply"
            args = [SEMSIM, "convert", scans / f"{name}.pcd", out]
            if voxel:
                args += ["--voxel", str(voxel)]
            sh(*args)
            files.append(out)
        pairs.append((tag, files[0], files[1], truth, perturbed(truth)))
    if REAL.is_dir():
        t = np.loadtxt(REAL / "small-gicp" / "T_target_source.txt")
        pairs.append(("c_small_gicp_real", REAL / "small-gicp/source.ply", REAL / "small-gicp/target.ply", t, np.eye(4)))
    return pairs


def timed(fn, repeats=3):
    best = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        dt = time.perf_counter() - t0
        if best is None or dt < best[0]:
            best = (dt, out)
    return best


def open3d_runs(src, tgt, guess, truth):
    s, t = o3d.geometry.PointCloud(), o3d.geometry.PointCloud()
    s.points = o3d.utility.Vector3dVector(src)
    t.points = o3d.utility.Vector3dVector(tgt)
    rows = []
    reg = o3d.pipelines.registration
    for method, est in (("point-to-point", reg.TransformationEstimationPointToPoint()),
                        ("point-to-plane", reg.TransformationEstimationPointToPlane())):
        def run(max_it, fixed):
            crit = reg.ICPConvergenceCriteria(relative_fitness=0 if fixed else 1e-6,
                                              relative_rmse=0 if fixed else 1e-6, max_iteration=max_it)
            if method == "point-to-plane":
                t.estimate_normals(o3d.geometry.KDTreeSearchParamHybrid(radius=0.15, max_nn=30))
            return reg.registration_icp(s, t, GATE_M, guess, est, crit)
        dt10, _ = timed(lambda: run(10, True))
        dt, res = timed(lambda: run(100, False))
        e = errors(np.asarray(res.transformation), truth)
        rows.append(dict(library="Open3D 0.20", method=method, ms_per_iteration=1e3 * dt10 / 10,
                         total_ms=1e3 * dt, iterations="", error_m=e[0], error_deg=e[1]))
    return rows


def small_gicp_runs(src, tgt, guess, truth):
    rows = []
    for method, kind in (("point-to-point", "ICP"), ("point-to-plane", "PLANE_ICP"), ("GICP", "GICP")):
        def run(max_it):
            s = small_gicp.PointCloud(src)
            t = small_gicp.PointCloud(tgt)
            if kind != "ICP":
                small_gicp.estimate_normals_covariances(s, num_neighbors=20, num_threads=THREADS)
                small_gicp.estimate_normals_covariances(t, num_neighbors=20, num_threads=THREADS)
            tree = small_gicp.KdTree(t, num_threads=THREADS)
            return small_gicp.align(t, s, tree, init_T_target_source=guess, registration_type=kind,
                                    max_correspondence_distance=GATE_M, num_threads=THREADS, max_iterations=max_it)
        dt10, r10 = timed(lambda: run(10))
        dt, res = timed(lambda: run(100))
        e = errors(res.T_target_source, truth)
        rows.append(dict(library="small_gicp", method=method, ms_per_iteration=1e3 * dt10 / max(r10.iterations, 1),
                         total_ms=1e3 * dt, iterations=res.iterations, error_m=e[0], error_deg=e[1]))
    return rows


def semsim_runs(src_path, tgt_path, guess, truth):
    rows = []
    gfile = WORK / "guess.txt"
    np.savetxt(gfile, guess)
    for method in ("p2p", "p2plane", "gicp"):
        def run():
            out = subprocess.run([str(SEMSIM), "register", str(src_path), str(tgt_path), "--guess", str(gfile),
                                  "--method", method, "--json"], capture_output=True, text=True)
            if out.returncode != 0:
                return None, out.stderr.strip().splitlines()[-1] if out.stderr.strip() else "failed"
            return json.loads(out.stdout), ""
        best = None
        for _ in range(3):
            j, err = run()
            if j and (best is None or j["total_ms"] < best["total_ms"]):
                best = j
        if best is None:
            rows.append(dict(library="semsim", method=method, ms_per_iteration="", total_ms="", iterations="",
                             error_m="", error_deg="", note=err))
            continue
        T = np.array(best["transform"]).reshape(4, 4)
        e = errors(T, truth)
        rows.append(dict(library="semsim", method=method, ms_per_iteration=best["ms_per_iteration"],
                         total_ms=best["total_ms"], iterations=best["iterations"], error_m=e[0], error_deg=e[1]))
    return rows


def main():
    pairs = make_pairs()
    table = []
    for tag, sp, tp, truth, guess in pairs:
        src, tgt = load_xyz(sp), load_xyz(tp)
        start = errors(guess, truth)
        print(f"== {tag}: {len(src)} -> {len(tgt)} points, start {start[0]:.3f} m / {start[1]:.2f} deg", flush=True)
        for rows in (semsim_runs(sp, tp, guess, truth), open3d_runs(src, tgt, guess, truth),
                     small_gicp_runs(src, tgt, guess, truth)):
            for r in rows:
                r.update(pair=tag, source_points=len(src), target_points=len(tgt))
                table.append(r)
                print("  ", {k: (round(v, 4) if isinstance(v, float) else v) for k, v in r.items()}, flush=True)
    RESULTS.mkdir(parents=True, exist_ok=True)
    keys = ["pair", "library", "method", "ms_per_iteration", "total_ms", "iterations", "error_m", "error_deg",
            "source_points", "target_points", "note"]
    with open(RESULTS / "icp_compare.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(table)
    fmt = lambda v, p: f"{v:.{p}f}" if isinstance(v, float) else str(v)
    with open(RESULTS / "icp_compare.md", "w") as f:
        f.write("| pair | library | method | ms/iteration | total ms | iterations | error m | error deg |\n")
        f.write("|---|---|---|---|---|---|---|---|\n")
        for r in table:
            f.write(f"| {r['pair']} | {r['library']} | {r['method']} | {fmt(r['ms_per_iteration'], 1)} | "
                    f"{fmt(r['total_ms'], 1)} | {r['iterations']} | {fmt(r['error_m'], 4)} | {fmt(r['error_deg'], 3)} |\n")
    print((RESULTS / "icp_compare.md").read_text())


if __name__ == "__main__":
    sys.exit(main())
