#!/usr/bin/env bash
# Immediate-mode throughput (issue 17): frames of 100,000 and of 10 million vertices
# (glColor3f + glTexCoord2f + glVertex3f each, GL_TRIANGLES, 3000 vertices per glBegin/glEnd,
# glFinish + swap at the end of each frame), not culled and culled (GL_CULL_FACE on with
# glCullFace(GL_FRONT_AND_BACK): every triangle culled), the median of 4 frames after the first, through Mesa's
# libGL.so.1 (llvmpipe, in a GLX window under Xvfb) and glrt's (GLRT_MODE=raster, in a GLX
# window under Xvfb and headless), all in one run; prints vertices per second and glrt / Mesa
# for each case. Mesa has no headless context in glrt-demo (--headless is glrt's
# glrtCreateContext), so both glrt columns are divided by Mesa's GLX figure.
#   bash bench/immediate.sh [VERTICES...]        (default: 100000 10000000)
# Environment: BENCH_PROFILE=release|debug (default release), GLRT_DIR (a folder holding a
# built glrt-demo and libGL.so.1 to measure instead of building), MESA_LIBGL (default the
# system libGL.so.1), SIZE (window size, default 64x64), FRAMES (default 5), GLRT_MODE (default
# raster), CALLGRIND=1 to add callgrind's instructions per vertex (repeatable where wall times
# are not): the difference of 200,000- and 100,000-vertex single-frame runs / 100,000, glrt
# headless and Mesa in GLX, culled and not.
set -euo pipefail
cd "$(dirname "$0")/.."

(($# > 0)) || set -- 100000 10000000
profile=${BENCH_PROFILE:-release}
mesa=${MESA_LIBGL:-/usr/lib/x86_64-linux-gnu/libGL.so.1}
size=${SIZE:-64x64}
frames=${FRAMES:-5}
export GLRT_MODE=${GLRT_MODE:-raster}

if [[ -n ${GLRT_DIR:-} ]]; then
    dir=$(realpath "$GLRT_DIR")
else
    if [[ $profile == release ]]; then cargo build --release --lib --bin glrt-demo; else cargo build --lib --bin glrt-demo; fi
    dir="$PWD/target/$profile"
    ln -sf libglrt.so "$dir/libGL.so.1"
fi
demo="$dir/glrt-demo"
xvfb=(xvfb-run -a -s "-screen 0 1024x768x24")

# Vertices per second of the median frame after the first of one run: $1 = glx or headless, then the demo's flags.
rate() {
    local how=$1 out
    shift
    if [[ $how == glx ]]; then
        out=$("${xvfb[@]}" "$demo" --size "$size" --frames "$frames" "$@")
    else
        out=$("$demo" --headless --size "$size" --frames "$frames" "$@")
    fi
    grep -o 'median of .* vertices/s' <<<"$out" | grep -o '[0-9.]* vertices/s$' | cut -d' ' -f1
}

echo "# Immediate mode, $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) CPUs, load $(cut -d' ' -f1 /proc/loadavg)," \
    "commit $(git rev-parse --short HEAD), $profile build, window $size, median of $((frames - 1)) frames after the first, GLRT_MODE=$GLRT_MODE"
printf '%-12s %-6s %14s %16s %18s %10s %15s\n' vertices culled "Mesa GLX v/s" "glrt GLX v/s" "glrt headless v/s" "GLX ratio" "headless ratio"
for vertices in "$@"; do
    for cull in no yes; do
        flags=(--bench-immediate "$vertices")
        [[ $cull == yes ]] && flags+=(--cull)
        m=$(rate glx --lib "$mesa" "${flags[@]}")
        g=$(rate glx --lib "$dir/libGL.so.1" "${flags[@]}")
        h=$(rate headless --lib "$dir/libGL.so.1" "${flags[@]}")
        awk -v n="$vertices" -v c="$cull" -v m="$m" -v g="$g" -v h="$h" \
            'BEGIN { printf "%-12s %-6s %14.3e %16.3e %18.3e %9.2fx %14.2fx\n", n, c, m, g, h, g / m, h / m }'
    done
done

[[ ${CALLGRIND:-0} == 1 ]] || exit 0
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# Instructions of a single-frame run of $2 vertices ($3: --cull or nothing), $1 = glrt or mesa.
instructions() {
    local lib=$1 n=$2 cull=$3 run=()
    [[ $lib == mesa ]] && run=("${xvfb[@]}")
    local args=(--size "$size" --frames 1 --bench-immediate "$n" $cull)
    if [[ $lib == glrt ]]; then args+=(--headless --lib "$dir/libGL.so.1"); else args+=(--lib "$mesa"); fi
    "${run[@]}" valgrind --tool=callgrind --callgrind-out-file="$scratch/cg.out" "$demo" "${args[@]}" >/dev/null 2>&1
    callgrind_annotate "$scratch/cg.out" 2>/dev/null | grep -m1 'PROGRAM TOTALS' | awk '{ gsub(",", "", $1); print $1 }'
}
echo
echo "callgrind, instructions per vertex (whole process: (200,000-vertex frame - 100,000) / 100,000)"
printf "%-6s %14s %18s %22s\n" culled "Mesa GLX" "glrt headless" "glrt / Mesa (instr.)"
for cull in no yes; do
    flag=
    [[ $cull == yes ]] && flag=--cull
    m=$(awk -v a="$(instructions mesa 100000 "$flag")" -v b="$(instructions mesa 200000 "$flag")" 'BEGIN { print (b - a) / 100000 }')
    g=$(awk -v a="$(instructions glrt 100000 "$flag")" -v b="$(instructions glrt 200000 "$flag")" 'BEGIN { print (b - a) / 100000 }')
    awk -v c="$cull" -v m="$m" -v g="$g" 'BEGIN { printf "%-6s %14.1f %18.1f %21.2fx\n", c, m, g, g / m }'
done
