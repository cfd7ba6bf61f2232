#!/usr/bin/env bash
# The two ray-tracing back ends side by side on a GPU with VK_KHR_ray_tracing_pipeline
# (bench/pathtrace.md keeps the results): for each of GLRT_TRACER=compute (with GLRT_BVH=wide
# and binary) and hardware, the
# demo and the Quake-3-like demo at SIZE, and the re-batched world at ~1M triangles
# (`--rebatch --detail 11`), each path traced for FRAMES frames: frame times and the tracer's
# summary (`GLRT_LOG=info`: rays per frame by kind, GPU time of the tracing pass, rays/s);
# then parity images, 64 samples per pixel of one frame from each back end (both draw the
# same random numbers per pixel and sample; glxgears too when BIN_DIR has the glrt command),
# compared afterwards with `python3 scripts/png_luma.py --diff A B`.
#   bash bench/tracers.sh BIN_DIR OUT_DIR [FRAMES] [SIZE] [regions]
# BIN_DIR holds a release build's libglrt.so and glrt-demo.
# With `regions` (issue 21 item 1, bench/pathtrace.md "Merged chunk regions"): instead, the
# hardware tracer with GLRT_CHUNK_REGIONS=0 (an instance per chunk, as before), 2 (the
# default), 4 and 8, then the compute tracer (its default regions; bench/compute_regions_gpu.sh
# sweeps them), on the three scenes, two rounds alternating (the
# summary gives instances, of chunks and in the top level, and the tracing pass's ms); then
# parity, 64-spp frames of the demo (120) and q3 (300) merged (2) and unmerged (0), to compare
# with `python3 scripts/png_luma.py --diff OUT/demo-120-regions0.png OUT/demo-120-regions2.png`.
set -uo pipefail
bin=$(cd "$1" && pwd)
out=$2
frames=${3:-300}
size=${4:-1280x720}
mode=${5:-all}
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

if [[ $mode == regions ]]; then
    for round in 1 2; do
        for regions in 0 2 4 8; do
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
    exit 0
fi

# The compute tracer over both BVH layouts (GLRT_BVH: wide nodes with quantised boxes, or
# default, or binary nodes), then the hardware tracer.
tracers=(compute-wide compute-binary hardware)
# settings TRACER: its variables.
settings() {
    if [[ $1 == compute-* ]]; then echo "GLRT_TRACER=compute GLRT_BVH=${1#compute-}"; else echo "GLRT_TRACER=$1"; fi
}
for tracer in "${tracers[@]}"; do
    run "demo-$tracer" "$(settings "$tracer")" --frames "$frames"
    run "q3-$tracer" "$(settings "$tracer")" --q3 --frames "$frames"
    run "rebatch-$tracer" "$(settings "$tracer")" --rebatch --detail 11 --frames "$frames"
done
for tracer in "${tracers[@]}"; do
    run "parity-demo-$tracer" "$(settings "$tracer") GLRT_SPP=64" --first-frame 120 --frames 2 --screenshot "$out/demo-120-$tracer.png"
    run "parity-q3-$tracer" "$(settings "$tracer") GLRT_SPP=64" --q3 --first-frame 300 --frames 2 --screenshot "$out/q3-300-$tracer.png"
done
# glxgears (the captured fixture, replayed by the glrt command when BIN_DIR has it), frame 2.
if [[ -x $bin/glrt ]]; then
    for tracer in "${tracers[@]}"; do
        echo "== parity-glxgears-$tracer"
        # shellcheck disable=SC2046 # the settings are words on purpose
        "${clean[@]}" $(settings "$tracer") GLRT_SPP=64 "$bin/glrt" replay tests/fixtures/glxgears.glrtcap --frames 2..3 --out "$out/glxgears-$tracer" 2>&1 \
            | grep -E "path tracer|error|WARN" || echo "(no output: exit $?)"
        mv "$out/glxgears-$tracer/frame-00002.png" "$out/glxgears-2-$tracer.png" && rmdir "$out/glxgears-$tracer"
    done
fi
ls -la "$out"
