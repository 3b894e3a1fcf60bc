#!/usr/bin/env bash
# Sets up the test oracles (idempotent; a second run does nothing but check):
#   * target/oracles/venv: a Python venv with pye57, laspy[lazrs], mcap(+ros2), mujoco (requirements.txt)
#   * tools/oracles/node_modules: gltf-validator and playwright-core (package-lock.json)
#   * Debian packages: libsdformat-dev (SDFormat's parser), liburdfdom-tools (check_urdf), chromium
#   * target/oracles/bin/sdf_check: a tiny program that loads an SDF file with libsdformat
# Prints what it could not set up; the tests then say which oracle is missing (and fail when
# SEMSIM_REQUIRE_ORACLES=1, as scripts/test.sh sets).
set -uo pipefail
cd "$(dirname "$0")/../.."
root="$PWD"
out="$root/target/oracles"
mkdir -p "$out/bin"

# 1. Debian packages (only when they are missing and we may install).
need=()
pkg-config --exists sdformat12 2>/dev/null || need+=(libsdformat-dev)
command -v check_urdf >/dev/null || need+=(liburdfdom-tools)
command -v chromium >/dev/null || need+=(chromium)
command -v g++ >/dev/null || need+=(g++)
command -v pkg-config >/dev/null || need+=(pkg-config)
if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then
    echo "oracles: installing ${need[*]} (apt)"
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null) \
      || echo "oracles: note: apt could not install ${need[*]}"
  else
    echo "oracles: note: not root; install ${need[*]} to run every oracle test"
  fi
fi

# 2. The Python venv.
stamp="$out/venv/.requirements"
if ! cmp -s tools/oracles/requirements.txt "$stamp" 2>/dev/null; then
  echo "oracles: creating target/oracles/venv"
  rm -rf "$out/venv"
  if python3 -m venv "$out/venv" && "$out/venv/bin/pip" install -q --disable-pip-version-check -r tools/oracles/requirements.txt; then
    cp tools/oracles/requirements.txt "$stamp"
  else
    echo "oracles: note: the Python venv could not be set up"
  fi
fi

# 3. npm packages.
if [ ! -d tools/oracles/node_modules/gltf-validator ] || [ ! -d tools/oracles/node_modules/playwright-core ]; then
  echo "oracles: npm ci in tools/oracles"
  (cd tools/oracles && npm ci --silent --no-audit --no-fund >/dev/null) || echo "oracles: note: npm ci failed"
fi

# 4. The SDFormat checker.
if pkg-config --exists sdformat12 2>/dev/null; then
  src=tools/oracles/sdf_check.cc
  if [ ! -x "$out/bin/sdf_check" ] || [ "$src" -nt "$out/bin/sdf_check" ]; then
    echo "oracles: building target/oracles/bin/sdf_check"
    # shellcheck disable=SC2046
    g++ -std=c++17 -O1 -o "$out/bin/sdf_check.tmp" "$src" $(pkg-config --cflags --libs sdformat12) \
      && mv "$out/bin/sdf_check.tmp" "$out/bin/sdf_check" || echo "oracles: note: sdf_check did not build"
  fi
fi
echo "oracles: ready in target/oracles and tools/oracles/node_modules"
