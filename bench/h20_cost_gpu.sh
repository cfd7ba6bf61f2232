#!/usr/bin/env bash
# Branch h20-cost's GPU runs (issue 20; bench/denoise.md, "The specular channel's cost,
# again"), on bench/session23_gpu.sh's set-up (.dev/base23 = main 997be7e, and this branch's
# stripped release build xz-compressed in .dev/h20cost, or NEW=NAME), from the repo root on the
# GPU machine (run tool, carrying .gl and .dev); two device commands:
#   bash bench/h20_cost_gpu.sh trace     # session23's trace section (demo, q3) and the 1M world
#   bash bench/h20_cost_gpu.sh denoise   # session23's denoise section
set -uo pipefail
cd "$(dirname "$0")/.."
n=${NEW:-h20cost}
for section in "$@"; do
case $section in
trace)
  NEW=$n bash bench/session23_gpu.sh trace
  # The 1M-triangle world (no lights: what the channel costs it is the megakernel's registers).
  source bench/gpu_driver.sh
  for b in base23 $n; do for t in compute hardware; do
    echo -n "$b $t 1M: "
    timeout 200 env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_DUMP -u GLRT_PASSTHROUGH GLRT_LOG=info GLRT_MODE=pathtrace GLRT_TRACER=$t LD_LIBRARY_PATH=/tmp/$b \
      /tmp/$b/glrt-demo --headless --size 1280x720 --rebatch --detail 11 --frames 100 2>&1 | grep -E "tracing pass|error|panick" | tr '\n' ' '; echo
  done; done ;;
denoise)
  NEW=$n bash bench/session23_gpu.sh denoise
  # (session 23 lease B also ran h20-cost's unrolled à-trous taps against the loop, chosen by
  # GLRT_DENOISE_UNROLL; the loop won and the variable is gone.)
  ;;
esac
done
