"""semsim's rapier simulation against MuJoCo on the same exported world, robot and commands.

Input: the JSON that `cargo run --release -p interop --example side_by_side -- DIR` prints
(semsim's run: its speed, the robot's final pose and the doors' angles, and the MJCF it exported
of the same world and robot). This script loads that MJCF in MuJoCo (the oracles' venv),
drives the same command (every wheel motor at linear speed / wheel radius from `from_s` to
`to_s`, then braking at 0) for the same simulated time at the same 1/60 s step, best of R runs,
and writes bench/results/mujoco_side_by_side.json and .md: simulated seconds per wall second
of each engine, the distance between the robots' final positions, their headings, and each
door's final angle in both.

semsim's time includes what a semsim run always does besides physics (event detectors, the
judge, the trajectory); MuJoCo's is `mj_step` alone.
"""
import argparse
import json
import math
import os
import sys
import time

import mujoco
import numpy as np


def run_mujoco(path, command, seconds):
    model = mujoco.MjModel.from_xml_path(path)
    data = mujoco.MjData(model)
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "start")
    if key >= 0:
        mujoco.mj_resetDataKeyframe(model, data, key)
    motors = []
    for a in range(model.nu):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, a) or ""
        if name.endswith("_motor"):
            joint = model.actuator_trnid[a, 0]
            body = model.jnt_bodyid[joint]
            geom = model.body_geomadr[body]
            motors.append((a, float(model.geom_size[geom, 0])))  # the tyre's radius
    steps = int(round(seconds / model.opt.timestep))
    t0 = time.perf_counter()
    for _ in range(steps):
        t = data.time
        v = command["linear_mps"] if command["from_s"] <= t + 1e-9 < command["to_s"] else 0.0
        for a, radius in motors:
            data.ctrl[a] = v / radius
        mujoco.mj_step(model, data)
    wall = time.perf_counter() - t0
    mujoco.mj_forward(model, data)
    chassis = next(
        b
        for b in range(model.nbody)
        if (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) or "").endswith("_chassis")
    )
    m = np.asarray(data.xmat[chassis]).reshape(3, 3)
    doors = {}
    for j in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or ""
        if name.startswith("door_") and name.endswith("_hinge"):
            doors[name[: -len("_hinge")]] = math.degrees(float(data.qpos[model.jnt_qposadr[j]]))
    warnings = {
        mujoco.mjtWarning(i).name: int(data.warning[i].number)
        for i in range(len(data.warning))
        if data.warning[i].number > 0
    }
    return {
        "steps": steps,
        "sim_s": float(data.time),
        "wall_s": wall,
        "final": {
            "x_m": float(data.xpos[chassis][0]),
            "y_m": float(data.xpos[chassis][1]),
            "z_m": float(data.xpos[chassis][2]),
            "yaw_deg": math.degrees(math.atan2(m[1, 0], m[0, 0])),
        },
        "doors_deg": doors,
        "warnings": warnings,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("semsim_json", help="the side_by_side example's output")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--out", default="bench/results/mujoco_side_by_side")
    args = ap.parse_args()
    with open(args.semsim_json) as f:
        semsim = json.load(f)
    runs = [run_mujoco(semsim["mjcf"], semsim["command"], semsim["seconds"]) for _ in range(args.runs)]
    runs.sort(key=lambda r: r["wall_s"])
    best = runs[0]
    mj_wall = [r["wall_s"] for r in runs]
    mj = dict(best)
    mj["wall_s"] = mj_wall
    mj["wall_s_best"] = best["wall_s"]
    mj["sim_s_per_wall_s"] = best["sim_s"] / best["wall_s"]
    ours = semsim["semsim"]
    ours_best = min(ours["wall_s"])
    a, b = ours["final"], mj["final"]
    distance = math.hypot(a["x_m"] - b["x_m"], a["y_m"] - b["y_m"])
    yaw_diff = (a["yaw_deg"] - b["yaw_deg"] + 180.0) % 360.0 - 180.0
    doors = {
        name: {"semsim": ours["doors_deg"].get(name), "mujoco": angle,
               "difference": None if ours["doors_deg"].get(name) is None else ours["doors_deg"][name] - angle}
        for name, angle in mj["doors_deg"].items()
    }
    start = semsim["start"]
    travelled = {
        "semsim": math.hypot(a["x_m"] - start["x_m"], a["y_m"] - start["y_m"]),
        "mujoco": math.hypot(b["x_m"] - start["x_m"], b["y_m"] - start["y_m"]),
    }
    result = {
        "scenario": {
            "world": "default building",
            "robot": semsim["robot"],
            "start": start,
            "command": semsim["command"],
            "seconds": semsim["seconds"],
            "dt_s": semsim["dt_s"],
        },
        "machine": {"cpus": os.cpu_count(), "mujoco": mujoco.__version__},
        "semsim": {**ours, "wall_s_best": ours_best, "sim_s_per_wall_s_best": ours["sim_s"] / ours_best},
        "mujoco": mj,
        "agreement": {
            "final_distance_m": distance,
            "final_yaw_difference_deg": yaw_diff,
            "travelled_m": travelled,
            "doors_deg": doors,
        },
    }
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out + ".json", "w") as f:
        json.dump(result, f, indent=1)
    lines = [
        "# semsim (rapier) and MuJoCo side by side",
        "",
        f"Default building, {semsim['robot']} from ({start['x_m']}, {start['y_m']}) heading "
        f"{start['yaw_deg']} deg, {semsim['command']['linear_mps']} m/s forward for "
        f"{semsim['command']['to_s']} s then braking, {semsim['seconds']} s simulated at "
        f"{semsim['dt_s']:.5f} s a step (`bash bench/mujoco_side_by_side.sh`).",
        "",
        "| engine | simulated s per wall s (best) | final x, y (m) | heading (deg) | travelled (m) |",
        "|---|---|---|---|---|",
        f"| semsim (rapier 0.36, with detectors and judge) | {ours['sim_s'] / ours_best:.0f} | "
        f"{a['x_m']:.3f}, {a['y_m']:.3f} | {a['yaw_deg']:.1f} | {travelled['semsim']:.3f} |",
        f"| MuJoCo {mujoco.__version__} (mj_step) | {mj['sim_s_per_wall_s']:.0f} | "
        f"{b['x_m']:.3f}, {b['y_m']:.3f} | {b['yaw_deg']:.1f} | {travelled['mujoco']:.3f} |",
        "",
        f"Final positions {distance:.3f} m apart, headings {yaw_diff:.1f} deg apart.",
        "",
        "| door | semsim (deg) | MuJoCo (deg) |",
        "|---|---|---|",
    ]
    for name, d in doors.items():
        s = "-" if d["semsim"] is None else f"{d['semsim']:.1f}"
        lines.append(f"| {name} | {s} | {d['mujoco']:.1f} |")
    with open(args.out + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print(json.dumps(result["agreement"], indent=1))
    print(f"semsim: {ours['sim_s'] / ours_best:.0f} sim s/wall s; MuJoCo: {mj['sim_s_per_wall_s']:.0f} sim s/wall s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
