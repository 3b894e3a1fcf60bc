#!/usr/bin/env bash
# The semantic map on every generator style: for each style, generated buildings (fixed seeds)
# scanned along `semsim scan --survey` poses with the realistic laser (`--laser real`),
# registered from the simulated odometry (`semsim register --sequence`), mapped (`semsim map`)
# and scored against ground truth (`semsim eval map --cloud ... --poses ...`).
# Writes one table per style to bench/results/styles.md (and the raw evaluations under
# bench/work/styles/).
#
#   bash bench/styles.sh                      # styles office garage hall mixed, seeds 1-10
#   STYLES="garage" SEEDS="1 2" bash bench/styles.sh
#   LASER=ideal bash bench/styles.sh          # the ideal laser instead
#   REUSE=1 bash bench/styles.sh              # keep the scans and registrations already in
#                                             # $WORK; only map and score again (semantic work)
#   SEMSIM=/tmp/semsim bash bench/styles.sh  # that binary, no build
#   REUSE=scans bash bench/styles.sh          # keep the scans; register, map and score again
#   SEEDS="11 12 13 14 15" WORK=bench/work/heldout OUT=bench/results/styles_heldout.md \
#     bash bench/styles.sh                    # the held-out seeds (README)
set -euo pipefail
cd "$(dirname "$0")/.."
STYLES=${STYLES:-"office garage hall mixed"}
SEEDS=${SEEDS:-"1 2 3 4 5 6 7 8 9 10"}
LASER=${LASER:-real}
OUT=${OUT:-bench/results/styles.md}
WORK=${WORK:-bench/work/styles}
REUSE=${REUSE:-0}
# SEMSIM=path: that binary instead of building one (e.g. a copy, to go on building meanwhile)
if [ -n "${SEMSIM:-}" ]; then S=$SEMSIM; else cargo build --release -q -p semsim; S=target/release/semsim; fi
# (Only the styles asked for are scanned again: the others' results stay in $WORK.)
if [ "$REUSE" != 1 ] && [ "$REUSE" != scans ]; then for style in $STYLES; do rm -rf "$WORK/$style"-*; done; fi
mkdir -p "$WORK"
for style in $STYLES; do
  for seed in $SEEDS; do
    d="$WORK/$style-$seed"
    mkdir -p "$d"
    echo "== $style seed $seed"
    # A building whose registration (or any step) fails is recorded as failed, not dropped.
    step() { local what=$1; shift; "$@" >>"$d/log.txt" 2>&1 || { echo "$what" >"$d/failed.txt"; return 1; }; }
    if [ "$REUSE" = 1 ] && [ -f "$d/reg/map.pcd" ]; then
      # (log.txt too: a copy made with `cp -al` shares its files with the original)
      rm -rf "$d/failed.txt" "$d/map" "$d/eval.json" "$d/log.txt"
    elif [ "$REUSE" = scans ] && [ -f "$d/scans/poses.txt" ]; then
      rm -rf "$d/failed.txt" "$d/reg" "$d/map" "$d/eval.json" "$d/log.txt"
      step register "$S" register --sequence "$d/scans" --out "$d/reg" || true
    else
      rm -rf "$d" && mkdir -p "$d"
      step generate "$S" building generate --style "$style" --seed "$seed" --out "$d/building.toml" &&
        step scan "$S" scan --building "$d/building.toml" --survey --laser "$LASER" --out "$d/scans" &&
        step register "$S" register --sequence "$d/scans" --out "$d/reg" || true
    fi
    if [ ! -f "$d/failed.txt" ]; then
      step map "$S" map "$d/reg/map.pcd" --out "$d/map" &&
        "$S" eval map "$d/map/semantic_map.json" --building "$d/building.toml" \
          --cloud "$d"/scans/scan*.pcd --poses "$d/reg/poses.txt" \
          --true-poses "$d/scans/poses.txt" --json >"$d/eval.json" 2>>"$d/log.txt" ||
        { [ -f "$d/failed.txt" ] || echo eval >"$d/failed.txt"; }
    fi
    if [ -f "$d/failed.txt" ]; then echo "   failed at: $(cat "$d/failed.txt")"; fi
  done
done
python3 - "$WORK" "$OUT" "$LASER" "$STYLES" "$SEEDS" <<'PY'
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
    beams = sum(e.get("walls_on_beams_or_columns", 0) for e in evs)
    errs = [e["wall_endpoint_error_mean_m"] for e in evs if e.get("wall_endpoint_error_mean_m") is not None]
    err = sum(errs) / len(errs) if errs else float("nan")
    bm = total(evs, "beams")
    # Ramps: matched / seen (reported), the largest pitch error (evaluations without ramps: -).
    rp = {k: sum(e.get("ramps", {}).get(k, 0) for e in evs) for k in ("expected", "detected", "matched")}
    pitch = [abs(m["pitch_error_deg"]) for e in evs for m in e.get("ramp_matches", [])]
    ramps = (f"{rp['matched']}/{rp['expected']} ({rp['detected']})"
             + (f", {max(pitch):.2f}" if pitch else "")) if any("ramps" in e for e in evs) else "-"
    return (f"| {name} | {poses} | {f1(w):.3f} | {f1(d):.3f} | {exact}/{st['expected']} | {exact_full}/{len(full)} | "
            f"{false_stairs} | {recall:.3f} ({o['matched']}/{o['expected']}) | {beams} | {100 * err:.1f} | "
            f"{bm['matched']}/{bm['expected']} ({bm['detected']}) | {ramps} |")

lines = [
    "# The semantic map on every generator style",
    "",
    f"`bash bench/styles.sh` (seeds {' '.join(seeds)}; laser `{laser}`): each building generated with",
    "`semsim building generate --style S --seed N`, scanned along `semsim scan --survey` poses,",
    "registered from the simulated odometry, mapped and scored with `semsim eval map --cloud`.",
    "F1 and recall are over all buildings of the style (summed counts); stairs exact: staircases",
    "found with the true step count / staircases the scans saw; every step seen: the same for the",
    "flights whose every step the scans saw (at least 5 returns on its tread, riser or the top edge",
    "of its side; a step never seen cannot be counted); false stairs: staircases",
    "reported where there is none; beams as walls: walls reported on a beam or a row of pillars;",
    "endpoint error: mean of the buildings' mean wall endpoint errors; beams found: true beams, ducts",
    "and pipes matched / seen (beams the map reports); ramps: true ramps matched / seen (ramps the map",
    "reports), and the largest pitch error of a matched one (degrees).",
    "",
]
header = ("| building | poses | walls F1 | doors F1 | stairs exact | every step seen | false stairs | "
          "obstacles recall | beams as walls | endpoint error (cm) | beams found (reported) | ramps |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|")
for style in styles:
    lines += [f"## {style}", "", header]
    evs, all_poses, failed = [], 0, 0
    for seed in seeds:
        d = os.path.join(work, f"{style}-{seed}")
        scans = os.path.join(d, "scans")
        poses = sum(1 for n in os.listdir(scans) if n.endswith(".pcd")) if os.path.isdir(scans) else 0
        if os.path.exists(os.path.join(d, "failed.txt")):
            what = open(os.path.join(d, "failed.txt")).read().strip()
            lines.append(f"| seed {seed} | {poses} | failed at `{what}` (see `{d}/log.txt`) | | | | | | | | | |")
            failed += 1
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
PY
