#!/usr/bin/env bash
# Overhead of the call log (GLRT_TRACE) and of the capture (GLRT_CAPTURE): frames per second of
# `glrt-demo --headless` through glrt's libGL.so.1 with each off and on, in the same run (the
# modes alternate, ROUNDS times, so that load from other jobs spreads over all of them), and
# the bytes each writes per frame. Prints a Markdown table (bench/overhead.md keeps results).
#   bash bench/overhead.sh [FRAMES] [ROUNDS]        (default 300 frames, 3 rounds)
# Environment: BENCH_PROFILE=release|debug (default release).
# The capture rows appear when the library supports GLRT_CAPTURE: a probe run with it set must
# leave a non-empty file.
set -euo pipefail
cd "$(dirname "$0")/.."

frames=${1:-300}
rounds=${2:-3}
profile=${BENCH_PROFILE:-release}

if [[ $profile == release ]]; then cargo build --release; else cargo build; fi
dir="$PWD/target/$profile"
ln -sf libglrt.so "$dir/libGL.so.1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Runs the demo with the given VAR=value settings; prints its average frame time in ms.
demo() {
    env -u GLRT_TRACE -u GLRT_TRACE_FILTER -u GLRT_CAPTURE -u GLRT_CAPTURE_FRAMES -u GLRT_PASSTHROUGH \
        LD_LIBRARY_PATH="$dir" "$@" "$dir/glrt-demo" --headless --frames "$frames" |
        sed -n 's/.*frame time ms: avg \([0-9.]*\).*/\1/p'
}

modes=(off trace)
declare -A settings=([off]="" [trace]="GLRT_TRACE=$tmp/trace.log" [capture]="GLRT_CAPTURE=$tmp/capture.bin")
declare -A output=([trace]="$tmp/trace.log" [capture]="$tmp/capture.bin")
demo GLRT_CAPTURE="$tmp/probe.bin" >/dev/null
if [[ -s $tmp/probe.bin ]]; then
    modes+=(capture)
else
    echo "overhead.sh: GLRT_CAPTURE left no file: this library has no capture; its rows are left out" >&2
fi

declare -A times=()
for ((round = 1; round <= rounds; round++)); do
    for mode in "${modes[@]}"; do
        # shellcheck disable=SC2086 # settings hold zero or one VAR=value word
        ms=$(demo ${settings[$mode]})
        times[$mode]+="$ms "
    done
done

echo "glrt-demo --headless --frames $frames, $profile build, $rounds rounds, $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| mode | average frame time per run (ms) | frames/s (mean) | bytes per frame |"
echo "|------|---------------------------------|-----------------|-----------------|"
for mode in "${modes[@]}"; do
    bytes="-"
    if [[ -n ${output[$mode]:-} ]]; then
        bytes=$(($(stat -c %s "${output[$mode]}") / frames))
    fi
    label=$mode
    [[ $mode == off ]] || label="$mode on"
    awk -v label="$label" -v t="${times[$mode]}" -v bytes="$bytes" 'BEGIN {
        n = split(t, v, " "); sum = 0; list = ""
        for (i = 1; i <= n; i++) { sum += v[i]; list = list (i > 1 ? ", " : "") v[i] }
        printf "| %s | %s | %.0f | %s |\n", label, list, 1000 * n / sum, bytes
    }'
done
