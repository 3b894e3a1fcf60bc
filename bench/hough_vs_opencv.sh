#!/usr/bin/env bash
# Sets up bench/.venv-opencv (opencv-python-headless, numpy) and compares semsim's progressive
# probabilistic Hough transform (the `hough` example of crates/semantic, run in release mode by
# the Python script) with OpenCV's HoughLinesP, pinned to two cores.
# Results: bench/results/hough_vs_opencv.md.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x bench/.venv-opencv/bin/python ]; then
  python3 -m venv bench/.venv-opencv
fi
bench/.venv-opencv/bin/pip install -q "opencv-python-headless>=4.8" numpy
exec taskset -c 0,1 bench/.venv-opencv/bin/python bench/hough_vs_opencv.py "$@"
