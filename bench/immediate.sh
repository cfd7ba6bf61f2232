#!/usr/bin/env bash
# Immediate-mode throughput (issue 17): frames of 100,000 and of 10 million vertices
# (glColor3f + glTexCoord2f + glVertex3f each, GL_TRIANGLES, 3000 vertices per glBegin/glEnd,
# glFinish + swap at the end of each frame), not culled and culled (every triangle back-facing,
# GL_CULL_FACE on), best of 3 frames each, through Mesa's libGL.so.1 (llvmpipe, in a GLX
# window under Xvfb) and glrt's (GLRT_MODE=raster, in a GLX window under Xvfb and headless),
# all in one run; prints vertices per second and glrt / Mesa for each case.
#   bash bench/immediate.sh [VERTICES...]        (default: 100000 10000000)
# Environment: BENCH_PROFILE=release|debug (default release), MESA_LIBGL (default the system
# libGL.so.1), SIZE (window size, default 64x64), FRAMES (default 3), GLRT_MODE (default raster).
set -euo pipefail
cd "$(dirname "$0")/.."

(($# > 0)) || set -- 100000 10000000
profile=${BENCH_PROFILE:-release}
mesa=${MESA_LIBGL:-/usr/lib/x86_64-linux-gnu/libGL.so.1}
size=${SIZE:-64x64}
frames=${FRAMES:-3}
export GLRT_MODE=${GLRT_MODE:-raster}

if [[ $profile == release ]]; then cargo build --release --bin glrt-demo; else cargo build --bin glrt-demo; fi
dir="$PWD/target/$profile"
ln -sf libglrt.so "$dir/libGL.so.1"
demo="$dir/glrt-demo"

# Vertices per second of the best frame of one run: $1 = glx or headless, then the demo's flags.
rate() {
    local how=$1 out
    shift
    if [[ $how == glx ]]; then
        out=$(xvfb-run -a -s "-screen 0 1024x768x24" "$demo" --size "$size" --frames "$frames" "$@")
    else
        out=$("$demo" --headless --size "$size" --frames "$frames" "$@")
    fi
    grep -o 'best of .* vertices/s' <<<"$out" | grep -o '[0-9.]* vertices/s$' | cut -d' ' -f1
}

echo "# Immediate mode, $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) CPUs, load $(cut -d' ' -f1 /proc/loadavg)," \
    "commit $(git rev-parse --short HEAD), $profile build, window $size, best of $frames frames, GLRT_MODE=$GLRT_MODE"
printf '%-12s %-6s %14s %16s %16s %9s %13s\n' vertices culled "Mesa GLX v/s" "glrt GLX v/s" "glrt headless v/s" "GLX ratio" "headless ratio"
for vertices in "$@"; do
    for cull in no yes; do
        flags=(--bench-immediate "$vertices")
        [[ $cull == yes ]] && flags+=(--cull)
        m=$(rate glx --lib "$mesa" "${flags[@]}")
        g=$(rate glx --lib "$dir/libGL.so.1" "${flags[@]}")
        h=$(rate headless --lib "$dir/libGL.so.1" "${flags[@]}")
        awk -v n="$vertices" -v c="$cull" -v m="$m" -v g="$g" -v h="$h" \
            'BEGIN { printf "%-12s %-6s %14.3e %16.3e %16.3e %8.2fx %12.2fx\n", n, c, m, g, h, g / m, h / m }'
    done
done
