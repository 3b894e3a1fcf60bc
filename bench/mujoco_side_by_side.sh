#!/usr/bin/env bash
# semsim's rapier simulation against MuJoCo on the same world, robot and commands: the default
# building and the Pioneer 3-AT, exported to MJCF by semsim (interop), driven 0.4 m/s north from
# the corridor through the closed door into room A for 10 s, then braking, 20 s simulated at
# 1/60 s, best of 5 runs each, pinned to two cores.
#   bash bench/mujoco_side_by_side.sh [side_by_side options: --robot NAME --start X,Y,YAW
#                                      --speed MPS --drive-s S --seconds S --runs N]
# Results: bench/results/mujoco_side_by_side.{json,md}.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/oracles/setup.sh >/dev/null
cargo build --release -q -p interop --example side_by_side
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
taskset -c 0,1 target/release/examples/side_by_side "$work" "$@" > "$work/semsim.json"
exec taskset -c 0,1 target/oracles/venv/bin/python bench/mujoco_side_by_side.py "$work/semsim.json"
