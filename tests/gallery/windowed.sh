#!/usr/bin/env bash
# Starts the gallery in a window on a private Xvfb display, waits for its window, lets it render,
# sends Escape as a real X key event, and waits for it to quit. Prints the gallery's output.
# usage: windowed.sh GALLERY_EXE CACHE_DIR
set -u
exe=$1 cache=$2
command -v Xvfb >/dev/null && command -v xdotool >/dev/null || { echo "SKIP: Xvfb or xdotool missing"; exit 77; }

for n in $(seq 90 140); do [[ -e /tmp/.X11-unix/X$n || -e /tmp/.X$n-lock ]] || break; done
Xvfb ":$n" -screen 0 800x600x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; kill $app 2>/dev/null' EXIT
export DISPLAY=":$n"
for _ in $(seq 50); do xdotool getmouselocation >/dev/null 2>&1 && break; sleep 0.1; done

"$exe" --size 320x200 --tolerance 2 --cache "$cache" >"$cache/out.txt" 2>&1 &
app=$!
win=$(timeout 90 xdotool search --sync --name "spatter shooting gallery" | head -1)
[[ -n $win ]] || { echo "FAIL: no gallery window appeared"; cat "$cache/out.txt"; exit 1; }
# Wait for the first frame (proxies are built before it), then let a few more render.
for _ in $(seq 900); do grep -q "first frame shown" "$cache/out.txt" && break; sleep 0.1; done
grep -q "first frame shown" "$cache/out.txt" || { echo "FAIL: no frame was shown"; cat "$cache/out.txt"; exit 1; }
sleep 1
xdotool windowfocus --sync "$win" 2>/dev/null
xdotool key --window "$win" Escape
xdotool key Escape
for _ in $(seq 100); do kill -0 $app 2>/dev/null || break; sleep 0.1; done
if kill -0 $app 2>/dev/null; then echo "FAIL: the gallery did not quit on Escape"; exit 1; fi
wait $app
rc=$?
cat "$cache/out.txt"
exit $rc
