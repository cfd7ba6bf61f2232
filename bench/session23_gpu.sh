#!/usr/bin/env bash
# Session 23's runs on the GPU machine (logs bench/session23-h200-*.log). Run by the device tool
# from the repo root, carrying .gl and .dev, where .dev/NAME/*.xz hold xz-compressed stripped
# release builds (glrt, glrt-demo, libglrt.so) of the builds compared (base23 = main 997be7e,
# new, and others named by the sections), and .dev/openarena-1280x720-f340-440.glrtcap.xz the
# OpenArena capture (scripts/openarena.sh capture 1280x720 340..440).
#   OUT=DIR bash bench/session23_gpu.sh SECTION...
set -uo pipefail
source "$(dirname "$0")/gpu_driver.sh"
OUT=${OUT:-/tmp/out}
source "$(dirname "$0")/gpu_builds.sh"
for section in "$@"; do
case $section in
regions) # the compute tracer over merged regions (h21-compute)
  bash bench/compute_regions_gpu.sh /tmp/new $OUT/regions trace parity ;;
oa) # CPU per frame of the OpenArena capture, base23 against new, two rounds
  for r in 1 2; do for b in base23 new; do for m in raster pathtrace; do echo "== r$r $b oa $m"; GLRT_TRACER=hardware GLRT_MODE=$m timeout 200 /tmp/$b/glrt replay /tmp/oa.glrtcap --frames 340..440 --bench 2>&1 | tail -3; done; done; done ;;
trace) # both tracers, demo and q3, base23 against $NEW (default new); the compute tracer of
  # $NEW also without merged regions (GLRT_CHUNK_REGIONS=0: base23's compute structure)
  n=${NEW:-new}
  for r in 1 2; do for b in base23 $n; do for t in compute hardware; do
    demo $b "r$r $t demo" "GLRT_TRACER=$t" --frames 200
    demo $b "r$r $t q3" "GLRT_TRACER=$t" --q3 --frames 200
  done; done
  demo $n "r$r compute demo regions0" "GLRT_TRACER=compute GLRT_CHUNK_REGIONS=0" --frames 200; done ;;
denoise) # the denoiser's passes at 1080p, base23 against $NEW
  for b in base23 ${NEW:-new}; do echo "=== $b"; SIZES=1920x1080 TRACERS=compute bash bench/denoise_gpu.sh /tmp/$b 200; done ;;
esac
done
