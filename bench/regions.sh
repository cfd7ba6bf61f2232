#!/usr/bin/env bash
# Merged chunk regions of the hardware tracer (issue 21 item 1, bench/pathtrace.md "Merged
# chunk regions"): on a GPU with VK_KHR_ray_tracing_pipeline, the hardware tracer with
# GLRT_CHUNK_REGIONS=0 (a bottom level and an instance per chunk, as before), 1 (a region
# per world cell), 2 (the default: 2x2x2 cells) and 4, then the compute tracer for reference,
# on the demo, the Quake-3-like demo and the re-batched world at ~1M triangles
# (`--rebatch --detail 11`), FRAMES frames each at SIZE, two rounds alternating: the tracer's
# summary (`GLRT_LOG=info`: instances, of chunks and in the top level; tracing pass ms per
# frame; acceleration-structure GPU ms). Then parity: one frame at 64 samples per pixel,
# merged (2) and unmerged (0), of the demo (frame 120) and q3 (frame 300); compare with
# `python3 scripts/png_luma.py --diff OUT/demo-120-regions0.png OUT/demo-120-regions2.png`
# (the same random numbers per pixel and sample: identical up to float rounding of the
# driver's traversal order).
#   bash bench/regions.sh BIN_DIR OUT_DIR [FRAMES] [SIZE]
# BIN_DIR holds a release build's libglrt.so and glrt-demo.
set -uo pipefail
bin=$(cd "$1" && pwd)
out=$2
frames=${3:-300}
size=${4:-1280x720}
mkdir -p "$out"
ln -sf libglrt.so "$bin/libGL.so.1"
clean=(env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_DUMP -u GLRT_PASSTHROUGH -u GLRT_MODE LD_LIBRARY_PATH="$bin" GLRT_LOG=info GLRT_MODE=pathtrace)

# run NAME "VAR=VALUE ..." [demo args...]: one run; its frame-time and tracer lines.
run() {
    local name=$1 settings=$2
    shift 2
    echo "== $name ($settings; $size)"
    # shellcheck disable=SC2086 # the settings are words on purpose
    "${clean[@]}" $settings "$bin/glrt-demo" --headless --size "$size" "$@" 2>&1 \
        | grep -E "frame time|path tracer|tracer|rebatch:|Vulkan device|error|panick|WARN" || echo "(no output: exit $?)"
}

for round in 1 2; do
    for regions in 0 1 2 4; do
        s="GLRT_TRACER=hardware GLRT_CHUNK_REGIONS=$regions"
        run "r$round-demo-hardware-regions$regions" "$s" --frames "$frames"
        run "r$round-q3-hardware-regions$regions" "$s" --q3 --frames "$frames"
        run "r$round-rebatch-hardware-regions$regions" "$s" --rebatch --detail 11 --frames "$frames"
    done
    run "r$round-demo-compute" "GLRT_TRACER=compute" --frames "$frames"
    run "r$round-q3-compute" "GLRT_TRACER=compute" --q3 --frames "$frames"
    run "r$round-rebatch-compute" "GLRT_TRACER=compute" --rebatch --detail 11 --frames "$frames"
done
for regions in 0 2; do
    s="GLRT_TRACER=hardware GLRT_CHUNK_REGIONS=$regions GLRT_SPP=64"
    run "parity-demo-regions$regions" "$s" --first-frame 120 --frames 2 --screenshot "$out/demo-120-regions$regions.png"
    run "parity-q3-regions$regions" "$s" --q3 --first-frame 300 --frames 2 --screenshot "$out/q3-300-regions$regions.png"
done
ls -la "$out"
