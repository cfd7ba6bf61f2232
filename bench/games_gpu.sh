#!/usr/bin/env bash
# The raster/path-traced pairs of bench/games.md on the GPU machine (run tool, from the repo root;
# carry .gl (the Vulkan loader, see /work/.library/device) and .dev: stripped glrt, glrt-demo,
# libGL.so.1 (libglrt.so) from target/release, and openarena-1280x720-f340-440.glrtcap.xz made by
# scripts/openarena.sh capture 1280x720 340..440). Writes $OUT/TAG/*.png.
#   bash bench/games_gpu.sh TAG [BIN_DIR]   (BIN_DIR: glrt, glrt-demo and libGL.so.1; default .dev)
set -uo pipefail
tag=${1:-run}
bin=$(cd "${2:-.dev}" && pwd)
source "$(dirname "$0")/gpu_driver.sh"
nvidia-smi -L
o=$OUT/$tag; mkdir -p $o
xz -dc .dev/openarena-1280x720-f340-440.glrtcap.xz > /tmp/oa.glrtcap
for mode in none raster pathtrace; do
  echo "== openarena 1280x720 frames 350..440 GLRT_MODE=$mode"
  GLRT_MODE=$mode $bin/glrt replay /tmp/oa.glrtcap --frames 350..440 --bench 2>&1 | tail -3
done
for mode in raster pathtrace; do
  echo "== openarena frame 400 $mode spp 64 image"
  mkdir -p /tmp/oa-$mode
  GLRT_SPP=64 GLRT_MODE=$mode $bin/glrt replay /tmp/oa.glrtcap --frames 400..401 --out /tmp/oa-$mode 2>&1 | tail -2
  cp /tmp/oa-$mode/frame-00400.png $o/oa-400-$mode.png
done
for mode in raster pathtrace; do
  echo "== q3 demo 1280x720 480 frames GLRT_MODE=$mode"
  LD_LIBRARY_PATH=$bin GLRT_MODE=$mode $bin/glrt-demo --q3 --headless --size 1280x720 --frames 480 2>&1 | tail -4
  echo "== q3 frame 300 $mode spp 64"
  LD_LIBRARY_PATH=$bin GLRT_SPP=64 GLRT_MODE=$mode $bin/glrt-demo --q3 --headless --size 1280x720 --first-frame 300 --frames 2 --screenshot $o/q3-300-$mode.png 2>&1 | tail -2
done
ls -la $o
