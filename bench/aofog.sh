#!/usr/bin/env bash
# Cost and look of the height fog (seed 002; render::fog) and the ambient occlusion (seed 000;
# render::ao, raster mode only) of issue 23: frame times of the demo and the Quake-3-like demo
# without and with each effect (raster: none, fog, ao; path traced: none, fog) at 1280x720,
# 1920x1080 and 3840x2160 (seed 002 reports 210/206, 174/169 and 127/120 fps without/with fog
# for 600k triangles on a GTX 970); then before/after image pairs at 1280x720 (OUT_DIR/*.png,
# for bench/images/).
#   bash bench/aofog.sh BIN_DIR OUT_DIR [FRAMES]
# BIN_DIR holds a release build's libglrt.so and glrt-demo. On the GPU machine (run tool, from
# the repo root, carrying .gl as bench/games_gpu.sh does) the NVIDIA Vulkan driver is set up
# first. SIZES="WxH ..." and MODES="raster pathtrace" override what is timed. Each run logs at
# GLRT_LOG=info, so the occlusion's per-pass GPU times (timestamps, render::pass_times) print
# as "ambient occlusion: N frames timed; GPU ms per frame: depth copy …, kernel …, blur …,
# apply …, all …" (the fog has no pass of its own: it is evaluated in the draws' shaders).
set -uo pipefail
bin=$(cd "$1" && pwd)
out=$2
frames=${3:-300}
sizes=${SIZES:-1280x720 1920x1080 3840x2160}
modes=${MODES:-raster pathtrace}
mkdir -p "$out"
ln -sf libglrt.so "$bin/libGL.so.1"
source "$(dirname "$0")/gpu_driver.sh"
clean=(env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_DUMP -u GLRT_PASSTHROUGH -u GLRT_CONFIG GLRT_LOG=info LD_LIBRARY_PATH="$bin")
# The fog of each scene: the demo's room is y-up in metres-like units (the eye 2.2 above the
# floor), the Quake-3-like level z-up in Quake units (64 a metre); densities chosen by eye on
# lavapipe renders of the two image frames.
demo_fog="GLRT_FOG_DENSITY=0.05 GLRT_FOG_FALLOFF=0.5 GLRT_FOG_HEIGHT=0 GLRT_FOG_UP=[0,1,0] GLRT_FOG_COLOR=[0.62,0.66,0.72]"
q3_fog="GLRT_FOG_DENSITY=0.0006 GLRT_FOG_FALLOFF=0.004 GLRT_FOG_HEIGHT=0 GLRT_FOG_UP=[0,0,1] GLRT_FOG_COLOR=[0.62,0.66,0.72]"
# The occlusion radius of each scene, in its units.
demo_ao="GLRT_AO_RADIUS=0.6 GLRT_AO_BIAS=0.02"
q3_ao="GLRT_AO_RADIUS=24 GLRT_AO_BIAS=0.5"

# run NAME "VAR=VALUE ..." [demo args...]: one run of the demo; its frame-time line.
run() {
    local name=$1 settings=$2
    shift 2
    echo "== $name"
    # shellcheck disable=SC2086 # the settings are words on purpose
    "${clean[@]}" $settings "$bin/glrt-demo" --headless "$@" 2>&1 \
        | grep -E "frame time|frames timed|Vulkan device|error|panick|WARN" || echo "(no output: exit $?)"
}

# effects MODE: the effects timed in MODE (occlusion is raster mode's only).
effects() {
    if [[ $1 == raster ]]; then echo "none fog ao"; else echo "none fog"; fi
}

# settings SCENE EFFECT: the variables that turn EFFECT on for SCENE (demo or q3).
settings() {
    local fog=${1}_fog ao=${1}_ao
    case $2 in
        none) echo "GLRT_FOG=0 GLRT_AO=0" ;;
        fog) echo "GLRT_FOG=1 GLRT_AO=0 ${!fog}" ;;
        ao) echo "GLRT_FOG=0 GLRT_AO=1 ${!ao}" ;;
    esac
}

for mode in $modes; do
    for size in $sizes; do
        for effect in $(effects "$mode"); do
            run "demo $mode $size $effect" "GLRT_MODE=$mode $(settings demo "$effect")" --size "$size" --frames "$frames"
            run "q3 $mode $size $effect" "GLRT_MODE=$mode $(settings q3 "$effect")" --q3 --size "$size" --frames "$frames"
        done
    done
done
for mode in $modes; do
    for effect in $(effects "$mode"); do
        run "image demo-120-$mode-$effect" "GLRT_MODE=$mode $(settings demo "$effect")" --size 1280x720 --first-frame 120 --frames 2 --screenshot "$out/demo-120-$mode-$effect.png"
        run "image q3-300-$mode-$effect" "GLRT_MODE=$mode $(settings q3 "$effect")" --q3 --size 1280x720 --first-frame 300 --frames 2 --screenshot "$out/q3-300-$mode-$effect.png"
    done
done
ls -la "$out"
