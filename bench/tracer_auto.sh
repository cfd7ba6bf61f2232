#!/usr/bin/env bash
# What `tracer = "auto"` picks (issue 21 item 2, bench/pathtrace.md "A measured auto"): on a
# GPU with VK_KHR_ray_tracing_pipeline, for the demo, the Quake-3-like demo and the
# re-batched world at ~1M triangles, a first run with an empty cache (the trial: 90 frames of
# each back end, its log line "tracer = "auto" chose the ... tracer (... hardware X ms,
# compute Y ms)") and a second run with that cache (the remembered choice, no trial). Each
# scene gets its own cache directory: choices are remembered per device and program, and the
# three scenes are one program (glrt-demo). Then `glrt info` with the demo's cache.
#   bash bench/tracer_auto.sh BIN_DIR OUT_DIR [FRAMES] [SIZE]
# BIN_DIR holds a release build's libglrt.so, glrt-demo and glrt.
set -uo pipefail
bin=$(cd "$1" && pwd)
out=$(mkdir -p "$2" && cd "$2" && pwd)
frames=${3:-300}
size=${4:-1280x720}
ln -sf libglrt.so "$bin/libGL.so.1"
clean=(env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_DUMP -u GLRT_PASSTHROUGH -u GLRT_MODE -u GLRT_TRACER LD_LIBRARY_PATH="$bin" GLRT_LOG=info GLRT_MODE=pathtrace)

for scene in demo q3 rebatch; do
    case $scene in
        demo) args=() ;;
        q3) args=(--q3) ;;
        rebatch) args=(--rebatch --detail 11) ;;
    esac
    for run in trial remembered; do
        echo "== $scene-$run"
        "${clean[@]}" XDG_CACHE_HOME="$out/cache-$scene" "$bin/glrt-demo" --headless --size "$size" --frames "$frames" "${args[@]}" 2>&1 \
            | grep -E "frame time|path tracer|tracer|Vulkan device|error|panick|WARN" || echo "(no output: exit $?)"
    done
    cat "$out/cache-$scene/glrt/tracers"
done
if [[ -x $bin/glrt ]]; then
    "${clean[@]}" XDG_CACHE_HOME="$out/cache-demo" "$bin/glrt" info
fi
