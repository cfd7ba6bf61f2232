#!/usr/bin/env bash
# Installs what is missing, builds glrt (debug), links target/debug/libGL.so.1 and runs every
# test. The integration tests that need an X server start their own Xvfb. With no arguments it
# then runs piglit's fast subset (scripts/piglit.sh --fast, installing piglit when missing) and
# compares each result with tests/piglit/expected.txt: a changed result fails the run and is
# printed as a diff. GLRT_PIGLIT=0 leaves piglit out.
#   bash scripts/test.sh [cargo test args...]
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
cargo build
ln -sf libglrt.so target/debug/libGL.so.1
cargo test --no-fail-fast "$@"
if (($# == 0)) && [[ ${GLRT_PIGLIT:-1} != 0 ]]; then
    bash scripts/piglit.sh --fast
fi
