#!/usr/bin/env bash
# Installs the system packages glrt's demo and tests need, only those that are missing.
# Runs `apt-get update` first only when something has to be installed.
# Usage: bash scripts/setup.sh   (as root, or with sudo available)
set -euo pipefail

# package -> a file it installs (checked instead of dpkg, which may lie in containers)
declare -A PROBES=(
    [xvfb]=/usr/bin/Xvfb
    [x11-utils]=/usr/bin/xwininfo
    [x11-apps]=/usr/bin/xwd
    # glxinfo and glxgears (mesa-utils depends on mesa-utils-bin)
    [mesa-utils]=/usr/bin/glxinfo
    [mesa-vulkan-drivers]=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
    [libvulkan1]=/usr/lib/x86_64-linux-gnu/libvulkan.so.1
    [vulkan-tools]=/usr/bin/vulkaninfo
    [glslang-tools]=/usr/bin/glslangValidator
    [libgl1-mesa-dri]=/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so
    [libgl1]=/usr/lib/x86_64-linux-gnu/libGL.so.1
    [xauth]=/usr/bin/xauth
    # the C++ compiler nv-flip-sys builds NVIDIA's FLIP with (a test dependency)
    [g++]=/usr/bin/g++
)

missing=()
for pkg in "${!PROBES[@]}"; do
    [[ -e "${PROBES[$pkg]}" ]] || missing+=("$pkg")
done

if ((${#missing[@]} == 0)); then
    echo "setup: all system packages present"
    exit 0
fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    SUDO="sudo"
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get -o DPkg::Lock::Timeout=900 update -qq
$SUDO apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends "${missing[@]}"
