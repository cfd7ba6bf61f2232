#!/usr/bin/env bash
# Frames per second of glrt's Vulkan raster back end against Mesa's llvmpipe (the system
# libGL.so.1) on this machine, as ratios (bench/raster.md keeps results):
# - glrt-demo: headless through glrt (off-screen, on the default Vulkan device: lavapipe here)
#   against the same demo on Mesa's libGL (`--lib`) in a window under Xvfb;
# - glxgears in an Xvfb window through glrt and through Mesa (glxgears' own FPS reports), and
#   FRAMES frames of glxgears captured through glrt, replayed headless with
#   `glrt replay --bench`, against glxgears itself on Mesa under Xvfb (its own FPS report,
#   over its first 5 seconds).
#   bash bench/raster.sh [FRAMES] [SIZE]     (default 300 frames, demo at 640x480)
# Release build (built here if needed). Needs Xvfb, glxgears (bash scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."

frames=${1:-300}
size=${2:-640x480}
mesa=/usr/lib/x86_64-linux-gnu/libGL.so.1
cargo build --release
dir="$PWD/target/release"
ln -sf libglrt.so "$dir/libGL.so.1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
xvfb() { xvfb-run -a -s "-screen 0 1280x1024x24" "$@"; }
# The environment without glrt settings and without LD_LIBRARY_PATH (a command prefix).
clean=(env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_CAPTURE_FRAMES -u GLRT_DUMP -u GLRT_PASSTHROUGH -u LD_LIBRARY_PATH GLRT_MODE=raster)
# frames/s from the demo's "frame time ms: avg X" line on standard input.
fps() { sed -n 's/.*frame time ms: avg \([0-9.]*\).*/\1/p' | awk '{ printf "%.1f", 1000 / $1 }'; }

demo_glrt=$("${clean[@]}" LD_LIBRARY_PATH="$dir" "$dir/glrt-demo" --headless --frames "$frames" --size "$size" | fps)
demo_mesa=$(xvfb "${clean[@]}" "$dir/glrt-demo" --lib "$mesa" --frames "$frames" --size "$size" | fps)

"${clean[@]}" GLRT_CAPTURE="$tmp/gears.glrtcap" GLRT_CAPTURE_FRAMES="0..$frames" LD_LIBRARY_PATH="$dir" \
    timeout 60 xvfb-run -a -s "-screen 0 640x480x24" glxgears >/dev/null 2>&1 || true
gears_glrt=$("$dir/glrt" replay "$tmp/gears.glrtcap" --bench | sed -n 's/.*frames\/s \([0-9.]*\).*/\1/p')
gears_frames=$("$dir/glrt" info "$tmp/gears.glrtcap" | sed -n 's/^frames: \([0-9]*\).*/\1/p')
# glxgears' own FPS report (its first, over 5 seconds) in an Xvfb window, through LIBDIR's libGL.
gears_live() { "${clean[@]}" ${1:+LD_LIBRARY_PATH="$1"} timeout 7 xvfb-run -a -s "-screen 0 640x480x24" glxgears 2>/dev/null |
    sed -n 's/.* frames in [0-9.]* seconds = \([0-9.]*\) FPS/\1/p' | head -n 1 || true; }
gears_live_glrt=$(gears_live "$dir")
gears_mesa=$(gears_live "")

echo "$(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg); glrt on $(GLRT_LOG=info "$dir/glrt" replay "$tmp/gears.glrtcap" --frames 0..1 2>&1 | sed -n 's/.*Vulkan device //p')"
echo
echo "| program | glrt frames/s | Mesa llvmpipe frames/s | glrt / Mesa |"
echo "|---------|---------------|------------------------|-------------|"
row() { awk -v n="$1" -v g="$2" -v m="$3" 'BEGIN { printf "| %s | %s | %s | %.2f |\n", n, g, m, (m > 0 ? g / m : 0) }'; }
row "glrt-demo $size, $frames frames (glrt headless, Mesa under Xvfb)" "$demo_glrt" "$demo_mesa"
row "glxgears 300x300 in an Xvfb window (each: glxgears' first FPS report)" "${gears_live_glrt:-0}" "${gears_mesa:-0}"
row "glxgears 300x300 ($gears_frames captured frames replayed headless; Mesa: glxgears' first FPS report)" "$gears_glrt" "${gears_mesa:-0}"
