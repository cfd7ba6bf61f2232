#!/usr/bin/env bash
# OpenArena (ioquake3 with Debian's `openarena` and `openarena-data`), run unchanged through
# glrt's libGL.so.1 (LD_LIBRARY_PATH) under a private Xvfb (xvfb-run -a), non-interactively:
# the benchmark demo that openarena-data ships (demos/demo088-test1.dm_71 in
# pak6-patch088.pk3, 3398 frames) played as a timedemo (`+timedemo 1 +demo demo088-test1`),
# with ioquake3's GL1 renderer (cl_renderer opengl1), a windowed custom size, no sound, no frame
# cap and no vsync. Every run gets a fresh home directory (no q3config.cfg carried over).
#
#   bash scripts/openarena.sh capture WxH A..B OUT.glrtcap.xz
#       GLRT_CAPTURE with GLRT_CAPTURE_FRAMES=A..B, with no renderer (GLRT_MODE=none: the calls
#       are the same), then compressed with xz -9; the game quits soon after frame B. Frames
#       count every swap from the start: frames 0-38 are the menu and the loading screen, the
#       demo's frame k is frame 38 + k (give or take one: the loading screen's length).
#   bash scripts/openarena.sh fps [WxH] [ROUNDS]                    (default 320x240, 2 rounds)
#       The timedemo's frames per second through glrt raster (lavapipe), glrt GLRT_MODE=none (no
#       renderer) and Mesa's own libGL.so.1 (llvmpipe), the three alternating ROUNDS times in
#       one run; prints a Markdown table: frames per second and CPU milliseconds per frame (user
#       + sys of the game, its libGL's threads and Xvfb, loading included; steadier than frames
#       per second on a shared machine), each with its ratio to Mesa.
#   bash scripts/openarena.sh frames WxH N DIR
#       GLRT_DUMP=DIR in raster mode: every frame as DIR/frame-NNNNN.png until the game quits,
#       N frames into the demo (about frame N + 38; the last two, in flight when the game exits
#       without destroying its context, are not written), and GLRT_FRAME_LOG=DIR/frames.jsonl.
#   bash scripts/openarena.sh run [VAR=value...] -- [ioquake3 arguments...]
#       The timedemo through glrt with the given environment and extra engine arguments (for
#       example `perf record` around it: OA_WRAP="perf record -e cpu-clock -o FILE").
#
# Environment: BENCH_PROFILE=release|debug (default release), MESA_LIBGL (default the system
# libGL.so.1), OA_DEMO (default demo088-test1), OA_WRAP (a command put before the engine),
# OA_KEEP_RAW=FILE (capture: also keep the uncompressed .glrtcap there), OA_SIZE (run: the
# window size, default 320x240).
set -euo pipefail
cd "$(dirname "$0")/.."

profile=${BENCH_PROFILE:-release}
mesa=${MESA_LIBGL:-/usr/lib/x86_64-linux-gnu/libGL.so.1}
demo=${OA_DEMO:-demo088-test1}
engine=/usr/lib/ioquake3/ioquake3

# Installs openarena (and its data, ioquake3) when missing, and the packages glrt needs.
install() {
    bash scripts/setup.sh
    [[ -x /usr/games/openarena && -x $engine ]] && return
    local sudo=""
    [[ $(id -u) -eq 0 ]] || sudo=sudo
    echo "openarena.sh: installing openarena"
    export DEBIAN_FRONTEND=noninteractive
    $sudo apt-get -o DPkg::Lock::Timeout=900 update -qq
    $sudo apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends openarena
}

build() {
    if [[ $profile == release ]]; then cargo build --release; else cargo build; fi
    ln -sf libglrt.so "target/$profile/libGL.so.1"
}

glrt_dir="$PWD/target/$profile"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# game WxH LIBDIR [VAR=value...] -- [engine arguments...]: the timedemo at WxH with LIBDIR first
# on the library path (empty: the system's), in a fresh home, under xvfb-run; its console on
# stdout. Arguments are those of Debian's /usr/games/openarena wrapper (standalone game,
# protocol 71 of the demo) plus the benchmark settings.
game() {
    local size=$1 libdir=$2
    shift 2
    local envs=()
    while (($#)) && [[ $1 != -- ]]; do envs+=("$1"); shift; done
    (($#)) && shift
    local home
    home=$(mktemp -d -p "$tmp" home.XXXX)
    local args=(
        +set com_basegame baseoa +set fs_basepath /usr/lib/openarena +set fs_homepath "$home"
        +set com_legacyprotocol 71 +set com_protocol 71 +set cl_motd 0 +set com_introplayed 1
        +set cl_renderer opengl1 +set r_mode -1 +set r_customwidth "${size%x*}"
        +set r_customheight "${size#*x}" +set r_fullscreen 0 +set r_swapInterval 0
        +set com_maxfps 0 +set s_initsound 0 +set in_nograb 1 +set nextdemo quit
        +set timedemo 1 +demo "$demo" "$@"
    )
    # shellcheck disable=SC2086 # OA_WRAP is a command line of several words
    env HOME="$home" ${libdir:+LD_LIBRARY_PATH="$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"} "${envs[@]}" \
        xvfb-run -a -s "-screen 0 ${size}x24 -nolisten tcp" ${OA_WRAP:-} "$engine" "${args[@]}" 2>&1
}

# The timedemo's frames per second from the console output on stdin ("N frames S seconds F fps").
fps_of() { sed -n 's/^\([0-9]*\) frames \([0-9.]*\) seconds \([0-9.]*\) fps.*/\3/p' | tail -n 1; }

# quit_after N: engine arguments that quit the game N frames after the demo started (its
# loading screen's frames are drawn within one engine frame). `wait N` holds the commands after
# it for N runs of the command buffer, which ioquake3 runs twice per engine frame.
quit_after() { echo "+wait $((2 * $1)) +quit"; }

capture() {
    local size=${1:?WxH} frames=${2:?A..B} out=${3:?OUT.glrtcap.xz}
    local raw="$tmp/openarena.glrtcap"
    # The game quits 50 frames after the last one captured (the loading screen takes about 40).
    game "$size" "$glrt_dir" GLRT_MODE=none GLRT_CAPTURE="$raw" GLRT_CAPTURE_FRAMES="$frames" -- \
        $(quit_after $((${frames#*..} + 10))) >"$tmp/console.log" ||
        { tail -n 30 "$tmp/console.log" >&2; exit 1; }
    grep ' fps ' "$tmp/console.log" || true
    [[ -s $raw ]] || { echo "openarena.sh: no capture written" >&2; exit 1; }
    [[ -z ${OA_KEEP_RAW:-} ]] || cp "$raw" "$OA_KEEP_RAW"
    "$glrt_dir/glrt" info "$raw" >"$tmp/info.txt"
    sed -n '1,3p' "$tmp/info.txt"
    xz -9 -T1 -c "$raw" >"$out"
    echo "openarena.sh: $out: $(stat -c %s "$out") bytes (raw $(stat -c %s "$raw"))"
}

fps() {
    local size=${1:-320x240} rounds=${2:-2}
    local modes=(glrt-raster glrt-none mesa)
    declare -A rates=() cpu=()
    local TIMEFORMAT='%U %S'
    for ((round = 1; round <= rounds; round++)); do
        for mode in "${modes[@]}"; do
            local out="$tmp/$mode-$round.log"
            # CPU seconds (user + sys) of everything the run started: the game, its libGL's
            # threads, Xvfb; loading included.
            case $mode in
            glrt-raster) { time game "$size" "$glrt_dir" GLRT_MODE=raster -- >"$out"; } 2>"$out.cpu" ;;
            glrt-none) { time game "$size" "$glrt_dir" GLRT_MODE=none -- >"$out"; } 2>"$out.cpu" ;;
            mesa) { time game "$size" "$(dirname "$mesa")" -- >"$out"; } 2>"$out.cpu" ;;
            esac
            local f frames ms
            f=$(fps_of <"$out")
            [[ -n $f ]] || { tail -n 30 "$out" >&2; echo "openarena.sh: $mode: no timedemo result" >&2; exit 1; }
            frames=$(sed -n 's/^\([0-9]*\) frames [0-9.]* seconds .*/\1/p' "$out" | tail -n 1)
            ms=$(awk -v f="$frames" '{ printf "%.1f", 1000 * ($1 + $2) / f }' "$out.cpu")
            echo "openarena.sh: round $round $mode: $f fps, $ms ms of CPU per frame" >&2
            rates[$mode]+="$f "
            cpu[$mode]+="$ms "
        done
    done
    echo "OpenArena timedemo $demo at $size, $profile build, $rounds rounds, $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"
    echo
    echo "| libGL | frames/s per run | mean | / Mesa | CPU ms per frame per run | mean | / Mesa |"
    echo "|-------|------------------|------|--------|--------------------------|------|--------|"
    for mode in "${modes[@]}"; do
        awk -v label="$mode" -v r="${rates[$mode]}" -v mr="${rates[mesa]}" -v c="${cpu[$mode]}" -v mc="${cpu[mesa]}" '
            function mean(t, v, n, i, s) { n = split(t, v, " "); s = 0; for (i = 1; i <= n; i++) s += v[i]; return s / n }
            function list(t, v, n, i, l) { n = split(t, v, " "); l = ""; for (i = 1; i <= n; i++) l = l (i > 1 ? ", " : "") v[i]; return l }
            BEGIN {
                printf "| %s | %s | %.1f | %.2fx | %s | %.1f | %.2fx |\n", label, list(r), mean(r), mean(r) / mean(mr),
                    list(c), mean(c), mean(c) / mean(mc)
            }'
    done
}

frames() {
    local size=${1:?WxH} count=${2:?N} dir=${3:?DIR}
    rm -rf "$dir" && mkdir -p "$dir"
    dir=$(cd "$dir" && pwd)
    game "$size" "$glrt_dir" GLRT_MODE=raster GLRT_DUMP="$dir" GLRT_FRAME_LOG="$dir/frames.jsonl" -- \
        $(quit_after "$count") >"$dir/console.log" || { tail -n 30 "$dir/console.log" >&2; exit 1; }
    echo "openarena.sh: $(find "$dir" -name 'frame-*.png' | wc -l) frames in $dir (console: $dir/console.log)"
}

command=${1:-}
case $command in
capture | fps | frames | run) shift ;;
*) sed -n '2,/^set /{/^#/p}' "$0" >&2; exit 2 ;;
esac
install >&2
build >&2
case $command in
capture) capture "$@" ;;
fps) fps "$@" ;;
frames) frames "$@" ;;
run)
    envs=()
    while (($#)) && [[ $1 != -- ]]; do envs+=("$1"); shift; done
    (($#)) && shift
    game "${OA_SIZE:-320x240}" "$glrt_dir" "${envs[@]}" -- "$@"
    ;;
esac
