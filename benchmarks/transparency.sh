#!/usr/bin/env bash
# The three transparency methods (docs/transparency.md) side by side in one run: what each
# costs per frame and how far its picture is from the exact one. Files made here (python3, no
# other module):
# - torus: a blended torus (alpha 0.45, double-sided, 96 x 48 quads) tilted so that it covers
#   itself twice and three times over, the self-overlapping mesh sorting by object cannot order;
# - foliage: 200 alpha-masked leaves (a cut-out texture, MASK at 0.5) scattered through a
#   blended pond plane (alpha 0.5), a mask over a blend;
# - crowd: 144 blended spheres (alpha 0.35, 24 x 12) in a 12 x 12 grid seen at a grazing
#   angle, many layers a pixel (at 1080p within the 4.5 M fragments one storage buffer of
#   lavapipe holds: no warning, docs/transparency.md);
# and the Blender export ../shared/assets/gltf-samples/BlenderIO_01_alpha_blend when it exists.
# For each, `lantern bench frame` at WIDTHxHEIGHT (median of RUNS frames, GPU render pass and
# render() with readback) with --transparency sorted, exact and weighted, and `lantern compare`
# of the sorted and weighted pictures against the exact one (mean absolute error over RGBA,
# FLIP mean). The exact method
# is the reference here: against the ray-cast composite it is exact to float rounding on the
# bench's analytic scenes (tests/image/TransparencyTest.cpp).
# Usage: benchmarks/transparency.sh   (LANTERN=path/to/lantern, default build/dev/apps/lantern/lantern;
#        WIDTH, HEIGHT default 1920 1080; RUNS default 10)
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
width=${WIDTH:-1920} height=${HEIGHT:-1080} runs=${RUNS:-10}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

python3 - "$out" <<'PY'
import array, base64, json, math, struct, sys, zlib
out = sys.argv[1]

def gltf(path, meshes, nodes, materials, images=None, camera=None):
    """meshes: list of (positions, normals, indices, texcoords or None); nodes: list of dicts."""
    blob = bytearray()
    views, accessors, gmeshes = [], [], []
    def add(data, target, ctype, count, kind, minmax=None):
        while len(blob) % 4: blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data) * data.itemsize, "target": target})
        blob.extend(data.tobytes())
        a = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": kind}
        if minmax: a["min"], a["max"] = minmax
        accessors.append(a)
        return len(accessors) - 1
    for pos, nrm, idx, uv, material in meshes:
        n = len(pos) // 3
        lo = [min(pos[i::3]) for i in range(3)]; hi = [max(pos[i::3]) for i in range(3)]
        attrs = {"POSITION": add(pos, 34962, 5126, n, "VEC3", (lo, hi)), "NORMAL": add(nrm, 34962, 5126, n, "VEC3")}
        if uv is not None: attrs["TEXCOORD_0"] = add(uv, 34962, 5126, n, "VEC2")
        gmeshes.append({"primitives": [{"attributes": attrs, "indices": add(idx, 34963, 5125, len(idx), "SCALAR"), "material": material}]})
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}],
           "nodes": nodes, "meshes": gmeshes, "materials": materials, "accessors": accessors,
           "bufferViews": views,
           "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}]}
    if images:
        doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(images[0]).decode()}]
        doc["textures"] = [{"source": 0}]
    if camera:
        doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.05}}]
        doc["nodes"].append({"camera": 0, "translation": camera[0], "rotation": camera[1]})
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
    with open(path, "w") as f: json.dump(doc, f)

def torus(R, r, nu, nv):
    pos, nrm, idx = array.array("f"), array.array("f"), array.array("I")
    for i in range(nu + 1):
        u = 2 * math.pi * i / nu
        for j in range(nv + 1):
            v = 2 * math.pi * j / nv
            c = [math.cos(u) * math.cos(v), math.sin(v), math.sin(u) * math.cos(v)]
            pos.extend([math.cos(u) * R + r * c[0], r * c[1], math.sin(u) * R + r * c[2]]); nrm.extend(c)
    for i in range(nu):
        for j in range(nv):
            a, b = i * (nv + 1) + j, (i + 1) * (nv + 1) + j
            idx.extend([a, a + 1, b, b, a + 1, b + 1])
    return pos, nrm, idx

def sphere(radius, nu, nv):
    pos, nrm, idx = array.array("f"), array.array("f"), array.array("I")
    for j in range(nv + 1):
        t = math.pi * j / nv
        for i in range(nu + 1):
            p = 2 * math.pi * i / nu
            n = [math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p)]
            pos.extend(radius * c for c in n); nrm.extend(n)
    for j in range(nv):
        for i in range(nu):
            a, b = j * (nu + 1) + i, (j + 1) * (nu + 1) + i
            idx.extend([a, b, a + 1, a + 1, b, b + 1])
    return pos, nrm, idx

def quad(size, uv=False):
    s = size / 2
    pos = array.array("f", [-s, 0, -s, s, 0, -s, s, 0, s, -s, 0, s])
    nrm = array.array("f", [0, 1, 0] * 4)
    idx = array.array("I", [0, 2, 1, 0, 3, 2])
    tex = array.array("f", [0, 0, 1, 0, 1, 1, 0, 1]) if uv else None
    return pos, nrm, idx, tex

def leaf_png(n=64):
    rows = []
    for y in range(n):
        row = bytearray([0])
        for x in range(n):
            u, v = (x + 0.5) / n * 2 - 1, (y + 0.5) / n * 2 - 1
            inside = u * u + (v * 1.6) ** 2 < 1 and abs(v) < 0.6 + 0.3 * math.cos(5 * u)
            row.extend([40, 140 + int(60 * (1 - abs(u))), 50, 255 if inside else 0])
        rows.append(bytes(row))
    def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, 6, 0, 0, 0)) + \
        chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b"")

def blended(colour, alpha):
    return {"pbrMetallicRoughness": {"baseColorFactor": colour + [alpha], "metallicFactor": 0, "roughnessFactor": 0.5},
            "alphaMode": "BLEND", "doubleSided": True}

def quat(axis, angle):
    l = math.sqrt(sum(a * a for a in axis)); s = math.sin(angle / 2) / l
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)]

p, n, i = torus(1.0, 0.4, 96, 48)
gltf(f"{out}/torus.gltf", [(p, n, i, None, 0)], [{"mesh": 0, "rotation": quat([1, 0, 0], 0.35)}],
     [blended([0.9, 0.5, 0.2], 0.45)])

import random
random.seed(7)
leaves = []
for k in range(200):
    leaves.append({"mesh": 1, "translation": [random.uniform(-2, 2), random.uniform(-0.6, 0.8), random.uniform(-2, 2)],
                   "rotation": quat([random.uniform(-1, 1), 1, random.uniform(-1, 1)], random.uniform(0, 6.28)),
                   "scale": [0.5, 0.5, 0.5]})
pond = quad(5.0); leaf = quad(1.0, uv=True)
gltf(f"{out}/foliage.gltf", [(pond[0], pond[1], pond[2], None, 0), (leaf[0], leaf[1], leaf[2], leaf[3], 1)],
     [{"mesh": 0}] + leaves,
     [blended([0.2, 0.4, 0.8], 0.5),
      {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}, "alphaMode": "MASK",
       "alphaCutoff": 0.5, "doubleSided": True}], images=[leaf_png()])

p, n, i = sphere(0.45, 24, 12)
nodes = [{"mesh": 0, "translation": [x - 5.5, 0, z - 5.5]} for x in range(12) for z in range(12)]
gltf(f"{out}/crowd.gltf", [(p, n, i, None, 0)], nodes, [blended([0.3, 0.7, 0.9], 0.35)],
     camera=([0, 2.5, 10.0], quat([1, 0, 0], -0.2)))
PY

files=("$out/torus.gltf" "$out/foliage.gltf" "$out/crowd.gltf")
sample=../shared/assets/gltf-samples/BlenderIO_01_alpha_blend/01_alpha_blend.gltf
[ -f "$sample" ] || sample=$(ls ../shared/assets/gltf-samples/BlenderIO_01_alpha_blend/*/*.gl* 2>/dev/null | head -1 || true)
[ -n "$sample" ] && [ -f "$sample" ] && files+=("$(realpath "$sample")")

frame() {  # file method -> "gpu_ms wall_ms"
    "$lantern" bench frame "$1" --width "$width" --height "$height" --runs "$runs" \
        --transparency "$2" 2>/dev/null |
        awk '/GPU render pass/ {g=$(NF-1)} /render\(\) \+ readback/ && !/EXR/ {w=$(NF-1)} END {print g, w}'
}
metric() {  # a b -> "mean-abs flip-mean" of a against b
    "$lantern" compare "$2" "$1" 2>/dev/null |
        awk '$1 == "all" {r=$3} /^FLIP/ {for (i = 1; i <= NF; ++i) if ($i == "mean") f=$(i+1); sub(",", "", f)} END {print r, f}'
}
printf '| file | method | GPU render pass ms | render()+readback ms | x sorted (GPU) | mean abs error vs exact | FLIP mean vs exact |\n|---|---|---|---|---|---|---|\n'
for f in "${files[@]}"; do
    name=$(basename "$f" | sed 's/\.gltf$//; s/\.glb$//')
    for m in sorted exact weighted; do
        "$lantern" render "$f" --width "$width" --height "$height" --transparency "$m" -o "$out/$name-$m.exr" >/dev/null 2>&1
    done
    read -r gs ws < <(frame "$f" sorted)
    for m in sorted exact weighted; do
        if [ "$m" = sorted ]; then g=$gs w=$ws; else read -r g w < <(frame "$f" "$m"); fi
        if [ "$m" = exact ]; then e="-" fl="-"; else read -r e fl < <(metric "$out/$name-$m.exr" "$out/$name-exact.exr"); fi
        ratio=$(awk -v a="$g" -v b="$gs" 'BEGIN {printf "%.2f", a / b}')
        printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$m" "$g" "$w" "$ratio" "$e" "$fl"
    done
done
