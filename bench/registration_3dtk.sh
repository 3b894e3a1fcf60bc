#!/usr/bin/env bash
# Registers 3DTK's 2009 corridor (../shared/data/real/3dtk-corridor) with `semsim register
# --sequence` twice: the defaults, and the defaults without range weighting
# ([registration] range_knee_m = 0). For each it reports the pose of scans 1 and 2 relative to
# scan 0 against slam6d's 2009 registration (frames_2009/), and a check that needs no
# reference: the floor (and ceiling) plane of each scan, fitted in its own frame and moved by
# the registered poses, must agree with scan 0's (the robot stood on one flat floor).
# Needs numpy (the oracle venv of tools/oracles/setup.sh). Results:
# bench/results/registration_3dtk.md.
set -euo pipefail
cd "$(dirname "$0")/.."
data=../shared/data/real/3dtk-corridor
py=target/oracles/venv/bin/python
[ -x "$py" ] || bash tools/oracles/setup.sh
cargo build -q --release -p semsim
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '[registration]\nrange_knee_m = 0.0\n' > "$work/unweighted.toml"
target/release/semsim register --sequence "$data" --out "$work/default" > /dev/null 2>&1
target/release/semsim register --sequence "$data" --config "$work/unweighted.toml" \
  --out "$work/unweighted" > /dev/null 2>&1
"$py" bench/registration_3dtk.py "$data" \
  "defaults=$work/default/poses.txt" "no range weighting=$work/unweighted/poses.txt" \
  > bench/results/registration_3dtk.md
cat bench/results/registration_3dtk.md
