#!/usr/bin/env bash
# Immediate-mode throughput: 10 million vertices (glColor3f + glTexCoord2f + glVertex3f each,
# GL_TRIANGLES, 3000 vertices per glBegin/glEnd, glFinish + swap at the end) through glrt's
# libGL.so.1 and through Mesa's (llvmpipe, GLX window under Xvfb), in the same run.
#   bash bench/immediate.sh [VERTICES]
# Environment: BENCH_PROFILE=release|debug (default release), MESA_LIBGL (default the system
# libGL.so.1), GLRT_BENCH_GLX=1 to run glrt in a GLX window too (default: headless context).
set -euo pipefail
cd "$(dirname "$0")/.."

vertices=${1:-10000000}
profile=${BENCH_PROFILE:-release}
mesa=${MESA_LIBGL:-/usr/lib/x86_64-linux-gnu/libGL.so.1}

bash scripts/setup.sh
if [[ $profile == release ]]; then cargo build --release; else cargo build; fi
dir="$PWD/target/$profile"
ln -sf libglrt.so "$dir/libGL.so.1"
demo="$dir/glrt-demo"

# One vertices/s figure from a run of the benchmark mode.
rate() { grep -o '[0-9.]* vertices/s' | cut -d' ' -f1; }

glrt_args=(--lib "$dir/libGL.so.1" --bench-immediate "$vertices")
if [[ ${GLRT_BENCH_GLX:-0} == 1 ]]; then
    glrt_out=$(xvfb-run -a -s "-screen 0 1024x768x24" "$demo" "${glrt_args[@]}")
else
    glrt_out=$("$demo" --headless "${glrt_args[@]}")
fi
mesa_out=$(xvfb-run -a -s "-screen 0 1024x768x24" "$demo" --lib "$mesa" --bench-immediate "$vertices")

echo "glrt: $glrt_out"
echo "mesa: $mesa_out"
glrt_rate=$(rate <<<"$glrt_out")
mesa_rate=$(rate <<<"$mesa_out")
awk -v g="$glrt_rate" -v m="$mesa_rate" 'BEGIN { printf "glrt/mesa vertices per second: %.2f\n", g / m }'
