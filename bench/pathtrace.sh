#!/usr/bin/env bash
# The compute path tracer on a GPU (bench/pathtrace.md keeps the results): glrt-demo
# headless at SIZE through glrt's libGL.so.1, rasterized (the peer, same process kind, same
# device) and path traced, then the Quake-3-like re-batched world at ~1M triangles
# (`--rebatch --detail 11`: 1,045,440 triangles in the world, those in view traced).
# For each run: the demo's frame times, and the tracer's own summary (`GLRT_LOG=info`, logged
# when the tracer is destroyed: triangles and instances traced, rays per frame by kind, BVH
# nodes and triangle tests per ray, GPU time of the tracing pass from timestamps, rays/s).
#   bash bench/pathtrace.sh BIN_DIR OUT_DIR [FRAMES] [SIZE]
# BIN_DIR holds a release build's libglrt.so and glrt-demo (target/release here; the GPU
# machine gets them carried). Screenshots of the last frame go to OUT_DIR.
set -uo pipefail
bin=$(cd "$1" && pwd)
out=$2
frames=${3:-300}
size=${4:-1280x720}
mkdir -p "$out"
ln -sf libglrt.so "$bin/libGL.so.1"
clean=(env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_DUMP -u GLRT_PASSTHROUGH -u GLRT_MODE LD_LIBRARY_PATH="$bin" GLRT_LOG=info)

# run NAME "VAR=VALUE ..." [demo args...]: one run with those settings; its frame-time and
# tracer lines.
run() {
    local name=$1 settings=$2
    shift 2
    echo "== $name ($settings; $size, $frames frames)"
    # shellcheck disable=SC2086 # the settings are words on purpose
    "${clean[@]}" $settings "$bin/glrt-demo" --headless --frames "$frames" --size "$size" \
        --screenshot "$out/$name.png" "$@" 2>&1 | grep -E "frame time|path tracer|rebatch:|Vulkan device|error|panick" || echo "(no output: exit $?)"
}

run demo-raster "GLRT_MODE=raster"
run demo-pathtrace "GLRT_MODE=pathtrace"
run demo-pathtrace-spp4 "GLRT_MODE=pathtrace GLRT_SPP=4"
run demo-pathtrace-bounces0 "GLRT_MODE=pathtrace GLRT_BOUNCES=0"
run demo-pathtrace-bounces4 "GLRT_MODE=pathtrace GLRT_BOUNCES=4"
run rebatch-raster "GLRT_MODE=raster" --rebatch --detail 11
run rebatch-pathtrace "GLRT_MODE=pathtrace" --rebatch --detail 11
