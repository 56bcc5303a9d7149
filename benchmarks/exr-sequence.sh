#!/usr/bin/env bash
# A 24-frame 1080p float EXR sequence with depth, as a user writes it, against the two stages
# that bound it: rendering with readback alone (`lantern bench frame`, render() + readback, the
# same AOV) and OpenEXR zip encoding of the same frames on every core by `oiiotool` (OpenImageIO,
# Debian package openimageio-tools), reading them from uncompressed files. Prints the sequence's
# time per frame and its ratio to max(render, encode), ROUNDS times interleaved.
# Usage: benchmarks/exr-sequence.sh   (LANTERN=path/to/lantern, default build/dev/apps/lantern/lantern;
#        ROUNDS default 2; SCENE default builtin:spheres-animated)
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
rounds=${ROUNDS:-2} scene=${SCENE:-builtin:spheres-animated}
command -v oiiotool >/dev/null || { echo "exr-sequence.sh: needs oiiotool (apt install openimageio-tools)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
size=(--width 1920 --height 1080)
seconds() { local t0 t1; t0=$(date +%s.%N); "$@" >/dev/null 2>&1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc -l; }
"$lantern" render "$scene" --frames 0-23 -o "$out/plain_##.exr" --aov depth --compression none "${size[@]}" >/dev/null
for round in $(seq "$rounds"); do
    rm -f "$out"/f_*.exr "$out"/z_*.exr
    sequence=$(seconds "$lantern" render "$scene" --frames 0-23 -o "$out/f_##.exr" --aov depth "${size[@]}")
    render=$("$lantern" bench frame "$scene" --aov depth "${size[@]}" --runs 5 --warmup 1 |
        awk '/render only: render\(\) \+ readback/ {print $(NF-1)}')
    encode=$(seconds oiiotool --threads 0 --frames 0-23 "$out/plain_@@.exr" --compression zip -d float -o "$out/z_@@.exr")
    python3 - "$round" "$sequence" "$render" "$encode" <<'PY'
import sys
r, seq, render, enc = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
seq_ms, enc_ms = seq * 1000 / 24, enc * 1000 / 24
bound = max(render, enc_ms)
print(f"round {r}: sequence {seq_ms:.1f} ms per frame; render + readback {render:.1f} ms; "
      f"oiiotool zip encode {enc_ms:.1f} ms; sequence / max = {seq_ms / bound:.2f}")
PY
done
ls -la "$out" | head -3 >/dev/null
