#!/usr/bin/env bash
# GPU machine: CPU per frame of Quake-3-class captures (issue 17), raster / path traced frame times.
source "$(dirname "$0")/gpu_driver.sh"
nvidia-smi -L; nproc
d=.dev; xz -dkf $d/glrt.xz $d/libGL.so.1.xz; chmod +x $d/glrt $d/glrt-demo
xz -dc $d/openarena-1280x720-f340-440.glrtcap.xz > /tmp/oa.glrtcap
xz -dc $d/q3-1280x720.glrtcap.xz > /tmp/q3.glrtcap
for cap in "/tmp/oa.glrtcap 350..440" "/tmp/q3.glrtcap 20..120"; do
  set -- $cap
  for mode in none raster pathtrace; do
    echo "== $(basename $1) frames $2 GLRT_MODE=$mode"
    GLRT_MODE=$mode $d/glrt replay $1 --frames $2 --bench 2>&1 | tail -6
  done
done
for mode in raster pathtrace; do
  echo "== glrt-demo --q3 1280x720 480 frames GLRT_MODE=$mode"
  LD_LIBRARY_PATH=$PWD/$d GLRT_MODE=$mode $d/glrt-demo --q3 --headless --size 1280x720 --frames 480 2>&1 | tail -2
done
