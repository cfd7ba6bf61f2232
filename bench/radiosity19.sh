#!/usr/bin/env bash
# Issue 19 on the GPU machine (session 22): the precompute with the sketched reordering at 16k
# patches (stage times and peak memory, under the 10-minute limit), the orderings' errors at
# 4k (exact against sketched, patches as built and shuffled), the per-frame update at 16k
# with the direct light's BVH traversal work, and the largest precompute the budget allows.
#   bash bench/radiosity19.sh BIN_DIR [STEPS]
# BIN_DIR holds a release build's glrt (cargo build --release --bin glrt). STEPS picks among
# "update order4k pre16k pre16kexact pre32k refuse64k q3fixture oa4k oa8k oa16k" (all but
# pre16kexact and the q3/oa steps by default; session 23: the seed's table on a Quake-3 map,
# one step a command, each up to ~10 minutes; the OpenArena capture taken from
# $GLRT_OA_CAPTURE, default .dev/openarena-1280x720-f340-440.glrtcap.xz, carried with .dev). On
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
    q3fixture|oa4k|oa8k|oa16k)
        # The seed's table on a Quake-3 map's static world, lightmapped draws included
        # (--baked): memory, errors after 0/1/2 passes (seed and fitted log ranges), the CPU's
        # dense product against Jacobi and Gauss–Seidel gathering to convergence, then the
        # renderer's compressed update on the GPU under the last frame's lights. The budget
        # sets the patch count (n² · 24 bytes: 384 MiB ~ 4k, 1536 ~ 8k, 6144 ~ 16k); over 4,096
        # patches the report compresses with the sketched search only (the exact one is O(n³)).
        if [ $step = q3fixture ]; then
            capture=tests/fixtures/q3.glrtcap budget=6144
        else
            capture=$XDG_CACHE_HOME/oa.glrtcap
            [ -f "$capture" ] || xz -dc "${GLRT_OA_CAPTURE:-.dev/openarena-1280x720-f340-440.glrtcap.xz}" > "$capture" \
                || python3 -c 'import lzma, shutil, sys; shutil.copyfileobj(lzma.open(sys.argv[1]), open(sys.argv[2], "wb"))' "${GLRT_OA_CAPTURE:-.dev/openarena-1280x720-f340-440.glrtcap.xz}" "$capture"
            case $step in oa4k) budget=384 ;; oa8k) budget=1536 ;; *) budget=6144 ;; esac
        fi
        echo "== radiosity --baked $capture, budget $budget MiB"
        timed=$([ -x /usr/bin/time ] && echo "/usr/bin/time -v")  # peak memory where GNU time is installed
        GLRT_RADIOSITY_BUDGET_MB=$budget $timed timeout 590 "$bin/glrt" radiosity --baked "$capture" 2>&1 | grep -vE "% after|^\s+(Page|Volun|Invol|Swaps|File|Socket|Signals|Average|Exit|Minor|Major|Percent|System|User)"
        ;;
    esac
done
