#!/usr/bin/env bash
# Builds glrt in release mode and runs glrt-demo through it.
#   bash scripts/demo.sh [demo flags...]      (default: --frames 300)
# Uses the X display in $DISPLAY when one answers, otherwise glrt's headless context
# (--headless). glrt renders in its default mode (GLRT_MODE: path traced on a GPU, rasterized
# on Mesa lavapipe when the machine has no GPU; GLRT_DEVICE picks the device) and writes every
# presented frame as PNG into target/demo-frames (GLRT_DUMP); the demo prints its frame times.
# Then 8 frames at 160x120, path traced whatever the device, go to
# target/demo-frames-pathtrace, with the tracer's rays per frame (GLRT_LOG=info).
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

# run_demo DIR [VAR=VALUE...] -- [demo flags...]: the demo with frames written to DIR.
run_demo() {
    local dir=$1
    shift
    rm -rf "$dir" && mkdir -p "$dir"
    env GLRT_DUMP="$PWD/$dir" LD_LIBRARY_PATH="$PWD/target/release${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$@"
    local pngs
    pngs=$(find "$dir" -name '*.png' | wc -l)
    if ((pngs > 0)); then
        echo "demo.sh: $pngs frames written to $dir (last: $(ls "$dir" | tail -1))"
    else
        echo "demo.sh: no PNG frames written to $dir (no Vulkan device? see the messages above)" >&2
        exit 1
    fi
}

run_demo target/demo-frames target/release/glrt-demo "${args[@]}"
echo "demo.sh: path traced, 8 frames at 160x120 (headless):"
run_demo target/demo-frames-pathtrace GLRT_MODE=pathtrace GLRT_LOG=info \
    target/release/glrt-demo --headless --frames 8 --size 160x120
