#!/usr/bin/env bash
# Operator console figures (issue 14) on the demo map with its point-cloud layer: server CPU
# and real-time pacing at the 60 Hz step with the inspection robot and one WebSocket client,
# `state` message sizes and rate, headless Chromium's time to the first rendered world and its
# frame rate (software WebGL) with the cloud layer shown. The demo's output (`semsim demo`:
# map/semantic_map.json, map/labels.pcd, simulation/scenario.toml) is made once and cached in
# target/console-bench-demo/ (DEMO_DIR=... to use another). Writes bench/results/console.json
# and console.md and prints a table. Needs node (>= 20), tools/oracles/node_modules/playwright-core
# (tools/oracles/setup.sh) and /usr/bin/chromium (or CHROMIUM=...).
#
#     bash bench/console.sh
#
# SKIP_BUILD=1 uses the existing target/release/semsim (BIN=... another binary).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

if [ "${SKIP_BUILD:-0}" != 1 ]; then
  nice cargo build --release -p semsim
fi
bin="${BIN:-$root/target/release/semsim}"

demo="${DEMO_DIR:-$root/target/console-bench-demo}"
if [ ! -f "$demo/map/semantic_map.json" ] || [ ! -f "$demo/map/labels.pcd" ]; then
  if [ -n "${DEMO_DIR:-}" ]; then echo "DEMO_DIR=$demo has no map/semantic_map.json and map/labels.pcd" >&2; exit 1; fi
  rm -rf "$demo"
  echo "semsim demo -> $demo (once; cached)"
  nice "$bin" demo --out "$demo" >/dev/null
fi

node_major=$(node --version | sed 's/^v\([0-9]*\).*/\1/')
node_flags=()
if [ "$node_major" -lt 22 ]; then node_flags=(--experimental-websocket); fi

tmp=$(mktemp -d)
server_pid=
cleanup() {
  if [ -n "$server_pid" ] && kill -0 "$server_pid" 2>/dev/null; then
    kill -INT "$server_pid" 2>/dev/null || true
    for _ in $(seq 1 100); do kill -0 "$server_pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$server_pid" 2>/dev/null || true
  fi
  rm -rf "$tmp"
}
trap cleanup EXIT

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg) ($(nproc) CPUs)"
args=(console --map "$demo/map/semantic_map.json" --cloud "$demo/map/labels.pcd"
  --scenario "$demo/simulation/scenario.toml" --robot inspection --port 0)
"$bin" "${args[@]}" --out "$tmp/out" >"$tmp/stdout" 2>"$tmp/stderr" &
server_pid=$!
url=
for _ in $(seq 1 300); do
  url=$(sed -n 's/^console: //p' "$tmp/stdout" | head -1)
  [ -n "$url" ] && break
  kill -0 "$server_pid" 2>/dev/null || { cat "$tmp/stderr" >&2; echo "semsim console exited" >&2; exit 1; }
  sleep 0.1
done
[ -n "$url" ] || { cat "$tmp/stderr" >&2; echo "semsim console printed no URL" >&2; exit 1; }
echo "console at $url (pid $server_pid)"

CONSOLE_CMD="semsim ${args[*]//$root\//}" \
  node "${node_flags[@]}" bench/console_bench.mjs "$url" "$server_pid" bench/results
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "wrote bench/results/console.json and bench/results/console.md"
