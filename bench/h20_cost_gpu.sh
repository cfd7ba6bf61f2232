#!/usr/bin/env bash
# The specular channel's cost after branch h20-cost (issue 20; bench/denoise.md, "The specular
# channel's cost, again"): release builds of main before the branch (.dev/base) and of the
# branch (.dev/new), xz-compressed as bench/session22_gpu.sh takes them (glrt, glrt-demo,
# libglrt.so), on the GPU machine (run tool, from the repo root, carrying .gl and .dev).
#   bash bench/h20_cost_gpu.sh trace; bash bench/h20_cost_gpu.sh denoise   (two device commands)
# trace: the tracing pass, base against new, both tracers, demo and q3 (two rounds) and the
# 1M world (session22_gpu.sh's section). denoise: the denoiser's passes at 1920x1080, base and
# new with the channel on and off (bench/denoise_gpu.sh), and new with the à-trous loop left to
# the driver's compiler (GLRT_DENOISE_UNROLL=0) against unrolled (the default).
set -uo pipefail
cd "$(dirname "$0")/.."
bash bench/session22_gpu.sh > /dev/null 2>&1 # unpacks .dev/{base,new} into /tmp/{base,new}
for section in "$@"; do
case $section in
trace) bash bench/session22_gpu.sh trace ;;
denoise)
  for b in base new; do echo "=== $b"; SIZES=1920x1080 TRACERS=hardware bash bench/denoise_gpu.sh /tmp/$b 200; done
  echo "=== new, GLRT_DENOISE_UNROLL=0"; GLRT_DENOISE_UNROLL=0 SIZES=1920x1080 TRACERS=hardware bash bench/denoise_gpu.sh /tmp/new 200 ;;
esac
done
