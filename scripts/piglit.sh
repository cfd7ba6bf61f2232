#!/usr/bin/env bash
# Runs piglit's OpenGL 1.x tests (`spec@!opengl 1.0` ... `1.5` of the `opengl` profile, about
# 370 tests) through glrt's libGL.so.1 under Xvfb, prints pass/fail/skip/crash counts
# (of subtests, as `piglit summary console -s` does, and of whole tests), and compares each
# test's result with tests/piglit/expected.txt (scripts/piglit_compare.py: a diff of the tests
# whose result changed; exit status 1 when one did). Tests whose X connection Xvfb refused are
# run once more and their second result counts.
#   bash scripts/piglit.sh            run the tests
#   bash scripts/piglit.sh --fast     run only the fast subset, tests/piglit/fast.txt (a few
#                                     minutes on 2 cores with lavapipe; scripts/test.sh runs it)
#   bash scripts/piglit.sh --list     only list the selected tests (dry run)
# Environment: PIGLIT_FILTER (regex, default 'spec@!opengl 1\.'), PIGLIT_TIMEOUT (seconds per
# test, default 60), PIGLIT_TOTAL_TIMEOUT (seconds for the run, default 7200),
# PIGLIT_BUILD=debug|release (default debug), PIGLIT_LIBGL (a libGL.so.1 to test instead of
# glrt's, e.g. Mesa's, to compare; nothing is compared then).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
if ! command -v piglit >/dev/null; then
    echo "piglit.sh: installing piglit (about 2 GB)"
    SUDO=""; [[ $(id -u) -eq 0 ]] || SUDO=sudo
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends piglit \
        || { $SUDO apt-get -o DPkg::Lock::Timeout=900 update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends piglit; }
fi

build=${PIGLIT_BUILD:-debug}
if [[ -n ${PIGLIT_LIBGL:-} ]]; then
    libdir=$(mktemp -d)
    ln -s "$(realpath "$PIGLIT_LIBGL")" "$libdir/libGL.so.1"
    name=custom
else
    if [[ $build == release ]]; then cargo build --release; else cargo build; fi
    libdir="$PWD/target/$build"
    ln -sf libglrt.so "$libdir/libGL.so.1"
    name=glrt
fi

filter=${PIGLIT_FILTER:-'spec@!opengl 1\.'}
options=(-o -p glx --timeout "${PIGLIT_TIMEOUT:-60}")
expected="$PWD/tests/piglit/expected.txt"
compare=()
selection=()
selected="'$filter'"
if [[ ${1:-} == --fast ]]; then
    name="$name-fast"
    filter=.
    selected=tests/piglit/fast.txt
    selection=(--test-list "$PWD/tests/piglit/fast.txt")
    compare=(--ran-only)
fi
results="$PWD/target/piglit/$name"

if [[ ${1:-} == --list ]]; then
    piglit run opengl "$PWD/target/piglit/list" "${options[@]}" "${selection[@]}" -t "$filter" -d -l verbose \
        | sed -n 's/^dry-run: \(spec\/.*\)/\1/p' | sort -u | tee /dev/stderr | wc -l \
        | xargs -I{} echo "piglit.sh: {} tests match '$filter'"
    exit 0
fi

echo "piglit.sh: running $selected against $libdir/libGL.so.1; results in $results"
# Runs piglit into directory $1 on the tests matching regex $2, and, after it, further piglit
# options (a --test-list).
run_piglit() {
    local dir=$1 regex=$2
    shift 2
    LD_LIBRARY_PATH="$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
        timeout "${PIGLIT_TOTAL_TIMEOUT:-7200}" \
        xvfb-run -a -s "-screen 0 1024x768x24" piglit run opengl "$dir" "${options[@]}" -t "$regex" -l quiet "$@"
}
status=0
run_piglit "$results" "$filter" "${selection[@]}" || status=$?
if ((status == 124)); then
    echo "piglit.sh: stopped after PIGLIT_TOTAL_TIMEOUT; resuming only summarises what ran"
fi
# Under load Xvfb sometimes refuses a test's connection (`XOpenDisplay failed`): those tests
# did not run, so they are run again (up to three rounds, each only the tests refused in the
# round before) and the last result counts.
# Prints a regex matching the tests of results file $1 whose X connection was refused.
refused_tests() {
    python3 - "$1" <<'PY'
import bz2, json, re, sys
tests = json.load(bz2.open(sys.argv[1]))["tests"]
names = [n for n, t in tests.items() if "XOpenDisplay failed" in t.get("out", "") + t.get("err", "")]
print("^(" + "|".join(re.escape(n) for n in names) + ")$" if names else "")
PY
}
runs=("$results/results.json.bz2")
for round in 1 2 3; do
    refused=$(refused_tests "${runs[-1]}")
    [[ -n $refused ]] || break
    echo "piglit.sh: Xvfb refused some tests' connections; running them again (round $round): $refused"
    PIGLIT_TOTAL_TIMEOUT=1800 run_piglit "$results-refused-$round" "$refused" || true
    [[ -f $results-refused-$round/results.json.bz2 ]] || break
    runs+=("$results-refused-$round/results.json.bz2")
done
# Subtests count separately in the summary; the comparison counts whole tests.
piglit summary console -s "$results" | tail -n 12
if [[ -n ${PIGLIT_LIBGL:-} ]]; then
    python3 scripts/piglit_compare.py --counts "${runs[@]}"
else
    python3 scripts/piglit_compare.py "$expected" "${runs[@]}" "${compare[@]}"
fi
