#!/usr/bin/env bash
# Cost of the denoiser's passes (issue 20; render::denoise) with the specular channel
# (`GLRT_DENOISE_SPECULAR=1`, the default) and without it (`=0`: specular rides the diffuse
# channels): the demo path traced at 1 spp, 1920x1080 and 1280x720, each tracer, A-SVGF on.
# Each run logs at GLRT_LOG=info, so the denoiser's per-pass GPU times (timestamps,
# render::pass_times) print as "denoiser: N frames timed; GPU ms per frame: gradient …,
# temporal …, variance …, a-trous …, modulate …, all …", and the tracing pass's time too.
#   bash bench/denoise_gpu.sh BIN_DIR [FRAMES]
# BIN_DIR holds a release build's glrt-demo and libglrt.so (or libGL.so.1, as .dev does). On the GPU machine (run tool, from
# the repo root, carrying .gl; bench/gpu_driver.sh) the NVIDIA Vulkan driver is set up
# first. SIZES="WxH ..." and TRACERS="hardware compute" override what is timed.
set -uo pipefail
bin=$(cd "$1" && pwd)
frames=${2:-200}
sizes=${SIZES:-1920x1080 1280x720}
tracers=${TRACERS:-hardware compute}
# A BIN_DIR with libglrt.so (target/release) gets its libGL.so.1 link; .dev holds libGL.so.1.
if [[ -e "$bin/libglrt.so" ]]; then ln -sf libglrt.so "$bin/libGL.so.1"; fi
source "$(dirname "$0")/gpu_driver.sh"
clean=(env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_DUMP -u GLRT_PASSTHROUGH -u GLRT_CONFIG GLRT_LOG=info LD_LIBRARY_PATH="$bin")
for size in $sizes; do
    for tracer in $tracers; do
        for specular in 1 0; do
            echo "== demo $size $tracer specular channel $specular"
            "${clean[@]}" GLRT_MODE=pathtrace GLRT_TRACER="$tracer" GLRT_DENOISE=1 GLRT_DENOISE_SPECULAR=$specular \
                "$bin/glrt-demo" --headless --size "$size" --frames "$frames" 2>&1 \
                | grep -E "frame time|frames timed|tracing pass|Vulkan device|error|panick|WARN" || echo "(no output: exit $?)"
        done
    done
done
