#!/usr/bin/env bash
# `semsim bench icp` on a lent NVIDIA machine (see /work/.library/device/README.md). That
# machine has no Rust toolchain and no Vulkan loader, so both travel from here:
#
#   bash bench/gpu_device.sh prepare     # here: stripped release binary + Vulkan/EGL loaders
#   then, through the device tool, with carry [".device", ".gl"]:
#   bash bench/gpu_device.sh run         # there: unpack the loaders, run the benchmark
#
# The report lands in $OUT/bench_icp.json and the table at the end of the output.
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
prepare)
    grep -qxF '/.device/' .git/info/exclude || echo /.device/ >>.git/info/exclude
    grep -qxF '/.gl/' .git/info/exclude || echo /.gl/ >>.git/info/exclude
    cargo build --release -p semsim
    mkdir -p .device .gl /tmp/amd64/partial
    strip -o .device/semsim target/release/semsim
    o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
    apt-get $o update >/dev/null
    (cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
    du -sh .device .gl
    ;;
run)
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
    icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
    [ -f "$icd" ] && export VK_DRIVER_FILES="$icd"
    export XDG_RUNTIME_DIR=/tmp
    nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv || true
    out="${OUT:-/tmp}"
    # The CPU reference on 2 threads, as the 2-core machine the issue compares with.
    RAYON_NUM_THREADS=2 ./.device/semsim bench icp --device auto --iterations 20 \
        --json "$out/bench_icp.json" \
        2>&1 | tee "$out/bench_icp.txt"
    ;;
*)
    echo "usage: $0 prepare|run" >&2
    exit 2
    ;;
esac
