#!/usr/bin/env python3
"""The tables of bench/styles.sh from the evaluations in its work folder.

    python3 bench/styles_table.py WORK OUT LASER "STYLES" "SEEDS"
"""
import json, os, sys
work, out, laser, styles, seeds = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4].split(), sys.argv[5].split()

def f1(s):
    p = s["matched"] / s["detected"] if s["detected"] else 1.0
    r = s["matched"] / s["expected"] if s["expected"] else 1.0
    return 2 * p * r / (p + r) if p + r else 0.0

def total(evs, key):
    return {k: sum(e[key][k] for e in evs) for k in ("expected", "detected", "matched")}

def row(name, evs, poses):
    w, d, o = total(evs, "walls"), total(evs, "door_openings"), total(evs, "obstacles")
    st = total(evs, "stairs")
    exact = sum(1 for e in evs for m in e["stairs_matches"] if m["steps"] == m["steps_truth"])
    # Flights whose every step the scans saw (tread, riser or the top of its side: `stairs_seen`).
    full = {(i, s["truth"]) for i, e in enumerate(evs) for s in e.get("stairs_seen", [])
            if s["steps_seen"] == s["steps"]}
    exact_full = sum(1 for i, e in enumerate(evs) for m in e["stairs_matches"]
                     if (i, m["truth"]) in full and m["steps"] == m["steps_truth"])
    false_stairs = st["detected"] - st["matched"]
    recall = o["matched"] / o["expected"] if o["expected"] else 1.0
    # Obstacles reported where the scans saw no thing of the building (their boxes hold only
    # floor, ceiling and unexplained returns: a person's remains, mixed pixels); evaluations
    # older than `obstacles_unmatched`: -.
    if all("obstacles_unmatched" in e for e in evs):
        phantoms = str(sum(1 for e in evs for u in e["obstacles_unmatched"]
                           if all(n in ("floor", "ceiling", "unknown") for n, _ in u["seen_inside"])))
        precision = f"{o['matched'] / o['detected']:.2f}" if o["detected"] else "1.00"
    else:
        phantoms, precision = "-", "-"
    beams = sum(e.get("walls_on_beams_or_columns", 0) for e in evs)
    errs = [e["wall_endpoint_error_mean_m"] for e in evs if e.get("wall_endpoint_error_mean_m") is not None]
    err = sum(errs) / len(errs) if errs else float("nan")
    bm = total(evs, "beams")
    # Ramps: matched / seen (reported), the largest pitch error (evaluations without ramps: -).
    rp = {k: sum(e.get("ramps", {}).get(k, 0) for e in evs) for k in ("expected", "detected", "matched")}
    pitch = [abs(m["pitch_error_deg"]) for e in evs for m in e.get("ramp_matches", [])]
    ramps = (f"{rp['matched']}/{rp['expected']} ({rp['detected']})"
             + (f", {max(pitch):.2f}" if pitch else "")) if any("ramps" in e for e in evs) else "-"
    # Walls: the share of the true walls' seen length along which a map wall runs (evaluations
    # older than `wall_length`: -).
    if all("wall_length" in e for e in evs):
        seen = sum(e["wall_length"]["expected_m"] for e in evs)
        covered = f"{sum(e['wall_length']['covered_m'] for e in evs) / seen:.3f}" if seen else "1.000"
    else:
        covered = "-"
    return (f"| {name} | {poses} | {f1(w):.3f} | {covered} | {f1(d):.3f} | {exact}/{st['expected']} | {exact_full}/{len(full)} | "
            f"{false_stairs} | {recall:.3f} ({o['matched']}/{o['expected']}) | {precision} | {phantoms} | {beams} | {100 * err:.1f} | "
            f"{bm['matched']}/{bm['expected']} ({bm['detected']}) | {ramps} |")

lines = [
    "# The semantic map on every generator style",
    "",
    f"`bash bench/styles.sh` (seeds {' '.join(seeds)}; laser `{laser}`): each building generated with",
    "`semsim building generate --style S --seed N`, scanned along `semsim scan --survey` poses,",
    "registered from the simulated odometry, mapped and scored with `semsim eval map --cloud`.",
    "F1 and recall are over all buildings of the style (summed counts); walls covered: the share of",
    "the true walls' seen length along which a map wall runs (a wall matched by a map wall over",
    "half of it counts in F1 however much is missing); stairs exact: staircases",
    "found with the true step count / staircases the scans saw; every step seen: the same for the",
    "flights whose every step the scans saw (at least 5 returns on its tread, riser or the top edge",
    "of its side; a step never seen cannot be counted); false stairs: staircases",
    "reported where there is none; beams as walls: walls reported on a beam or a row of pillars;",
    "endpoint error: mean of the buildings' mean wall endpoint errors; beams found: true beams, ducts",
    "and pipes matched / seen (beams the map reports); ramps: true ramps matched / seen (ramps the map",
    "reports), and the largest pitch error of a matched one (degrees); obstacles precision: matched /",
    "reported (a car reported as its body and a side face counts one match and one unmatched box);",
    "phantoms: obstacles reported where the scans saw nothing of the building (their boxes hold only",
    "floor, ceiling and returns no entity explains: what is left of people, mixed pixels).",
    "",
]
header = ("| building | poses | walls F1 | walls covered | doors F1 | stairs exact | every step seen | false stairs | "
          "obstacles recall | obstacles precision | phantoms | beams as walls | endpoint error (cm) | beams found (reported) | ramps |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for style in styles:
    lines += [f"## {style}", "", header]
    evs, all_poses = [], 0
    for seed in seeds:
        d = os.path.join(work, f"{style}-{seed}")
        scans = os.path.join(d, "scans")
        poses = sum(1 for n in os.listdir(scans) if n.endswith(".pcd")) if os.path.isdir(scans) else 0
        if os.path.exists(os.path.join(d, "failed.txt")):
            what = open(os.path.join(d, "failed.txt")).read().strip()
            lines.append(f"| seed {seed} | {poses} | failed at `{what}` (see `{d}/log.txt`) | | | | | | | | | | | | |")
            continue
        ev = json.load(open(os.path.join(d, "eval.json")))
        evs.append(ev)
        all_poses += poses
        lines.append(row(f"seed {seed}", [ev], poses))
    if evs:
        lines.append(row(f"**all** ({len(evs)} of {len(seeds)})", evs, all_poses))
    lines.append("")
open(out, "w").write("\n".join(lines))
print("\n".join(lines))
