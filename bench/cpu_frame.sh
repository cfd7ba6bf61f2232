#!/usr/bin/env bash
# CPU cost of real frames (issue 17): captures of Quake-3-class frames replayed headless, the
# time of each frame split into the replay's reader (decoding records), its memory writes,
# glrt's front end (translate: the GL calls), hash tracking (classify) and the rest of the frame
# end (the renderer's recording and submission; 0 with GLRT_MODE=none), and callgrind's
# instruction counts per frame, per vertex and per draw.
#
#   bash bench/cpu_frame.sh [CAPTURE A..B]...
#
# Default captures: the q3 fixture (tests/fixtures/q3.glrtcap, frames 1..4) and, when present,
# /work/captures/openarena-1280x720-f340-440.glrtcap.xz (frames 340..440; decompressed to
# $TMPDIR and deleted after). Environment: MODES (default "none raster": GLRT_MODE of the timed
# runs and of the callgrind pairs), CALLGRIND=0 to skip the instruction counts (a replay under
# callgrind takes minutes; raster pairs take tens of minutes at the capture's size, so
# CALLGRIND_SIZE, e.g. 64x64, replays them at another drawable size: the recording is the
# same, lavapipe shades fewer pixels),
# RUNS (default 3: timed runs per mode, the fastest kept), GLRT_BIN (a built `glrt` to measure
# instead of building target/release/glrt).
#
# Times are from `glrt replay --bench`: wall clock split by per-record timers (they add about
# 0.1 us per GL call), as noisy as the machine's load, and the replaying thread's CPU time
# (/proc/thread-self/schedstat) split in the same proportions. Instruction counts are exact:
# callgrind runs the replay to frame A and to frame B, and frames A..B cost the difference;
# per vertex and per draw divide it by the vertices and draws `glrt replay --stats` counts.
# The renderer's column (raster mode) is `Renderer::present`, less the pipelines it created
# (`Pipelines::get`: lavapipe compiles each new pipeline, a one-off cost of the first frames
# that use it); Mesa's shader cache is warmed by the timed runs first.
set -euo pipefail
cd "$(dirname "$0")/.."

modes=${MODES:-none raster}
runs=${RUNS:-3}
if (($# == 0)); then
    set -- tests/fixtures/q3.glrtcap 1..4
    oa=/work/captures/openarena-1280x720-f340-440.glrtcap.xz
    [[ -f $oa ]] && set -- "$@" "$oa" 340..440
fi

if [[ -n ${GLRT_BIN:-} ]]; then
    glrt=$(realpath "$GLRT_BIN")
else
    cargo build --release --bin glrt
    glrt=$PWD/target/release/glrt
fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Callgrind of a replay in mode $4 to frame $3 of capture $1 (frames from $2), in
# $scratch/cg-$3.out.
callgrind() {
    local size=()
    [[ $4 != none && -n ${CALLGRIND_SIZE:-} ]] && size=(--size "$CALLGRIND_SIZE")
    GLRT_MODE=$4 valgrind --tool=callgrind --callgrind-out-file="$scratch/cg-$3.out" \
        "$glrt" replay "$1" --frames "$2..$3" "${size[@]}" >/dev/null 2>&1
}

# Inclusive instructions of function $2 (its full name as callgrind_annotate prints it after
# "file:", or "PROGRAM TOTALS") in callgrind output $1. callgrind_annotate lists a function
# once per source file its code comes from (code inlined from other files is on lines
# "other-file:function", each a part of the function's cost), and when it runs in a directory
# holding the sources (this script runs in the repository) it lists the function's own file
# twice: "src/...:function [object]", a part of its cost, and "/abs/path/src/...:function",
# the whole inclusive cost. The whole cost is the largest of the function's lines (checked
# against `valgrind --tool=callgrind --toggle-collect=FUNCTION`, whose total is the function's
# inclusive cost: bench/cpu_frame.md); the first line, which this script took before, left
# out 20 % of `Records::next` and 68 % of `Shadow::write`. Every function is listed
# (--threshold=100: by default the last 1 % is left out, which in raster mode, where
# lavapipe's compiler dominates, is all of glrt's front end).
inclusive() {
    callgrind_annotate --inclusive=yes --threshold=100 --auto=no "$1" 2>/dev/null | awk -v name="$2" '
        # "1,234 (12.34%)  file:function [object]" or "1,234 (12.34%)  PROGRAM TOTALS"
        match($0, /^ *[0-9,]+ +\( *[0-9.]+%\)  /) {
            cost = $1
            gsub(",", "", cost)
            rest = substr($0, RLENGTH + 1)
            sub(/ \[[^]]*\]$/, "", rest)
            colon = index(rest, ":")
            if ((rest == name || (colon > 0 && substr(rest, colon + 1) == name)) && cost + 0 > most) most = cost + 0
        }
        END { printf "%.0f\n", most }'
}

# Instructions per frame of function $1 over frames $a..$b.
per_frame() {
    awk -v x="$(inclusive "$scratch/cg-$a.out" "$1")" -v y="$(inclusive "$scratch/cg-$b.out" "$1")" -v n="$((b - a))" \
        'BEGIN { printf "%.2f", (y - x) / n / 1e6 }'
}

echo "# glrt replay CPU per frame ($(date -u +%Y-%m-%d), $(nproc) CPUs, load $(cut -d' ' -f1 /proc/loadavg), commit $(git rev-parse --short HEAD))"
while (($# >= 2)); do
    capture=$1 range=$2
    shift 2
    if [[ $capture == *.xz ]]; then
        xz -dc "$capture" >"$scratch/capture.glrtcap"
        file=$scratch/capture.glrtcap
    else
        file=$capture
    fi
    a=${range%..*} b=${range#*..}
    echo
    echo "## $(basename "$capture"), frames $range"
    # Draws and vertices per frame of the measured frames, from the frame log.
    rm -f "$scratch/frames.jsonl"
    GLRT_MODE=none GLRT_FRAME_LOG=$scratch/frames.jsonl "$glrt" replay "$file" --frames "$range" >/dev/null 2>&1
    read -r draws vertices < <(awk -v a="$a" -F'[:,]' '$2 >= a { n++; d += $4; v += $6 } END { printf "%.1f %.1f\n", d / n, v / n }' "$scratch/frames.jsonl")
    echo "per frame: $draws draws, $vertices vertices"
    for mode in $modes; do
        best= best_total=
        for _ in $(seq "$runs"); do
            out=$(GLRT_MODE=$mode "$glrt" replay "$file" --frames "$range" --bench 2>/dev/null || true)
            total=$(grep -E '^(cpu )?ms per frame' <<<"$out" | tail -1 | grep -o 'glrt [0-9.]*' | cut -d' ' -f2)
            if [[ -z $best ]] || awk -v t="$total" -v b="$best_total" 'BEGIN { exit !(t < b) }'; then
                best=$out best_total=$total
            fi
        done
        echo "GLRT_MODE=$mode, fastest of $runs runs by glrt's CPU time:"
        grep -E '^(frames:|ms per frame|cpu ms per frame|reader:)' <<<"$best" | sed 's/^/    /'
    done
    for mode in $modes; do
        [[ ${CALLGRIND:-1} != 0 ]] || break
        callgrind "$file" "$a" "$a" "$mode"
        callgrind "$file" "$a" "$b" "$mode"
        translate=$(per_frame "glrt::replay::calls::call")
        classify=$(per_frame "glrt::translate::classify::Classifier::classify")
        pipelines=$(per_frame "glrt::render::raster::pipelines::Pipelines::get")
        renderer=$(awk -v r="$(per_frame "<glrt::render::frame::Renderer as glrt::frame::sink::FrameSink>::present")" \
            -v p="$pipelines" 'BEGIN { printf "%.2f", r - p }')
        echo "callgrind (GLRT_MODE=$mode), M instructions per frame:" \
            " reader $(per_frame "<glrt::replay::reader::Records as core::iter::traits::iterator::Iterator>::next")" \
            " memory $(per_frame "glrt::replay::shadow::Shadow::write")" \
            " translate $translate  classify $classify  renderer $renderer (+ $pipelines creating pipelines)"
        awk -v t="$translate" -v c="$classify" -v r="$renderer" -v d="$draws" -v v="$vertices" \
            'BEGIN { f = t + c + r; printf "  glrt (translate + classify + renderer) %.2f M: per draw %.0f, per vertex %.0f instructions\n", f, f * 1e6 / d, f * 1e6 / v }'
    done
    rm -f "$scratch/capture.glrtcap"
done
