#!/usr/bin/env bash
# Sets up bench/.venv (Open3D 0.20 CPU build, small_gicp, numpy), builds semsim in release mode,
# and runs the ICP comparison pinned to two cores. Results: bench/results/icp_compare.{csv,md}.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! python3 -c 'import ctypes.util,sys; sys.exit(0 if ctypes.util.find_library("usb-1.0") else 1)'; then
  echo "installing libusb-1.0-0 (Open3D needs it to import)"; apt-get update -qq && apt-get install -y -qq libusb-1.0-0
fi
if [ ! -x bench/.venv/bin/python ]; then
  python3 -m venv bench/.venv
fi
bench/.venv/bin/pip install -q "open3d-cpu==0.20.*" "small_gicp>=1,<2" numpy
cargo build --release -q
exec taskset -c 0,1 bench/.venv/bin/python bench/compare_icp.py "$@"
