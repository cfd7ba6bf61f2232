#!/usr/bin/env bash
# On the GPU machine: run the raster test binary with 4 test threads until it hangs, then dump stacks.
source "$(dirname "$0")/gpu_driver.sh"
mkdir -p /tmp/eu; for f in .dbg/*.deb; do dpkg -x $f /tmp/eu; done
export LD_LIBRARY_PATH=/tmp/eu/usr/lib/x86_64-linux-gnu
xz -dc .dbg/raster.xz > /tmp/raster; chmod +x /tmp/raster
for i in 1 2 3 4 5 6 7 8; do
  /tmp/raster --test-threads 4 > /tmp/l 2>&1 & p=$!
  for s in $(seq 60); do sleep 1; kill -0 $p 2>/dev/null || break; done
  if kill -0 $p 2>/dev/null; then
    echo "run $i: hung"; /tmp/eu/usr/bin/eu-stack -p $p > $OUT/stacks-$i.txt 2>&1
    grep -c "^TID" $OUT/stacks-$i.txt; kill -9 $p
  else echo "run $i done: $(grep 'test result' /tmp/l | cut -c1-50)"; fi
done
xz -dc .dbg/rit.xz > /tmp/rit; chmod +x /tmp/rit; fails=0
for i in $(seq 20); do timeout 100 /tmp/rit -q > /tmp/r.$i 2>&1 || { fails=$((fails+1)); tail -5 /tmp/r.$i; }; done
echo "renderers_in_threads: 20 runs, $fails failed"; grep -h "device\|NVIDIA" /tmp/r.1 | head -2
