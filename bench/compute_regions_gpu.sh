#!/usr/bin/env bash
# The compute tracer over merged chunk regions (issue 21 item 3; bench/pathtrace.md "The
# compute tracer on merged regions"), on the GPU machine: GLRT_CHUNK_REGIONS=0 (a BVH and a
# top-level instance per chunk, as before), 2 (the default) and 4, on the demo (200 frames),
# the q3 demo and the 1M-triangle world (`--rebatch --detail 11`, 100 frames), two rounds
# alternating; each run's summary line gives the instances (of chunks, in the top level),
# nodes and triangle tests per ray, rays per frame by kind and the tracing pass's GPU ms.
# Then the wide layout on the 1M world (regions 0 and 2), the hardware tracer at 2 for
# reference, and parity: 16-spp frames (denoiser off) of the demo (frame 120) and q3 (300),
# compute regions 0 against 2 and 4, and compute against hardware, with scripts/png_luma.py.
# Run from the repo root (the device tool carries .gl for gpu_driver.sh), a section or more
# per call (each fits the device tool's 10 minutes):
#   bash bench/compute_regions_gpu.sh BIN_DIR OUT_DIR SECTION...   (trace wide parity)
# BIN_DIR holds a release build's libglrt.so and glrt-demo (libGL.so.1 is linked to it).
set -uo pipefail
source "$(dirname "$0")/gpu_driver.sh"
bin=$(cd "$1" && pwd)
out=$2
shift 2
mkdir -p "$out"
ln -sf libglrt.so "$bin/libGL.so.1"
clean=(env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_DUMP -u GLRT_PASSTHROUGH -u GLRT_MODE -u GLRT_TRACER -u GLRT_CHUNK_REGIONS -u GLRT_BVH LD_LIBRARY_PATH="$bin" GLRT_LOG=info GLRT_MODE=pathtrace)
summary() { grep -E "path tracer|frame time|error|panick|WARN" | tr '\n' ' '; echo; }
# demo NAME "VARS" ARGS...: one glrt-demo run at 1280x720, its summary on one line.
demo() { local name=$1 vars=$2; shift 2; echo -n "$name: "; timeout 300 "${clean[@]}" $vars "$bin/glrt-demo" --headless --size 1280x720 "$@" 2>&1 | summary; }
# image NAME "VARS" ARGS...: a 16-spp frame without the denoiser into OUT/NAME.png.
image() { local name=$1 vars=$2; shift 2; timeout 200 "${clean[@]}" $vars GLRT_SPP=16 GLRT_DENOISE=0 "$bin/glrt-demo" --headless --size 1280x720 "$@" --frames 2 --screenshot "$out/$name.png" >/dev/null 2>&1; }

# Warm the shader cache (first compile) so that no timed run pays it.
demo warm "GLRT_TRACER=compute" --frames 2 >/dev/null
for section in "$@"; do
case $section in
trace)
for round in 1 2; do
    for g in 0 2 4; do
        demo "r$round compute demo regions$g" "GLRT_TRACER=compute GLRT_CHUNK_REGIONS=$g" --frames 200
        demo "r$round compute q3 regions$g" "GLRT_TRACER=compute GLRT_CHUNK_REGIONS=$g" --q3 --frames 200
        demo "r$round compute 1M regions$g" "GLRT_TRACER=compute GLRT_CHUNK_REGIONS=$g" --rebatch --detail 11 --frames 100
    done
done
;;
wide)
for g in 0 2; do demo "compute wide 1M regions$g" "GLRT_TRACER=compute GLRT_BVH=wide GLRT_CHUNK_REGIONS=$g" --rebatch --detail 11 --frames 100; done
demo "hardware demo regions2" "GLRT_TRACER=hardware" --frames 200
demo "hardware 1M regions2" "GLRT_TRACER=hardware" --rebatch --detail 11 --frames 100

;;
parity)
for g in 0 2 4; do
    image "demo-120-compute-r$g" "GLRT_TRACER=compute GLRT_CHUNK_REGIONS=$g" --first-frame 120
    image "q3-300-compute-r$g" "GLRT_TRACER=compute GLRT_CHUNK_REGIONS=$g" --q3 --first-frame 300
done
image demo-120-hardware-r2 "GLRT_TRACER=hardware" --first-frame 120
for scene in demo-120 q3-300; do
    python3 scripts/png_luma.py --diff "$out/$scene-compute-r0.png" "$out/$scene-compute-r2.png"
    python3 scripts/png_luma.py --diff "$out/$scene-compute-r0.png" "$out/$scene-compute-r4.png"
done
python3 scripts/png_luma.py --diff "$out/demo-120-compute-r2.png" "$out/demo-120-hardware-r2.png"
ls -la "$out"
;;
esac
done
