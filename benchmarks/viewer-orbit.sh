#!/usr/bin/env bash
# The viewer orbiting a large scene (apps/lantern/view/ViewerLod.h): `lantern view FILE
# --stats` in a virtual X server (Xvfb), the mouse dragged across the window (an orbit) for
# SECONDS, then let go; the viewer prints, as it exits, the frames drawn while the camera moved
# (their median time and the level-of-detail bound it reached) and how long after the last
# move the settled, exact picture was done. FILE defaults to the 8.1 M-triangle grid of
# benchmarks/make-grid.py, written here.
# Usage: benchmarks/viewer-orbit.sh [FILE]   (LANTERN=path/to/lantern; WIDTH HEIGHT default
#        1280 720; SECONDS_MOVING default 6). Needs Xvfb and xdotool (Debian: xvfb, xdotool).
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
width=${WIDTH:-1280} height=${HEIGHT:-720} seconds=${SECONDS_MOVING:-6}
out=$(mktemp -d)
display=:$((90 + RANDOM % 100))
Xvfb "$display" -screen 0 "$((width + 64))x$((height + 64))x24" >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null || true; rm -rf "$out"' EXIT
export DISPLAY=$display
file=${1:-}
if [ -z "$file" ]; then
    python3 benchmarks/make-grid.py "$out/grid.gltf" --triangles 8.1e6
    file="$out/grid.gltf"
fi
"$lantern" view "$file" --width "$width" --height "$height" --stats --no-panel 2>"$out/stats.txt" &
viewer=$!
window=""
for _ in $(seq 1 300); do
    window=$(xdotool search --onlyvisible --name '^lantern view' 2>/dev/null | head -1) && [ -n "$window" ] && break
    sleep 0.2
done
[ -n "$window" ] || { echo "no viewer window"; kill $viewer; exit 1; }
sleep 3  # the first frames (pipelines, the levels of detail built on the first moving frame)
xdotool mousemove --window "$window" $((width / 3)) $((height / 2)) mousedown 1
steps=() # one xdotool process for the whole drag: 4 pixels every 20 ms, no gaps between calls
for _ in $(seq 1 $((seconds * 50))); do steps+=(mousemove_relative -- 4 0 sleep 0.02); done
xdotool "${steps[@]}" mouseup 1
sleep 3
xdotool key --window "$window" Escape
wait $viewer || true
grep -E "frame time|level of detail" "$out/stats.txt"
