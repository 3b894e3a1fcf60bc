#!/usr/bin/env bash
# Runs the description-file fuzz targets (fuzz/formats), one after the other, as ../run.sh does
# for the cloud targets:  fuzz/formats/run.sh [SECONDS_PER_TARGET] [TARGET...]
# Seeds in fuzz/formats/corpus/<target>/ are read, never changed (libFuzzer adds to work/).
# Prints one line per target and writes fuzz/formats/results.md; exits 0 with a message where
# nightly or cargo-fuzz is missing, 1 if a target found a crash, OOM or timeout.
set -uo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
shift || true
if ! cargo +nightly fuzz --help >/dev/null 2>&1; then
  echo "fuzz/formats/run.sh: skipping: needs the nightly toolchain and cargo-fuzz"
  exit 0
fi
if [ "$#" -gt 0 ]; then targets=("$@"); else mapfile -t targets < <(cargo +nightly fuzz list --fuzz-dir formats); fi
cargo +nightly fuzz build --fuzz-dir formats || exit 1
rows=(); failed=0
for t in "${targets[@]}"; do
  mkdir -p "formats/work/$t" "formats/corpus/$t" "formats/artifacts/$t"
  log="formats/work/$t.log"
  start=$(date +%s)
  cargo +nightly fuzz run --fuzz-dir formats "$t" "formats/work/$t" "formats/corpus/$t" -- \
    -artifact_prefix="formats/artifacts/$t/" -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -timeout=10 -max_total_time="$seconds" -print_final_stats=1 >"$log" 2>&1
  rc=$?
  elapsed=$(( $(date +%s) - start ))
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1)
  crash=$(grep -c 'ERROR: libFuzzer: deadly signal\|panicked at' "$log")
  oom=$(grep -c 'out-of-memory' "$log")
  tout=$(grep -c 'ERROR: libFuzzer: timeout' "$log")
  [ "$rc" -ne 0 ] && failed=1
  rows+=("| $t | ${execs:-?} | ${cov:-?} | $elapsed | $crash | $oom | $tout |")
  echo "${rows[-1]}"
done
{
  echo "# Fuzzing results: description files"
  echo
  echo "Last run: $(date -u '+%Y-%m-%d %H:%M') UTC, command \`fuzz/formats/run.sh $seconds\`, libFuzzer with ASAN, \`-rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10\`."
  echo
  echo "| target | executions | coverage | seconds | crashes | OOMs | timeouts |"
  echo "|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} > formats/results.md
exit $failed
