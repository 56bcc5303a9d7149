#!/usr/bin/env bash
# Measures what spreading a sequence over Slurm costs, on a private single-node cluster
# (docs/farm.md): the same 48 frames rendered by one process and by `lantern farm submit
# --wait` with 1 to 16 tasks, and 16 one-frame 16x16 tasks (scheduling and process start
# alone). Prints the median wall times as a Markdown table, then the overheads derived from
# them. Needs root and the Slurm packages (scripts/slurm-single-node.sh install); starts and
# stops its own cluster.
#
# Usage: scripts/farm-overhead.sh [LANTERN] [REPEATS]   (default build/dev/apps/lantern/lantern, 3)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
L=$(realpath "${1:-$here/../build/dev/apps/lantern/lantern}")
reps=${2:-3}
S=$here/slurm-single-node.sh
export LANTERN_SLURM_DIR=/tmp/lantern-farm-overhead-$$
out=$(mktemp -d /tmp/lantern-farm-overhead-out.XXXXXX)
"$S" start --watch $$ 2>/dev/null
trap '"$S" stop; rm -rf "$out"' EXIT
eval "$("$S" env)"
sleep 4 # the controller's first batch job starts about 3 s after the controller

scene=builtin:spheres-animated
size=(--fps 24 --width 640 --height 360)
now() { date +%s.%N; }
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
declare -A times

for ((rep = 1; rep <= reps; rep++)); do
    d=$out/$rep
    mkdir -p "$d/one"
    t0=$(now)
    "$L" render "$scene" --frames 0-47 -o "$d/one/f_##.exr" "${size[@]}" >/dev/null 2>&1
    times[one]+="$(echo "$(now) - $t0" | bc) "
    for n in 1 2 4 8 16; do
        t0=$(now)
        "$L" farm submit "$scene" --frames 0-47 --tasks $n -o "$d/n$n/f_##.exr" "${size[@]}" --wait >/dev/null 2>&1
        times[n$n]+="$(echo "$(now) - $t0" | bc) "
        for f in "$d"/one/*.exr; do cmp -s "$f" "$d/n$n/${f##*/}" || { echo "$f differs with $n tasks" >&2; exit 1; }; done
    done
    mkdir -p "$d/start"
    t0=$(now)
    "$L" render "$scene" --frames 0-0 -o "$d/start/f_##.exr" --width 16 --height 16 >/dev/null 2>&1
    times[start]+="$(echo "$(now) - $t0" | bc) "
    t0=$(now)
    "$L" farm submit "$scene" --frames 0-15 --tasks 16 -o "$d/tiny/f_##.exr" --width 16 --height 16 --wait >/dev/null 2>&1
    times[tiny]+="$(echo "$(now) - $t0" | bc) "
done

m() { printf '%.2f' "$(tr ' ' '\n' <<<"${times[$1]}" | grep . | median)"; }
runs() { for t in ${times[$1]}; do printf '%.2f ' "$t"; done; }
echo "$(nproc) CPUs, $reps runs each (median wall seconds; runs in brackets)"
echo
echo "| case | wall s | runs |"
echo "|---|---|---|"
echo "| one process, 48 frames 640x360 | $(m one) | $(runs one)|"
for n in 1 2 4 8 16; do echo "| farm submit --wait --tasks $n, same frames | $(m n$n) | $(runs n$n)|"; done
echo "| one process, one 16x16 frame (process start) | $(m start) | $(runs start)|"
echo "| farm submit --wait, 16 tasks of one 16x16 frame | $(m tiny) | $(runs tiny)|"
echo
printf 'job latency (1 task minus one process): %.2f s\n' "$(echo "$(m n1) - $(m one)" | bc)"
printf 'each further task (16 tasks minus 1 task, over 15): %.2f s\n' "$(echo "($(m n16) - $(m n1)) / 15" | bc -l)"
printf 'per task overhead at 16 tasks ((16 tasks - one process) / 16): %.2f s\n' "$(echo "($(m n16) - $(m one)) / 16" | bc -l)"
printf 'per one-frame task (16 tiny tasks / 16): %.2f s\n' "$(echo "$(m tiny) / 16" | bc -l)"
