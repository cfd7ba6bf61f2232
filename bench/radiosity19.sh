#!/usr/bin/env bash
# Issue 19 on the GPU machine (session 22): the precompute with the sketched reordering at 16k
# patches (stage times and peak memory, under the 10-minute limit), the orderings' errors at
# 4k (exact against sketched, patches as built and shuffled), the per-frame update at 16k
# with the direct light's BVH traversal work, and the largest precompute the budget allows.
#   bash bench/radiosity19.sh BIN_DIR [STEPS]
# BIN_DIR holds a release build's glrt (cargo build --release --bin glrt). STEPS picks among
# "update order4k pre16k pre16kexact pre32k refuse64k" (all but pre16kexact by default). On
# the GPU machine (run tool, from the repo root, carrying .gl; bench/gpu_driver.sh) the NVIDIA
# Vulkan driver is set up first.
set -uo pipefail
bin=$(cd "$1" && pwd)
steps=${2:-update order4k pre16k pre32k refuse64k}
source "$(dirname "$0")/gpu_driver.sh"
export XDG_CACHE_HOME=$(mktemp -d)
for step in $steps; do
    case $step in
    update)
        # The per-frame update at 16,224 patches: direct light (all points first, then one
        # slice an update) and product, GPU timestamps, and the shadow rays' BVH work.
        for s in 1 4 16; do
            echo "== radiosity --synthetic 16384, $s slices"
            GLRT_RADIOSITY_DIRECT_SLICES=$s timeout 120 "$bin/glrt" radiosity --synthetic 16384
        done
        echo "== radiosity --synthetic 4096, 4 slices"
        timeout 120 "$bin/glrt" radiosity --synthetic 4096
        ;;
    order4k)
        # 4,056 patches: errors, bytes and time of no reordering, the exact search (1 and 2
        # passes) and the sketched ones, patches as built and shuffled (~1 minute).
        echo "== radiosity --precompute 4096 --orderings"
        GLRT_RADIOSITY_BUDGET_MB=1024 timeout 300 "$bin/glrt" radiosity --precompute 4096 --orderings
        ;;
    pre16k)
        # 16,224 patches with the default (sketched) reordering: every stage's time and the
        # peak memory after it (pre16kexact: the same with the seed's exact search, ~4 minutes).
        echo "== radiosity --precompute 16384 (sketched reordering)"
        GLRT_RADIOSITY_BUDGET_MB=8192 timeout 500 "$bin/glrt" radiosity --precompute 16384
        ;;
    pre16kexact)
        echo "== radiosity --precompute 16384 (exact reordering)"
        GLRT_RADIOSITY_REORDER=exact GLRT_RADIOSITY_BUDGET_MB=8192 timeout 500 "$bin/glrt" radiosity --precompute 16384
        ;;
    pre32k)
        # 31,974 patches (a box of side 73): the largest whose k-bounce channel (4.09 GB) fits
        # NVIDIA's 4 GiB storage-buffer range; dense matrices 23.4 GiB, about 50 GB of host
        # memory at the peak.
        echo "== radiosity --precompute 31974"
        GLRT_RADIOSITY_BUDGET_MB=24576 timeout 580 "$bin/glrt" radiosity --precompute 31974
        ;;
    refuse64k)
        # 64k patches need 100 GB of dense matrices: past the budget's 65,536 MiB ceiling and
        # the host's 128 GiB with the rest of the precompute; refused with the budget's message.
        echo "== radiosity --precompute 65536"
        GLRT_RADIOSITY_BUDGET_MB=65536 timeout 60 "$bin/glrt" radiosity --precompute 65536
        ;;
    esac
done
