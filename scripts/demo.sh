#!/usr/bin/env bash
# Builds glrt in release mode and runs glrt-demo through it.
#   bash scripts/demo.sh [demo flags...]      (default: --frames 300)
# Uses the X display in $DISPLAY when one answers, otherwise glrt's headless context
# (--headless). Presented frames are asked for as PNG in target/demo-frames through
# GLRT_DUMP; the library does not write them yet (no renderer), and the script says so.
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
    echo "demo.sh: $pngs frames written to $frames_dir"
else
    echo "demo.sh: no PNG frames written (GLRT_DUMP is not implemented yet: glrt has no renderer)"
fi
