#!/usr/bin/env bash
# Batch throughput (docs/sequences.md "Batches"): COUNT sample files x 4 views at
# 256x256 PNG, as one `lantern render` batch (one process, one device) against `lantern render`
# run once per image, and F3D run once per image where f3d and Xvfb exist (F3D has no batch
# mode: each image is a process). The files are the glTF samples of ../shared/assets repeated
# in a list file until there are COUNT of them ({index} keeps their outputs apart). The four
# views are the same for all: front, right, back and left (azimuth 0, 90, 180, 270 degrees).
# Prints renders per second for each.
#
# Usage: benchmarks/batch-throughput.sh [COUNT=100] [LANTERN=build/ci/apps/lantern/lantern]
#        [ASSETS=../shared/assets/gltf-samples] [PER_IMAGE_COUNT=COUNT]
set -euo pipefail
count=${1:-100}
lantern=$(realpath "${2:-build/ci/apps/lantern/lantern}")
assets=$(realpath "${3:-../shared/assets/gltf-samples}")
per_image=${4:-$count}  # the files run once per image (fewer: a shorter run, the same rate)
size=(--width 256 --height 256)

[ -x "$lantern" ] || { echo "batch-throughput: no lantern at $lantern" >&2; exit 2; }
out=$(mktemp -d)
trap 'kill "${xvfb:-}" 2>/dev/null || true; rm -rf "$out"' EXIT

# The samples that render (a sample Lantern refuses would count as a failure, not a render).
mapfile -t samples < <(find "$assets" \( -name '*.gltf' -o -name '*.glb' \) | sort)
good=()
for s in "${samples[@]}"; do
    "$lantern" render "$s" "${size[@]}" -o "$out/probe.png" >/dev/null 2>&1 && good+=("$s")
done
for ((i = 0; i < count; ++i)); do echo "${good[i % ${#good[@]}]}"; done >"$out/list.txt"
echo "batch-throughput: $count files (${#good[@]} distinct samples of $assets) x 4 views, 256x256 PNG"

now() { date +%s.%N; }
rate() { awk -v n="$1" -v a="$2" -v b="$3" 'BEGIN { printf "%d renders in %.1f s: %.2f renders/s\n", n, b - a, n / (b - a) }'; }

t0=$(now)
"$lantern" render --list "$out/list.txt" --allow-folder "$assets" --views front,right,back,left \
    "${size[@]}" -o "$out/batch/{index}_{scene}_{view}.png" >/dev/null 2>"$out/batch.err" ||
    { cat "$out/batch.err" >&2; exit 1; }
t1=$(now)
echo -n "lantern, one batch:        "; rate $((count * 4)) "$t0" "$t1"
grep '^lantern: batch: [0-9]' "$out/batch.err"

head -n "$per_image" "$out/list.txt" >"$out/per-image.txt"
t0=$(now)
i=0
while read -r s; do
    for v in front right back left; do
        "$lantern" render "$s" --view "$v" "${size[@]}" -o "$out/single/${i}_$v.png" >/dev/null 2>&1
    done
    i=$((i + 1))
done <"$out/per-image.txt"
t1=$(now)
echo -n "lantern, once per image:   "; rate $((per_image * 4)) "$t0" "$t1"

if command -v f3d >/dev/null && command -v Xvfb >/dev/null; then
    display=:$((90 + RANDOM % 100))
    Xvfb "$display" -screen 0 1024x768x24 -nolisten tcp >/dev/null 2>&1 &
    xvfb=$!
    sleep 1
    export DISPLAY=$display
    t0=$(now)
    i=0
    while read -r s; do
        for a in 0 90 180 270; do
            f3d "$s" --camera-azimuth-angle="$a" --resolution=256,256 --output="$out/f3d_${i}_$a.png" \
                >/dev/null 2>&1
        done
        i=$((i + 1))
    done <"$out/per-image.txt"
    t1=$(now)
    echo -n "f3d, once per image:       "; rate $((per_image * 4)) "$t0" "$t1"
else
    echo "f3d, once per image:       not measured (f3d or Xvfb missing)"
fi
