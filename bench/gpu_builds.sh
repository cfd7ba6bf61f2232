# Sourced by the session GPU scripts (bench/session22_gpu.sh, session23_gpu.sh) after
# gpu_driver.sh, from the repo root on the GPU machine: unpacks every build carried in .dev
# (.dev/NAME/*.xz: xz-compressed stripped glrt, glrt-demo, libglrt.so) into /tmp/NAME with its
# libGL.so.1 link, and the OpenArena capture into /tmp/oa.glrtcap; defines `clean` (the
# environment of a timed run) and `demo` (one glrt-demo run at 1280x720, summarised on one line).
unpack() { local b=$1 d=/tmp/$1; [[ -x $d/glrt-demo ]] && return; mkdir -p $d; for f in .dev/$b/*.xz; do xz -dc $f > $d/$(basename $f .xz); done; chmod +x $d/*; ln -sf libglrt.so $d/libGL.so.1; }
for b in .dev/*/; do b=$(basename $b); compgen -G ".dev/$b/*.xz" >/dev/null && unpack $b; done
[[ -f /tmp/oa.glrtcap ]] || xz -dc .dev/openarena-1280x720-f340-440.glrtcap.xz > /tmp/oa.glrtcap
clean=(env -u GLRT_TRACE -u GLRT_CAPTURE -u GLRT_DUMP -u GLRT_PASSTHROUGH -u GLRT_MODE -u GLRT_TRACER GLRT_LOG=info GLRT_MODE=pathtrace)
summary() { grep -E "tracing pass|path tracer|instances|chose|error|panick|WARN|frame time" | tr '\n' ' '; echo; }
# demo BIN NAME "VARS" ARGS...: one glrt-demo run of build BIN at 1280x720, its summary on one line.
demo() { local b=$1 name=$2 vars=$3; shift 3; echo -n "$b $name: "; timeout 200 "${clean[@]}" LD_LIBRARY_PATH=/tmp/$b $vars /tmp/$b/glrt-demo --headless --size 1280x720 "$@" 2>&1 | summary; }
