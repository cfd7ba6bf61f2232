#!/usr/bin/env bash
# Session 22's runs on the GPU machine (logs bench/session22-h200-{a,b,c}.log; bench/pathtrace.md,
# denoise.md, radiosity.md, cpu_frame_gpu.md quote them). Run by the device tool from the repo
# root, carrying .gl and .dev, where .dev/NAME/*.xz hold xz-compressed stripped release builds
# (glrt, glrt-demo, libglrt.so) of the builds compared: base, new, h21only, and
# .dev/openarena-1280x720-f340-440.glrtcap.xz the OpenArena capture (scripts/openarena.sh capture).
#   bash bench/session22_gpu.sh SECTION...   (warm trace regions auto bisect oa2 denoise radiosity pre32k)
set -uo pipefail
source "$(dirname "$0")/gpu_driver.sh"
source "$(dirname "$0")/gpu_builds.sh"
for section in "$@"; do
case $section in
warm) # first runs: shader compiles with an empty cache
  for b in base new; do for t in compute hardware; do s=$(date +%s.%N); demo $b "warm-$t" "GLRT_TRACER=$t" --frames 2 >/dev/null; e=$(date +%s.%N); python3 -c "print('$b $t first run s', round($e-$s,1))"; done; done ;;
trace) # base against new, both tracers, three scenes
  for r in 1 2; do for b in base new; do for t in compute hardware; do
    demo $b "r$r $t demo" "GLRT_TRACER=$t" --frames 200
    demo $b "r$r $t q3" "GLRT_TRACER=$t" --q3 --frames 200
  done; done; done
  for b in base new; do for t in compute hardware; do demo $b "$t 1M" "GLRT_TRACER=$t" --rebatch --detail 11 --frames 100; done; done ;;
regions)
  for g in 0 1 2 4 8; do demo new "hardware demo regions$g" "GLRT_TRACER=hardware GLRT_CHUNK_REGIONS=$g" --frames 200; done
  for g in 0 2 4; do demo new "hardware 1M regions$g" "GLRT_TRACER=hardware GLRT_CHUNK_REGIONS=$g" --rebatch --detail 11 --frames 100; done
  mkdir -p $OUT/img
  for g in 0 2; do timeout 120 "${clean[@]}" LD_LIBRARY_PATH=/tmp/new GLRT_TRACER=hardware GLRT_CHUNK_REGIONS=$g GLRT_SPP=16 GLRT_DENOISE=0 /tmp/new/glrt-demo --headless --size 1280x720 --first-frame 120 --frames 2 --screenshot /tmp/demo-120-r$g.png >/dev/null 2>&1; done
  timeout 120 "${clean[@]}" LD_LIBRARY_PATH=/tmp/new GLRT_TRACER=compute GLRT_SPP=16 GLRT_DENOISE=0 /tmp/new/glrt-demo --headless --size 1280x720 --first-frame 120 --frames 2 --screenshot /tmp/demo-120-c.png >/dev/null 2>&1
  python3 scripts/png_luma.py --diff /tmp/demo-120-r0.png /tmp/demo-120-r2.png
  python3 scripts/png_luma.py --diff /tmp/demo-120-c.png /tmp/demo-120-r2.png
  cp /tmp/demo-120-r2.png $OUT/img/ ;;
auto)
  for scene in demo q3; do a=(); [[ $scene == q3 ]] && a=(--q3)
    for run in trial remembered; do demo new "auto $scene $run" "XDG_CACHE_HOME=/tmp/cache-$scene" --frames 260 "${a[@]}"; done
    cat /tmp/cache-$scene/glrt/tracers; done
  XDG_CACHE_HOME=/tmp/cache-demo /tmp/new/glrt info 2>&1 | tail -15 ;;
bisect) # which merge slowed the compute tracer
  for r in 1 2; do for b in base h21only new; do demo $b "r$r compute demo" "GLRT_TRACER=compute" --frames 200; done; done
  for b in base h21only new; do demo $b "compute q3" "GLRT_TRACER=compute" --q3 --frames 200; done ;;
oa2)
  for r in 1 2; do for b in base new; do for m in raster pathtrace; do echo "== r$r $b oa $m"; GLRT_TRACER=hardware GLRT_MODE=$m timeout 200 /tmp/$b/glrt replay /tmp/oa.glrtcap --frames 340..440 --bench 2>&1 | tail -3; done; done; done ;;
denoise) bash bench/denoise_gpu.sh /tmp/new 200 ;;
radiosity) bash bench/radiosity19.sh /tmp/new "update order4k pre16k refuse64k" ;;
pre32k) bash bench/radiosity19.sh /tmp/new pre32k ;;
oa) # CPU per frame of the OpenArena capture
  for b in base new; do for m in raster pathtrace; do echo "== $b oa $m"; GLRT_TRACER=hardware GLRT_MODE=$m timeout 200 /tmp/$b/glrt replay /tmp/oa.glrtcap --frames 340..440 --bench 2>&1 | tail -3; done; done ;;
esac
done
