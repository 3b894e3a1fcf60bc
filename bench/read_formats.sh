#!/usr/bin/env bash
# Reading speed and peak memory of LAZ and E57 against laspy[lazrs] and pye57 (the oracles'
# venv, set up by tools/oracles/setup.sh), on generated 10 M-point files, pinned to two cores.
#   bash bench/read_formats.sh [--points N] [--runs R]
# Results: bench/results/read_formats.{json,md}.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/oracles/setup.sh >/dev/null
cargo build --release -q -p semsim
exec taskset -c 0,1 target/oracles/venv/bin/python bench/read_formats.py "$@"
