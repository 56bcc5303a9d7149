#!/usr/bin/env bash
# Measures how far lavapipe renders of the same scene drift between lavapipe configurations
# (the tolerance docs/testing-with-lantern.md recommends): each scene is rendered once as the
# reference and again under each variant, then `lantern compare` reports the differences.
# Variants: the same settings again (run to run), LP_NUM_THREADS=1 (another rasteriser thread
# split), LP_NATIVE_VECTOR_WIDTH=128 (llvmpipe's 128-bit vectors), and llvmpipe told that the
# CPU lacks AVX and FMA (GALLIUM_OVERRIDE_CPU_CAPS=sse4.1) or SSE (=nosse), as on older CPUs;
# each at --msaa 1 and 4. The table's share of pixels is of those with an error > 1/255.
# Usage: scripts/compare-tolerance.sh [BUILD_DIR] [OUT_DIR]   (default build/dev, compare-tolerance)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/dev}
out=${2:-compare-tolerance}
lantern="$build/apps/lantern/lantern"
samples=../shared/assets/gltf-samples
mkdir -p "$out"
scenes=(builtin:teapots builtin:spheres "$samples/Duck/glTF-Binary/Duck.glb" "$samples/Suzanne/glTF/Suzanne.gltf")
for scene in "${scenes[@]}"; do
    [ -e "$scene" ] || [[ "$scene" == builtin:* ]] || { echo "skipping $scene (missing)" >&2; continue; }
    name=$(basename "${scene#builtin:}"); name=${name%.*}
    for msaa in 1 4; do
        ref="$out/$name-msaa$msaa-ref.exr"
        "$lantern" render "$scene" --width 640 --height 360 --msaa "$msaa" -o "$ref" -o "${ref%.exr}.png" >/dev/null
        for variant in again LP_NUM_THREADS=1 LP_NATIVE_VECTOR_WIDTH=128 \
            GALLIUM_OVERRIDE_CPU_CAPS=sse4.1 GALLIUM_OVERRIDE_CPU_CAPS=nosse; do
            test="$out/$name-msaa$msaa-${variant//=/-}.exr"
            env_args=()
            [ "$variant" = again ] || env_args=("$variant")
            env "${env_args[@]}" "$lantern" render "$scene" --width 640 --height 360 --msaa "$msaa" \
                -o "$test" -o "${test%.exr}.png" >/dev/null
            "$lantern" compare "$ref" "$test" --quiet --tolerance 0.0039216 --json "${test%.exr}.json" >/dev/null || true
            "$lantern" compare "${ref%.exr}.png" "${test%.exr}.png" --quiet --tolerance 0.0039216 --json "${test%.exr}.png.json" >/dev/null || true
        done
    done
done
python3 - "$out" <<'PY'
import json, glob, os, sys
rows = []
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    r = json.load(open(path))
    over = r["over_share"] * 100
    flip = r["flip"]["mean"] if r["flip"] else float("nan")
    psnr = "inf" if r["psnr"] is None else "%.1f" % r["psnr"]
    flipmax = r["flip"]["max"] if r["flip"] else float("nan")
    rows.append("| %s | %s | %.3g | %.3g | %.3f | %s | %.6f | %.2g | %.3g |" % (
        os.path.basename(path).replace(".json", ""), r["encoding"], r["max_abs"], r["mean_abs"], over,
        psnr, r["ssim"], flip, flipmax))
print("| pair | encoding | max abs | mean abs | % pixels > 1/255 | PSNR dB | SSIM | mean FLIP | max FLIP |")
print("|---|---|---|---|---|---|---|---|---|")
print("\n".join(rows))
PY
