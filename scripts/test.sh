#!/usr/bin/env bash
# The README's test command: sets up the test oracles (tools/oracles/setup.sh: a Python venv,
# npm packages, Debian's SDFormat, urdfdom tools and chromium), then runs the whole test suite
# with every oracle required (a missing one fails its test instead of skipping it).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/oracles/setup.sh
export SEMSIM_REQUIRE_ORACLES=1
cargo test --workspace "$@"
