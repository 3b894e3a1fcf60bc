#!/usr/bin/env bash
# Pictures of `semsim run` with no flags on each real scan sequence of ../shared/data/real
# (see its MANIFEST.md): what a person sees in the registered scans (from above and obliquely,
# coloured by height, the ceiling left out) beside the semantic map at the same scale (the
# floor where it was seen, walls, door leaves with their swing, openings, obstacles, columns,
# beams, and the simulated robot's path of the planned tour in red, its start in green).
# Writes docs/images/real/<dataset>-scans.png and -map.png (each kept under 300 KB) and the
# runs' summaries to bench/results/real_runs.md; the runs themselves go to bench/work/real/.
# Needs numpy (the oracle venv of tools/oracles/setup.sh, or any python3 with numpy: PY=...).
#
#   bash bench/real_pictures.sh
#   DATASETS="3dtk-corridor" bash bench/real_pictures.sh
#   SEMSIM=path/to/semsim bash bench/real_pictures.sh   # that binary, no build
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${DATA:-../shared/data/real}
DATASETS=${DATASETS:-"3dtk-corridor pcl-room small-gicp"}
WORK=${WORK:-bench/work/real}
IMAGES=${IMAGES:-docs/images/real}
OUT=${OUT:-bench/results/real_runs.md}
PY=${PY:-target/oracles/venv/bin/python}
[ -x "$PY" ] || bash tools/oracles/setup.sh
S=${SEMSIM:-target/release/semsim}
[ -n "${SEMSIM:-}" ] || cargo build --release -q -p semsim
mkdir -p "$WORK" "$IMAGES"
{
  echo "# semsim run on real scans, no flags"
  echo
  echo "Written by \`bash bench/real_pictures.sh\` ($(date -u +%Y-%m-%d))."
  echo
  echo "| dataset | exit | entities | floor | planned tour | verdict |"
  echo "|---|---|---|---|---|---|"
} > "$OUT"
for d in $DATASETS; do
  [ -d "$DATA/$d" ] || { echo "skip $d: $DATA/$d is absent"; continue; }
  rm -rf "${WORK:?}/$d"
  set +e
  "$S" run "$DATA/$d" --out "$WORK/$d" > "$WORK/$d.log" 2>&1
  rc=$?
  set -e
  echo "== $d: exit $rc"
  if [ -f "$WORK/$d/map/semantic_map.json" ]; then
    "$PY" bench/real_pictures.py "$WORK/$d" "$IMAGES/$d"
    for f in "$IMAGES/$d"-*.png; do
      size=$(stat -c %s "$f")
      [ "$size" -lt 300000 ] || { echo "$f is $size bytes (over 300 KB)"; exit 1; }
    done
  fi
  entities=$(grep -m1 '^entities: ' "$WORK/$d.log" | sed 's/^entities: //; s/;.*//' || true)
  floor=$(grep -o '"seen floor: [^"]*"' "$WORK/$d/map/semantic_map.json" 2>/dev/null | head -1 | tr -d '"' || true)
  tour=$(grep -m1 '^planned tour: ' "$WORK/$d.log" | sed 's/^planned tour: //' || true)
  verdict=$(grep -m1 -o 'verdict: [A-Z]*' "$WORK/$d.log" || true)
  echo "| $d | $rc | $entities | $floor | $tour | $verdict |" >> "$OUT"
done
echo "wrote $OUT and $IMAGES/"
