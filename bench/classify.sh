#!/usr/bin/env bash
# Cost of hash tracking per frame (issue 5) on a Quake-3-like world of at least 100,000
# triangles per frame (bench/classify.md keeps results):
# 1. the persistent static world alone: bench/static_world (glrt's module file compiled
#    optimised on its own, no GL) offers the rebatch room at --detail DETAIL through a turn
#    of the camera and times begin_frame + offer + end_frame;
# 2. the whole pipeline: FRAMES frames of `glrt-demo --rebatch --detail DETAIL` captured
#    through glrt's libGL, replayed with `glrt replay --bench` (frame times without hash
#    tracking statistics) and `glrt replay --stats` (one JSON line per frame): its
#    `classify_ms` per frame, and `vertex_bytes / classify_ms` as GB/s of vertex data.
#   bash bench/classify.sh [DETAIL] [FRAMES]     (default 10 and 130: one turn and 10 frames;
#   about 1.7 MB of capture per frame at detail 10, kept under target/ while it runs)
# Release build (built here if needed); PROFILE=debug uses target/debug as it is (to check the
# script, not to measure).
set -euo pipefail
cd "$(dirname "$0")/.."

detail=${1:-10}
frames=${2:-130}
echo "$(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"

echo "## 1. Static world alone (detail $detail)"
(cd bench/static_world && CARGO_TARGET_DIR="$PWD/../../target/static-world-bench" cargo build --release --offline -q)
target/static-world-bench/release/static-world-bench "$detail" 360

echo "## 2. Capture replayed with --stats (detail $detail, $frames frames)"
profile=${PROFILE:-release}
[ "$profile" = release ] && cargo build --release -q
dir="$PWD/target/$profile"
ln -sf libglrt.so "$dir/libGL.so.1"
tmp=$(mktemp -d -p "$PWD/target")
trap 'rm -rf "$tmp"' EXIT
env -u GLRT_TRACE -u GLRT_CAPTURE_FRAMES -u GLRT_DUMP LD_LIBRARY_PATH="$dir" GLRT_CAPTURE="$tmp/rebatch.glrtcap" \
    "$dir/glrt-demo" --rebatch --verbose --detail "$detail" --headless --size 320x240 --frames "$frames" >"$tmp/demo.txt"
head -n 2 "$tmp/demo.txt" | tail -n 1
# Triangles drawn per frame (the demo's --verbose lines), and the vertex bytes they carry
# through the hashing (3 vertices × (12 bytes of position + 8 of texture coordinates)).
triangles=$(sed -n 's/^rebatch frame [0-9]*: [0-9]* surfaces, \([0-9]*\) triangles.*/\1/p' "$tmp/demo.txt" |
    awk '{ s += $1 } END { printf "%.0f", s / NR }')
echo "triangles drawn per frame: $triangles (capture $(du -h "$tmp/rebatch.glrtcap" | cut -f1))"
start=$(date +%s.%N); "$dir/glrt" replay "$tmp/rebatch.glrtcap" --bench >"$tmp/bench.txt"; end=$(date +%s.%N)
echo "replay --bench: $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }') s; $(tail -n 1 "$tmp/bench.txt")"
start=$(date +%s.%N); "$dir/glrt" replay "$tmp/rebatch.glrtcap" --stats >"$tmp/stats.jsonl"; end=$(date +%s.%N)
echo "replay --stats: $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }') s"
tail -n 1 "$tmp/stats.jsonl"
python3 - "$tmp/stats.jsonl" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.startswith("{")]
if not rows or "classify_ms" not in rows[0]:
    print("no classify_ms key in the --stats lines: compare the two replay times above")
    sys.exit()
ms = sorted(r["classify_ms"] for r in rows)
mean = sum(ms) / len(ms)
tris = sum(sum(r["triangles"].values()) for r in rows) / len(rows)
gbs = sum(r.get("vertex_bytes", 0) for r in rows) / (sum(ms) / 1000) / 1e9 if sum(ms) else 0
print(f"classify_ms per frame: mean {mean:.3f} median {ms[len(ms) // 2]:.3f} max {ms[-1]:.3f}; "
      f"{tris:.0f} triangles per frame; {gbs:.2f} GB/s of vertex data (vertex_bytes / classify_ms)")
PY
