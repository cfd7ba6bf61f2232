#!/usr/bin/env bash
# Builds glrt in release mode and runs glrt-demo through it.
#   bash scripts/demo.sh [demo flags...]      (default: --frames 300)
# Uses the X display in $DISPLAY when one answers, otherwise glrt's headless context
# (--headless). glrt renders with its Vulkan raster back end (GLRT_DEVICE picks the device;
# Mesa lavapipe on a machine without GPU) and writes every presented frame as PNG into
# target/demo-frames (GLRT_DUMP); the demo prints its frame times.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cargo build --release
ln -sf libglrt.so target/release/libGL.so.1

args=("$@")
((${#args[@]})) || args=(--frames 300)
if [[ -n "${DISPLAY:-}" ]] && xdpyinfo >/dev/null 2>&1; then
    echo "demo.sh: drawing in a window on $DISPLAY"
else
    echo "demo.sh: no X display answers; using glrt's headless context"
    args+=(--headless)
fi

frames_dir=target/demo-frames
rm -rf "$frames_dir" && mkdir -p "$frames_dir"
GLRT_DUMP="$PWD/$frames_dir" LD_LIBRARY_PATH="$PWD/target/release${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
    target/release/glrt-demo "${args[@]}"

pngs=$(find "$frames_dir" -name '*.png' | wc -l)
if ((pngs > 0)); then
    echo "demo.sh: $pngs frames written to $frames_dir (last: $(ls "$frames_dir" | tail -1))"
else
    echo "demo.sh: no PNG frames written (no Vulkan device? see the messages above)" >&2
    exit 1
fi
