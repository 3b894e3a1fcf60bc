#!/usr/bin/env bash
# The semantic stage on cluttered buildings of ~1.6 M points (issue #15: under 1 s on 2 cores):
# the clutter tests' garage (ideal laser) and a generated `garage` style building (realistic
# laser, survey poses), each scanned at full resolution and mapped RUNS times on two threads;
# per-stage medians written to bench/results/semantic_clutter.md.
#
#   bench/semantic_clutter.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-7}"
cargo build --release -q -p semantic --example bench_clutter
out=bench/results/semantic_clutter.md
{
  echo "# Semantic stage on cluttered buildings"
  echo
  echo "\`bench/semantic_clutter.sh $runs\` on $(nproc) CPUs ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)), $(date -u +%Y-%m-%d), RAYON_NUM_THREADS=2:"
  echo
  RAYON_NUM_THREADS=2 target/release/examples/bench_clutter "$runs"
} > "$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
