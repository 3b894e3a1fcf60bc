#!/usr/bin/env bash
# Runs the fuzz targets, one after the other, on the committed seed corpora.
#
#   fuzz/run.sh [SECONDS_PER_TARGET] [TARGET...]
#
# SECONDS_PER_TARGET defaults to 20, TARGET to every target of `cargo fuzz list`. Each target
# runs under libFuzzer with -rss_limit_mb=2048 (also the largest single allocation),
# -timeout=10 (seconds per input) and -max_total_time=SECONDS_PER_TARGET. The committed seeds
# in fuzz/corpus/<target>/ are read, never changed: what libFuzzer adds goes to
# fuzz/work/<target>/ (ignored by git, reused by the next run). A crash, OOM or timeout stops
# that target: its input is in fuzz/artifacts/<target>/ and the log in fuzz/work/<target>.log.
#
# Prints a summary table and writes it to fuzz/results.md (or to $FUZZ_RESULTS, as CI does so
# that a smoke run never replaces the committed 10-minute figures). Exits 0 (with a message) where
# the nightly toolchain or cargo-fuzz is missing; 1 if any target found a failure.
set -uo pipefail
cd "$(dirname "$0")"

seconds="${1:-20}"
shift || true
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -eq 0 ]; then
  echo "usage: fuzz/run.sh [SECONDS_PER_TARGET] [TARGET...]" >&2
  exit 2
fi

if ! cargo +nightly --version >/dev/null 2>&1; then
  echo "fuzz/run.sh: skipping: no nightly toolchain (rustup toolchain install nightly)"
  exit 0
fi
if ! cargo +nightly fuzz --help >/dev/null 2>&1; then
  echo "fuzz/run.sh: skipping: cargo-fuzz is not installed (cargo install cargo-fuzz)"
  exit 0
fi

if [ "$#" -gt 0 ]; then
  targets=("$@")
else
  mapfile -t targets < <(cargo +nightly fuzz list)
fi

echo "== building ${targets[*]}"
if [ "$#" -gt 0 ]; then
  for t in "${targets[@]}"; do
    cargo +nightly fuzz build "$t" || { echo "fuzz/run.sh: build of $t failed" >&2; exit 1; }
  done
else
  cargo +nightly fuzz build || { echo "fuzz/run.sh: build failed" >&2; exit 1; }
fi

rows=()
failed=0
for t in "${targets[@]}"; do
  mkdir -p "work/$t" "corpus/$t" "artifacts/$t"
  log="work/$t.log"
  echo "== $t: ${seconds} s"
  start=$(date +%s)
  cargo +nightly fuzz run "$t" "work/$t" "corpus/$t" -- \
    -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10 \
    -max_total_time="$seconds" -print_final_stats=1 >"$log" 2>&1
  rc=$?
  elapsed=$(( $(date +%s) - start ))
  execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1 | sed 's/cov: \([0-9]*\) ft: \([0-9]*\)/\1 \/ \2/')
  crashes=0; ooms=0; timeouts=0; artifact=""
  if grep -q 'ERROR: libFuzzer: out-of-memory' "$log"; then ooms=1
  elif grep -q 'ERROR: libFuzzer: timeout' "$log"; then timeouts=1
  elif [ "$rc" -ne 0 ]; then crashes=1
  fi
  artifact=$(grep -o 'artifact_prefix=[^;]*; Test unit written to [^ ]*' "$log" | tail -1 | sed 's/.*written to //')
  if [ $((crashes + ooms + timeouts)) -gt 0 ]; then
    failed=1
    echo "   FOUND: $(grep -m1 -E 'panicked at|ERROR: libFuzzer|ERROR: AddressSanitizer' "$log")"
    [ -n "$artifact" ] && echo "   input: $artifact"
  fi
  row="| $t | ${execs:-?} | ${cov:-?} | $elapsed | $crashes | $ooms | $timeouts |"
  echo "   $row"
  rows+=("$row")
done

# With TARGETs named, the rows of the other targets are kept from the previous results.md.
kept=()
if [ "$#" -gt 0 ] && [ -f results.md ]; then
  while IFS= read -r line; do
    name=$(awk -F'|' '{gsub(/ /, "", $2); print $2}' <<<"$line")
    keep=1
    for t in "${targets[@]}"; do [ "$name" = "$t" ] && keep=0; done
    [ "$keep" = 1 ] && kept+=("$line")
  done < <(grep '^| ' results.md | grep -v '^| target')
fi
{
  echo "# Fuzzing results"
  echo
  echo "Last run: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, $(cargo +nightly --version), $(cargo +nightly fuzz --version 2>/dev/null)."
  echo "Command (from the repository root): \`fuzz/run.sh $seconds${*:+ $*}\`"
  [ "${#kept[@]}" -gt 0 ] && echo "Rows of targets not named in that command are from earlier runs."
  echo "libFuzzer with the address sanitizer and debug assertions, \`-rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10\`."
  echo "A crash, OOM or timeout stops its target (so each count is 0 or 1); the input is kept in \`fuzz/artifacts/<target>/\`."
  echo
  echo "| target | executions | coverage (cov / ft) | seconds | crashes | OOMs | timeouts |"
  echo "|---|---|---|---|---|---|---|"
  [ "${#kept[@]}" -gt 0 ] && printf '%s\n' "${kept[@]}"
  printf '%s\n' "${rows[@]}"
} >"${FUZZ_RESULTS:-results.md}"
echo
cat "${FUZZ_RESULTS:-results.md}"
exit "$failed"
