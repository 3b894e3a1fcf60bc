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
#   CONFIG=variant.toml REUSE=scans bash bench/styles.sh  # register and map with a configuration
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
# CONFIG=path: a configuration file (TOML) for `register` and `map` (a variant to compare)
CFG=()
if [ -n "${CONFIG:-}" ]; then CFG=(--config "$CONFIG"); fi
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
      step register "$S" "${CFG[@]}" register --sequence "$d/scans" --out "$d/reg" || true
    else
      rm -rf "$d" && mkdir -p "$d"
      step generate "$S" building generate --style "$style" --seed "$seed" --out "$d/building.toml" &&
        step scan "$S" scan --building "$d/building.toml" --survey --laser "$LASER" --out "$d/scans" &&
        step register "$S" "${CFG[@]}" register --sequence "$d/scans" --out "$d/reg" || true
    fi
    if [ ! -f "$d/failed.txt" ]; then
      step map "$S" "${CFG[@]}" map "$d/reg/map.pcd" --out "$d/map" &&
        "$S" eval map "$d/map/semantic_map.json" --building "$d/building.toml" \
          --cloud "$d"/scans/scan*.pcd --poses "$d/reg/poses.txt" \
          --true-poses "$d/scans/poses.txt" --json >"$d/eval.json" 2>>"$d/log.txt" ||
        { [ -f "$d/failed.txt" ] || echo eval >"$d/failed.txt"; }
    fi
    if [ -f "$d/failed.txt" ]; then echo "   failed at: $(cat "$d/failed.txt")"; fi
  done
done
# The tables (bench/styles_table.py: also on its own, to write them again from $WORK's evaluations).
python3 bench/styles_table.py "$WORK" "$OUT" "$LASER" "$STYLES" "$SEEDS"
