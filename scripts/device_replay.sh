#!/usr/bin/env bash
# Replays the demo capture (tests/fixtures/demo.glrtcap, 4 frames at 320x240) headless with
# `glrt replay --out`, writing its frames as PNG:
#   OUT_DIR/device/frame-NNNNN.png    on the default Vulkan device (GLRT_DEVICE picks another)
#   OUT_DIR/lavapipe/frame-NNNNN.png  on Mesa's lavapipe (VK_DRIVER_FILES set to its ICD), when
#                                     it is installed; skipped with a message otherwise
# and says which frames are byte-identical. The tolerance comparison is a test: copy
# OUT_DIR/device back and run
#   GLRT_DEVICE_FRAMES=OUT_DIR/device cargo test --test end_to_end -- --ignored device_frames
# Needs no Rust toolchain: only the glrt binary, built elsewhere.
#   bash scripts/device_replay.sh OUT_DIR [GLRT]   (GLRT default: target/release/glrt, else
#                                                   target/debug/glrt)
# On the GPU machine (run tool: carry target/release/glrt):
#   bash scripts/device_replay.sh "$OUT"
set -euo pipefail
cd "$(dirname "$0")/.."

out=${1:?usage: bash scripts/device_replay.sh OUT_DIR [GLRT]}
glrt=${2:-target/release/glrt}
[[ -x $glrt ]] || glrt=target/debug/glrt
[[ -x $glrt ]] || { echo "device_replay.sh: no glrt binary (build with cargo build --release)" >&2; exit 1; }
capture=tests/fixtures/demo.glrtcap

# replay NAME [VAR=value...]: the demo frames into OUT_DIR/NAME; GLRT_LOG=info names the device.
replay() {
    local name=$1
    shift
    rm -rf "${out:?}/$name"
    echo "== $name"
    env "$@" GLRT_LOG=info "$glrt" replay "$capture" --out "$out/$name"
}

replay device
lavapipe=$(ls /usr/share/vulkan/icd.d/lvp_icd.*.json 2>/dev/null | head -n 1 || true)
if [[ -z $lavapipe ]]; then
    echo "device_replay.sh: lavapipe is not installed here; compare $out/device with a lavapipe replay made elsewhere"
    exit 0
fi
replay lavapipe VK_DRIVER_FILES="$lavapipe" VK_ICD_FILENAMES="$lavapipe"
for png in "$out"/device/frame-*.png; do
    name=$(basename "$png")
    if cmp -s "$png" "$out/lavapipe/$name"; then echo "$name: identical"; else echo "$name: differs"; fi
done
