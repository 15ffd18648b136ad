#!/usr/bin/env bash
# Starts the gallery in a window on a private Xvfb display, waits for its window, lets it render,
# quick-saves (F5) and quick-loads (F9) the decals into CACHE_DIR/quick.save, rebuilds the proxies (R),
# sends Escape as a real X key event, and waits for it to quit. Prints the gallery's output.
# usage: windowed.sh GALLERY_EXE CACHE_DIR
set -u
exe=$1 cache=$2
command -v Xvfb >/dev/null && command -v xdotool >/dev/null || { echo "SKIP: Xvfb or xdotool missing"; exit 77; }

# Xvfb picks a free display itself (-displayfd) and writes its number once it accepts clients.
Xvfb -displayfd 3 -screen 0 800x600x24 -nolisten tcp 3>"$cache/display" >/dev/null 2>&1 &
xvfb=$! app=""
trap 'kill $xvfb 2>/dev/null; kill $app 2>/dev/null' EXIT
for _ in $(seq 300); do [[ -s $cache/display ]] && break; sleep 0.1; done
n=$(head -n 1 "$cache/display")
[[ -n $n ]] || { echo "FAIL: Xvfb did not start"; exit 1; }
export DISPLAY=":$n"

# LeakSanitizer off for the gallery in an ASan build: the X server's GL driver, which GLFW loads and
# unloads again, leaves a few small blocks behind, and their stacks end in the unloaded module.
ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 "$exe" --size 320x200 --tolerance 2 --cache "$cache" --save "$cache/quick.save" >"$cache/out.txt" 2>&1 &
app=$!
win=$(timeout 90 xdotool search --sync --name "spatter shooting gallery" | head -1)
[[ -n $win ]] || { echo "FAIL: no gallery window appeared"; cat "$cache/out.txt"; exit 1; }
# Wait for the first frame (proxies are built before it), then let a few more render.
for _ in $(seq 900); do grep -q "first frame shown" "$cache/out.txt" && break; sleep 0.1; done
grep -q "first frame shown" "$cache/out.txt" || { echo "FAIL: no frame was shown"; cat "$cache/out.txt"; exit 1; }
sleep 1
xdotool windowfocus --sync "$win" 2>/dev/null
xdotool key --window "$win" F5
for _ in $(seq 50); do grep -q "saved .* decals" "$cache/out.txt" && break; sleep 0.1; done
xdotool key --window "$win" F9
for _ in $(seq 50); do grep -q "loaded .* decals" "$cache/out.txt" && break; sleep 0.1; done
# R rebuilds the proxies on a thread of their own while the window keeps drawing.
xdotool key --window "$win" r
for _ in $(seq 600); do grep -q "proxies rebuilt" "$cache/out.txt" && break; sleep 0.1; done
xdotool key --window "$win" Escape
xdotool key Escape
for _ in $(seq 100); do kill -0 $app 2>/dev/null || break; sleep 0.1; done
if kill -0 $app 2>/dev/null; then echo "FAIL: the gallery did not quit on Escape"; exit 1; fi
wait $app
rc=$?
cat "$cache/out.txt"
exit $rc
