#!/usr/bin/env bash
# Peak memory of the piglit tests that draw for a long time without swapping
# (`streaming-texture-leak`: 5000 textures of 4 MB, each drawn once; `gl-1.0-blend-func`:
# 27,500 blend states, each drawn and read back), through Mesa (llvmpipe, the system's libGL)
# and through glrt (lavapipe), each under `/usr/bin/time -v` in its own Xvfb. Prints one line
# per run: library, test, peak resident set, wall time, result. A run is stopped after
# PIGLIT_MEMORY_TIMEOUT seconds (default 600; `gl-1.0-blend-func` takes longer than that on
# Mesa too); its peak is then the peak so far.
#   bash bench/piglit_memory.sh [TEST ...]
# Environment: PIGLIT_BUILD=debug|release (glrt's build, default release),
# PIGLIT_MEMORY_TIMEOUT (seconds per run), GLRT_FRAME_BUDGET_MB (glrt's frame budget).
set -euo pipefail
cd "$(dirname "$0")/.."

tests=("$@")
((${#tests[@]})) || tests=(streaming-texture-leak gl-1.0-blend-func)
build=${PIGLIT_BUILD:-release}
limit=${PIGLIT_MEMORY_TIMEOUT:-600}
bin=/usr/lib/x86_64-linux-gnu/piglit/bin
[[ -x $bin/${tests[0]} ]] || bash scripts/piglit.sh --list >/dev/null
if [[ $build == release ]]; then cargo build --release -q; else cargo build -q; fi
ln -sf libglrt.so "target/$build/libGL.so.1"
out=$(mktemp -d)

# Runs test $2 with the libGL of directory $1 (empty: the system's) and prints its line.
run() {
    local lib=$1 test=$2 label=${1:+glrt}
    label=${label:-mesa}
    LD_LIBRARY_PATH="$lib" PIGLIT_PLATFORM=glx xvfb-run -a -s "-screen 0 1024x768x24" \
        /usr/bin/time -v -o "$out/$label-$test.time" timeout "$limit" "$bin/$test" -auto >"$out/$label-$test.out" 2>&1 || true
    local rss wall result
    rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$out/$label-$test.time")
    wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$out/$label-$test.time")
    result=$(sed -n 's/^PIGLIT: {"result": "\([a-z]*\)".*/\1/p' "$out/$label-$test.out" | tail -n 1)
    printf '%-5s %-24s peak %6d MB  wall %8s  %s\n' "$label" "$test" "$((rss / 1024))" "$wall" "${result:-stopped after ${limit} s}"
}
for test in "${tests[@]}"; do
    run "" "$test"
    run "$PWD/target/$build" "$test"
done
rm -rf "$out"
