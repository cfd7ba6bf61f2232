#!/usr/bin/env bash
# Capture overhead: glrt-demo --headless for N frames (default 300) with GLRT_CAPTURE off and
# on, in the same run, and the capture's size per frame.
#   bash bench/capture.sh [FRAMES]
# Environment: BENCH_PROFILE=release|debug (default release).
set -euo pipefail
cd "$(dirname "$0")/.."

frames=${1:-300}
profile=${BENCH_PROFILE:-release}
if [[ $profile == release ]]; then cargo build --release; else cargo build; fi
dir="$PWD/target/$profile"
ln -sf libglrt.so "$dir/libGL.so.1"
capture=$(mktemp --suffix=.glrtcap)
trap 'rm -f "$capture"' EXIT

# The average frame time (ms) of a run.
avg() { grep -o 'avg [0-9.]*' | cut -d' ' -f2; }
run() { LD_LIBRARY_PATH="$dir" "$dir/glrt-demo" --headless --frames "$frames" --size 640x480; }

off=$(run | avg)
on=$(GLRT_CAPTURE="$capture" run | avg)
size=$(stat -c %s "$capture")
echo "glrt-demo --headless, $frames frames, $profile build"
awk -v off="$off" -v on="$on" -v size="$size" -v n="$frames" 'BEGIN {
    printf "capture off: %.3f ms/frame (%.1f fps)\n", off, 1000 / off
    printf "capture on:  %.3f ms/frame (%.1f fps), %+.1f%%\n", on, 1000 / on, 100 * (on - off) / off
    printf "capture size: %d bytes, %.1f KiB per frame\n", size, size / n / 1024
}'
"$dir/glrt" info "$capture" | head -6
