#!/usr/bin/env python3
"""Loads an MJCF file with MuJoCo, steps it and reports what happened, as JSON on stdout.

Used by semsim's export tests (crates/interop/tests/export_mjcf.rs) as the reference reader of
MJCF. Usage:

    check_mjcf.py FILE.xml [--seconds S] [--push-doors N] [--wheel-speed RADPS]

* Loading: MuJoCo's compiler errors fail the run (exit 1, message on stderr); warnings that
  MuJoCo raises through Python's `warnings` or prints while loading and stepping are reported.
* The model starts from its keyframe `start` when it has one (the robot's arm servos hold their
  angles there), else from qpos0.
* --push-doors N: for the first half second, a force of N newtons on each door leaf's centre of
  mass, perpendicular to the leaf, in the direction that turns its hinge joint away from the
  nearer limit (towards the joint's positive direction unless the door is nearer its upper
  limit). Each door's report gives the joint angle before and after, its range, the push's
  sense and the leaf's rotation about world z seen from above (counter-clockwise positive).
* --wheel-speed W: every actuator named *_motor (the wheels' velocity actuators) gets ctrl = W
  (rad/s) for the whole run. The robot's report gives the chassis' start and end positions,
  its heading at the start, the distance it moved along that heading and its largest tilt.
* Stepping: S simulated seconds (default 2). `warnings` counts MuJoCo's runtime warnings
  (mjData.warning: inertia, contact/constraint buffer full, bad qpos/qvel/qacc/ctrl);
  `contacts` lists the pairs of geoms (by name) in contact after the last step.
"""

import argparse
import contextlib
import io
import json
import math
import os
import sys
import tempfile
import warnings

import mujoco
import numpy as np


def yaw_of(xmat):
    """The rotation about world z of a body's frame (its x axis seen from above), degrees."""
    m = np.asarray(xmat).reshape(3, 3)
    return math.degrees(math.atan2(m[1, 0], m[0, 0]))


def tilt_of(xmat):
    """The angle between a body's z axis and world z, degrees."""
    m = np.asarray(xmat).reshape(3, 3)
    return math.degrees(math.acos(max(-1.0, min(1.0, m[2, 2]))))


@contextlib.contextmanager
def captured_stderr():
    """Captures what the C library prints on file descriptor 2."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as tmp:
        os.dup2(tmp.fileno(), 2)
        box = {}
        try:
            yield box
        finally:
            sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            tmp.seek(0)
            box["text"] = tmp.read().decode("utf-8", "replace")


def doors_of(model):
    """The door hinge joints: (joint id, leaf body id), by the exporter's names."""
    out = []
    for j in range(model.njnt):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) or ""
        if name.startswith("door_") and name.endswith("_hinge"):
            out.append((j, int(model.jnt_bodyid[j]), name[: -len("_hinge")]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file")
    ap.add_argument("--seconds", type=float, default=2.0)
    ap.add_argument("--push-doors", type=float, default=0.0)
    ap.add_argument("--wheel-speed", type=float, default=None)
    args = ap.parse_args()

    caught = []
    with captured_stderr() as err, warnings.catch_warnings(record=True) as py_warnings:
        warnings.simplefilter("always")
        try:
            model = mujoco.MjModel.from_xml_path(args.file)
        except Exception as e:  # noqa: BLE001 - MuJoCo raises ValueError; report any failure
            print(f"check_mjcf: {args.file}: {e}", file=sys.stderr)
            return 1
        data = mujoco.MjData(model)
        key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "start")
        if key >= 0:
            mujoco.mj_resetDataKeyframe(model, data, key)
        mujoco.mj_forward(model, data)

        doors = doors_of(model)
        report_doors = []
        pushes = []
        for j, body, name in doors:
            q0 = float(data.qpos[model.jnt_qposadr[j]])
            lo, hi = (float(v) for v in model.jnt_range[j])
            sense = 1.0 if (hi - q0) >= (q0 - lo) else -1.0
            pushes.append((j, body, sense))
            report_doors.append(
                {
                    "name": name,
                    "angle0_deg": math.degrees(q0),
                    "range_deg": [math.degrees(lo), math.degrees(hi)],
                    "push_sense": sense,
                    "yaw0_deg": yaw_of(data.xmat[body]),
                    "max_angle_deg": -1e9,
                    "min_angle_deg": 1e9,
                }
            )

        motors = [
            a
            for a in range(model.nu)
            if (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, a) or "").endswith("_motor")
        ]
        chassis = None
        for b in range(model.nbody):
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) or ""
            if name.startswith("robot_") and name.endswith("_chassis"):
                chassis = b
        robot = None
        if chassis is not None:
            robot = {
                "start": [float(v) for v in data.xpos[chassis]],
                "heading_deg": yaw_of(data.xmat[chassis]),
                "max_tilt_deg": 0.0,
            }

        steps = int(round(args.seconds / model.opt.timestep))
        push_steps = int(round(0.5 / model.opt.timestep))
        for step in range(steps):
            data.xfrc_applied[:] = 0.0
            if args.push_doors > 0.0 and step < push_steps:
                for j, body, sense in pushes:
                    axis = np.asarray(data.xaxis[j])
                    arm = np.asarray(data.xipos[body]) - np.asarray(data.xanchor[j])
                    direction = np.cross(axis, arm)
                    norm = np.linalg.norm(direction)
                    if norm > 0:
                        data.xfrc_applied[body, :3] = sense * args.push_doors * direction / norm
            if args.wheel_speed is not None:
                for a in motors:
                    data.ctrl[a] = args.wheel_speed
            mujoco.mj_step(model, data)
            for (j, _, _), r in zip(pushes, report_doors):
                q = math.degrees(float(data.qpos[model.jnt_qposadr[j]]))
                r["max_angle_deg"] = max(r["max_angle_deg"], q)
                r["min_angle_deg"] = min(r["min_angle_deg"], q)
            if robot is not None:
                robot["max_tilt_deg"] = max(robot["max_tilt_deg"], tilt_of(data.xmat[chassis]))
        caught = [str(w.message) for w in py_warnings]

    # mj_step leaves the poses (xpos, xmat) of the state before its integration: update them.
    mujoco.mj_forward(model, data)
    for (j, body, _), r in zip(pushes, report_doors):
        r["angle_deg"] = math.degrees(float(data.qpos[model.jnt_qposadr[j]]))
        r["yaw_deg"] = yaw_of(data.xmat[body])
    if robot is not None:
        end = [float(v) for v in data.xpos[chassis]]
        h = math.radians(robot["heading_deg"])
        robot["end"] = end
        robot["forward_m"] = (end[0] - robot["start"][0]) * math.cos(h) + (
            end[1] - robot["start"][1]
        ) * math.sin(h)
        robot["tilt_deg"] = tilt_of(data.xmat[chassis])

    def geom(g):
        return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, int(g)) or f"geom {int(g)}"

    n = int(data.ncon)
    pairs = zip(data.contact.geom1[:n], data.contact.geom2[:n])
    contacts = sorted({tuple(sorted((geom(g1), geom(g2)))) for g1, g2 in pairs})
    warning_counts = {
        mujoco.mjtWarning(i).name: int(data.warning[i].number)
        for i in range(len(data.warning))
        if data.warning[i].number > 0
    }
    printed = [line for line in err.get("text", "").splitlines() if line.strip()]
    report = {
        "file": args.file,
        "nbody": int(model.nbody),
        "njnt": int(model.njnt),
        "ngeom": int(model.ngeom),
        "nsite": int(model.nsite),
        "nu": int(model.nu),
        "timestep": float(model.opt.timestep),
        "time": float(data.time),
        "warnings": warning_counts,
        "python_warnings": caught,
        "stderr": printed,
        "contacts": [list(c) for c in contacts],
        "doors": report_doors,
        "robot": robot,
    }
    print(json.dumps(report, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
