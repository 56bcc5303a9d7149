#!/usr/bin/env bash
# The same model as OBJ and as glTF converted from it by assimp's command line (Debian
# assimp-utils): a UV sphere (16 x 32 quads, positions, texture coordinates, normals) with one
# MTL material, converted with `assimp export sphere.obj sphere.gltf -fgltf2`, both rendered
# 128x128 by Lantern and compared with `lantern compare` (mean and largest difference).
# Twice: with an MTL whose colours are what Lantern's PBR fallback makes of assimp's glTF
# material (Ka = Kd, Ks = 0.045, Ns = 1: the geometry path alone differs), and with a plain
# MTL (Ka 0.2 x Kd, Ks 0: the material mappings differ too). docs/scene-format-support.md
# ("OBJ and glTF of the same model") has the results.
# Usage: benchmarks/obj-vs-gltf.sh   (LANTERN=path/to/lantern, default build/dev/apps/lantern/lantern)
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
command -v assimp >/dev/null || { echo "assimp not found: apt-get install assimp-utils" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

python3 - "$out/sphere.obj" <<'PY'
import math, sys
rows, cols = 16, 32
with open(sys.argv[1], "w") as o:
    o.write("mtllib sphere.mtl\no sphere\n")
    corners = [(i, j) for i in range(rows + 1) for j in range(cols + 1)]
    for i, j in corners:
        th, ph = math.pi * i / rows, 2 * math.pi * j / cols
        o.write("v %.6f %.6f %.6f\n" % (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)))
    for i, j in corners:
        o.write("vt %.6f %.6f\n" % (j / cols, 1 - i / rows))
    for i, j in corners:
        th, ph = math.pi * i / rows, 2 * math.pi * j / cols
        o.write("vn %.6f %.6f %.6f\n" % (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)))
    o.write("usemtl red\n")
    for i in range(rows):
        for j in range(cols):
            a = i * (cols + 1) + j + 1
            b = a + cols + 1
            for tri in ((a, b, a + 1), (a + 1, b, b + 1)):
                o.write("f " + " ".join("%d/%d/%d" % (k, k, k) for k in tri) + "\n")
PY

compare() {
    local name=$1 mtl=$2
    printf '%s' "$mtl" >"$out/sphere.mtl"
    (cd "$out" && assimp export sphere.obj sphere.gltf -fgltf2 >/dev/null)
    "$lantern" render "$out/sphere.obj" -o "$out/obj.exr" --width 128 --height 128 >/dev/null 2>&1
    "$lantern" render "$out/sphere.gltf" -o "$out/gltf.exr" --width 128 --height 128 >/dev/null 2>&1
    echo "== $name"
    "$lantern" compare "$out/obj.exr" "$out/gltf.exr" 2>&1 | grep -E "^(channel|all)" || true
}
compare "MTL matching the glTF's PBR mapping" \
    $'newmtl red\nKa 0.8 0.2 0.2\nKd 0.8 0.2 0.2\nKs 0.045 0.045 0.045\nNs 1\nillum 2\n'
compare "plain MTL" $'newmtl red\nKa 0.2 0.05 0.05\nKd 0.8 0.2 0.2\nKs 0 0 0\nNs 10\nillum 1\n'
