#!/usr/bin/env bash
# What the glTF features that exporters add (those below) cost a file that uses them, and that a
# file without them pays nothing. Files made here (python3, no other module):
# - materials-plain / materials-ext: 20,000 nodes, each with a mesh and a metallic-roughness
#   material; -ext adds KHR_materials_ior, specular, clearcoat and sheen to every material.
# - grid-base / grid-maps / grid-tangent-set1: a 1000 x 1000-quad grid (1,002,001 vertices,
#   2,000,000 triangles) with NORMAL, TEXCOORD_0 and a base-colour texture; -maps adds a
#   normal and an occlusion map; -tangent-set1 the same maps with TANGENT read and the
#   occlusion map on TEXCOORD_1.
# Each is loaded (`lantern info`) and loaded and rendered (`lantern render`, 640x360 PNG),
# the whole process, alternating, 3 runs: prints the median wall time and peak memory
# (/usr/bin/time "%e %M"), and the pipeline variants `lantern info` lists.
# Usage: benchmarks/gltf-feature-cost.sh   (LANTERN=path/to/lantern, default build/dev/apps/lantern/lantern)
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

python3 - "$out" <<'PY'
import array, base64, json, struct, sys, zlib
out = sys.argv[1]

def materials(ext):
    n = 20000
    pos = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(n))}],
           "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64," + base64.b64encode(pos).decode()}],
           "bufferViews": [{"buffer": 0, "byteLength": 36}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
           "meshes": [], "materials": [], "nodes": []}
    for i in range(n):
        m = {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.4, 0.3, 1], "metallicFactor": 0.1, "roughnessFactor": 0.5}}
        if ext:
            m["extensions"] = {"KHR_materials_ior": {"ior": 1.7}, "KHR_materials_specular": {"specularFactor": 0.8},
                               "KHR_materials_clearcoat": {"clearcoatFactor": 0.5, "clearcoatRoughnessFactor": 0.2},
                               "KHR_materials_sheen": {"sheenColorFactor": [0.2, 0.2, 0.2]}}
        doc["materials"].append(m)
        doc["meshes"].append({"primitives": [{"attributes": {"POSITION": 0}, "material": i}]})
        doc["nodes"].append({"mesh": i, "translation": [i % 100, i // 100, 0]})
    if ext:
        doc["extensionsUsed"] = ["KHR_materials_ior", "KHR_materials_specular", "KHR_materials_clearcoat", "KHR_materials_sheen"]
    json.dump(doc, open(f"{out}/materials-{'ext' if ext else 'plain'}.gltf", "w"))

def png(rgba):
    raw = b"".join(b"\x00" + bytes(rgba) * 8 for _ in range(8))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 8, 8, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

def grid():
    q = 1000
    side = q + 1
    pos, nrm, uv, uv1, tan, idx = (array.array(c) for c in "ffffff"[:5] + "I")
    for i in range(side):
        for j in range(side):
            pos.extend((j / q - 0.5, i / q - 0.5, 0.0)); nrm.extend((0.0, 0.0, 1.0))
            uv.extend((j / q * 8, i / q * 8)); uv1.extend((j / q, i / q)); tan.extend((1.0, 0.0, 0.0, 1.0))
    for i in range(q):
        for j in range(q):
            a = i * side + j
            idx.extend((a, a + 1, a + side, a + 1, a + side + 1, a + side))
    streams = [(pos, "VEC3", 5126), (nrm, "VEC3", 5126), (uv, "VEC2", 5126), (uv1, "VEC2", 5126),
               (tan, "VEC4", 5126), (idx, "SCALAR", 5125)]
    blob, views, accessors = b"", [], []
    for data, kind, comp in streams:
        b = data.tobytes()
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(b)})
        count = len(data) // {"VEC3": 3, "VEC2": 2, "VEC4": 4, "SCALAR": 1}[kind]
        accessors.append({"bufferView": len(views) - 1, "componentType": comp, "count": count, "type": kind})
        blob += b
    accessors[0]["min"], accessors[0]["max"] = [-0.5, -0.5, 0], [0.5, 0.5, 0]
    open(f"{out}/grid.bin", "wb").write(blob)
    images = [{"uri": "data:image/png;base64," + base64.b64encode(png(c)).decode()}
              for c in ((200, 180, 160, 255), (140, 128, 240, 255), (200, 200, 200, 255))]
    for name in ("base", "maps", "tangent-set1"):
        attributes = {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}
        material = {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.5}}
        if name != "base":
            material["normalTexture"] = {"index": 1}
            material["occlusionTexture"] = {"index": 2}
        if name == "tangent-set1":
            attributes.update({"TEXCOORD_1": 3, "TANGENT": 4})
            material["occlusionTexture"]["texCoord"] = 1
        doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
               "nodes": [{"mesh": 0, "rotation": [-0.3826834, 0, 0, 0.9238795]}],
               "meshes": [{"primitives": [{"attributes": attributes, "indices": 5, "material": 0}]}],
               "materials": [material], "images": images,
               "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
               "buffers": [{"byteLength": len(blob), "uri": "grid.bin"}],
               "bufferViews": views, "accessors": accessors}
        json.dump(doc, open(f"{out}/grid-{name}.gltf", "w"))

materials(False); materials(True); grid()
PY

measure() {  # "SECONDS KB" of one run of the command, which must succeed
    /usr/bin/time -f "%e %M" -o "$out/time" "$@" >"$out/log" 2>&1 || { tail -n 5 "$out/log" >&2; exit 1; }
    cat "$out/time"
}
median() { sort -n | sed -n 2p; }
for group in "materials-plain materials-ext" "grid-base grid-maps grid-tangent-set1"; do
    for what in load render; do
        declare -A t=() m=()
        for _ in 1 2 3; do
            for f in $group; do
                if [ "$what" = load ]; then r=$(measure "$lantern" info "$out/$f.gltf")
                else r=$(measure "$lantern" render "$out/$f.gltf" --width 640 --height 360 -o "$out/x.png"); fi
                t[$f]+="${r% *}"$'\n'; m[$f]+="${r#* }"$'\n'
            done
        done
        for f in $group; do
            printf '%-22s %-6s %6s s %8s KB\n' "$f" "$what" "$(printf '%s' "${t[$f]}" | median)" \
                "$(printf '%s' "${m[$f]}" | median)"
        done
        unset t m
    done
done
for f in grid-base grid-maps grid-tangent-set1; do
    echo "== $f"; "$lantern" info "$out/$f.gltf" 2>/dev/null | sed -n '/pipeline variants/,$p'
done
