#!/usr/bin/env bash
# One PNG of a model at 1920x1080, whole process, Lantern against F3D (Debian's f3d, OpenGL
# through Mesa), interleaved: each round runs `lantern render` then `f3d --output`, and the
# script prints the median wall time and peak resident memory of each and their ratios (issue
# 18; docs/performance.md quotes it). One untimed run of each comes first, so the numbers are
# those of a second run (files in the page cache, Lantern's pipeline cache warm). F3D needs a
# display for its OpenGL context: one Xvfb is started for the whole run, outside the timing.
#
# Usage: benchmarks/peer-f3d.sh MODEL.gltf|.glb [ROUNDS=5] [LANTERN=build/release/apps/lantern/lantern]
set -euo pipefail
model=${1:?usage: $0 MODEL [ROUNDS] [LANTERN]}
rounds=${2:-5}
lantern=${3:-build/release/apps/lantern/lantern}
width=1920
height=1080

for tool in f3d Xvfb /usr/bin/time; do
    command -v "$tool" >/dev/null || { echo "peer-f3d: $tool is missing (apt-get install f3d xvfb time)" >&2; exit 2; }
done
[ -x "$lantern" ] || { echo "peer-f3d: no lantern at $lantern (scripts/build.sh release)" >&2; exit 2; }

out=$(mktemp -d)
trap 'kill "$xvfb" 2>/dev/null || true; rm -rf "$out"' EXIT
display=:$((90 + RANDOM % 100))
Xvfb "$display" -screen 0 "${width}x${height}x24" -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
sleep 1
export DISPLAY=$display

# measure NAME CMD...: runs CMD under /usr/bin/time, appends "seconds KiB" to $out/NAME.
measure() {
    local name=$1
    shift
    /usr/bin/time -f '%e %M' -o "$out/$name.one" "$@" >/dev/null 2>"$out/$name.err" ||
        { echo "peer-f3d: $name failed:" >&2; cat "$out/$name.err" >&2; exit 1; }
    cat "$out/$name.one" >>"$out/$name"
}
run_lantern() { measure "$1" "$lantern" render "$model" -o "$out/lantern.png" --width "$width" --height "$height"; }
run_f3d() { measure "$1" f3d "$model" --output="$out/f3d.png" --resolution="$width,$height"; }

run_lantern warmup-lantern
run_f3d warmup-f3d
for _ in $(seq "$rounds"); do
    run_lantern lantern
    run_f3d f3d
done

median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
lt=$(cut -d' ' -f1 "$out/lantern" | median)
lm=$(cut -d' ' -f2 "$out/lantern" | median)
ft=$(cut -d' ' -f1 "$out/f3d" | median)
fm=$(cut -d' ' -f2 "$out/f3d" | median)
echo "peer-f3d: $(basename "$model"), ${width}x${height} PNG, whole process, median of $rounds interleaved rounds (after one untimed run of each)"
echo
echo "| | wall time (s) | peak memory (MiB) |"
echo "|---|---|---|"
awk -v lt="$lt" -v lm="$lm" -v ft="$ft" -v fm="$fm" 'BEGIN {
    printf "| F3D %s | %.2f | %.0f |\n", "", ft, fm / 1024
    printf "| Lantern | %.2f | %.0f |\n", lt, lm / 1024
    printf "| Lantern / F3D | %.2f | %.2f |\n", lt / ft, lm / fm
}'
echo
echo "every run (seconds KiB): lantern: $(tr '\n' ';' <"$out/lantern") f3d: $(tr '\n' ';' <"$out/f3d")"
