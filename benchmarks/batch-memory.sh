#!/usr/bin/env bash
# Resident memory of one `lantern render` batch of many renders (the C++ and
# Python loops are lantern_memory_loop and memory_loop.py): a list file naming SCENE RENDERS/4
# times, each rendered from four views at 64x64 PNG, so the batch loads the scene again for
# every entry and renders RENDERS images in one process. The script samples the process's
# VmRSS every 0.25 s beside the number of images written, and prints the resident memory when
# 100, 1000 and 10000 (those within RENDERS) images exist and at the end, and the growth
# after the first hundred; exits 1 when it exceeds MAX_GROWTH percent (given).
#
# Usage: benchmarks/batch-memory.sh [RENDERS=10000] [MAX_GROWTH=-1]
#        [SCENE=builtin:spheres-animated] [LANTERN=build/ci/apps/lantern/lantern]
set -euo pipefail
renders=${1:-10000}
max_growth=${2:--1}
scene=${3:-builtin:spheres-animated}
lantern=$(realpath "${4:-build/ci/apps/lantern/lantern}")
[ -x "$lantern" ] || { echo "batch-memory: no lantern at $lantern" >&2; exit 2; }
((renders >= 100 && renders % 4 == 0)) || { echo "batch-memory: RENDERS must be a multiple of 4, at least 100" >&2; exit 2; }

out=$(mktemp -d)
trap 'kill "${pid:-}" 2>/dev/null || true; rm -rf "$out"' EXIT
for ((i = 0; i < renders / 4; ++i)); do echo "$scene"; done >"$out/list.txt"
mkdir "$out/img"

"$lantern" render --list "$out/list.txt" --views front,right,back,left --width 64 --height 64 \
    -o "$out/img/{index}_{view}.png" >/dev/null 2>"$out/batch.err" &
pid=$!

rss() { awk '/^VmRSS:/ { printf "%.1f", $2 / 1024 }' "/proc/$pid/status" 2>/dev/null; }
declare -A at=()
last=""
last_count=0
while kill -0 "$pid" 2>/dev/null; do
    now=$(rss || true)  # the process may end between the check and the read
    # Temporary files come and go while find reads the folder: its complaints are not errors.
    done_count=$( (find "$out/img" -name '*.png' 2>/dev/null || true) | wc -l)
    if [ -n "$now" ]; then last=$now; last_count=$done_count; fi
    for mark in 100 1000 10000; do
        if ((mark <= renders && done_count >= mark)) && [ -z "${at[$mark]:-}" ] && [ -n "$now" ]; then
            at[$mark]=$now
        fi
    done
    sleep 0.25
done
wait "$pid" || { cat "$out/batch.err" >&2; exit 1; }
grep '^lantern: batch: [0-9]' "$out/batch.err" || true

printf 'lantern batch %s x 4 views 64x64: resident MiB when images written' "$scene"
for mark in 100 1000 10000; do
    ((mark <= renders)) && printf ' %d: %s' "$mark" "${at[$mark]:-?}"
done
printf ' last sample (%d images): %s\n' "$last_count" "$last"
[ -n "${at[100]:-}" ] || { echo "batch-memory: the batch ended before 100 images were sampled" >&2; exit 1; }
awk -v a="${at[100]}" -v b="$last" -v m="$max_growth" 'BEGIN {
    g = 100 * (b - a) / a
    printf "growth after image 100: %+.2f%%\n", g
    if (m >= 0 && g > m) { printf "resident memory grew %.2f%%, more than %s%%\n", g, m; exit 1 }
}'
