#!/usr/bin/env bash
# What instanced draws buy (render/DrawLists.cpp, shaders/include/instance.glsl): the same
# scenes drawn with one draw per node (`--no-instancing`) and with the nodes that share a mesh
# as one instanced draw (the default), side by side in one run. Files made here (python3, no
# other module):
# - cubes-shared / spheres-shared: 10,000 nodes on a 100 x 100 grid placing one mesh (a cube,
#   12 triangles; a 16 x 8 sphere, 224 triangles), each node turned and scaled its own way;
# - cubes-mi / spheres-mi: the same through `gltfpack -mi` (EXT_mesh_gpu_instancing, one node
#   with 10,000 instances; skipped without gltfpack);
# - cubes-unique: the cubes with a mesh per node (nothing to share), the baseline.
# For each: `lantern bench frame` at WIDTHxHEIGHT (median of RUNS frames: GPU render pass and
# render() with readback), with and without --no-instancing, and the whole process of
# `lantern render` to a PNG (wall time and peak memory, /usr/bin/time "%e %M").
# Usage: benchmarks/instancing.sh   (LANTERN=path/to/lantern, default build/dev/apps/lantern/lantern;
#        WIDTH, HEIGHT default 1920 1080; RUNS default 10)
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
width=${WIDTH:-1920} height=${HEIGHT:-1080} runs=${RUNS:-10}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

python3 - "$out" <<'PY'
import array, base64, json, math, sys
out = sys.argv[1]

def cube():
    pos, nrm, idx = array.array("f"), array.array("f"), array.array("I")
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]; n[axis] = sign
            u = [0.0, 0.0, 0.0]; u[(axis + 1) % 3] = 1.0
            v = [0.0, 0.0, 0.0]; v[(axis + 2) % 3] = 1.0
            base = len(pos) // 3
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pos.extend(0.35 * (n[k] + a * u[k] + b * v[k]) for k in range(3)); nrm.extend(n)
            quad = (0, 1, 2, 0, 2, 3) if sign > 0 else (0, 2, 1, 0, 3, 2)
            idx.extend(base + q for q in quad)
    return pos, nrm, idx

def sphere(seg=16, rings=8):
    pos, nrm, idx = array.array("f"), array.array("f"), array.array("I")
    for r in range(rings + 1):
        t = math.pi * r / rings
        for s in range(seg + 1):
            p = 2 * math.pi * s / seg
            n = (math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p))
            pos.extend(0.4 * c for c in n); nrm.extend(n)
    for r in range(rings):
        for s in range(seg):
            a, b = r * (seg + 1) + s, (r + 1) * (seg + 1) + s
            if r > 0: idx.extend((a, a + 1, b))
            if r < rings - 1: idx.extend((a + 1, b + 1, b))
    return pos, nrm, idx

def write(name, geometry, unique):
    pos, nrm, idx = geometry
    blob = pos.tobytes() + nrm.tobytes() + idx.tobytes()
    n = 10000
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos) * 4},
             {"buffer": 0, "byteOffset": len(pos) * 4, "byteLength": len(nrm) * 4},
             {"buffer": 0, "byteOffset": len(pos) * 8, "byteLength": len(idx) * 4}]
    lo = [min(pos[k::3]) for k in range(3)]; hi = [max(pos[k::3]) for k in range(3)]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(pos) // 3, "type": "VEC3", "min": lo, "max": hi},
                 {"bufferView": 1, "componentType": 5126, "count": len(nrm) // 3, "type": "VEC3"},
                 {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}]
    mesh = {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}
    nodes = []
    for i in range(n):
        a = 0.37 * i
        nodes.append({"mesh": i if unique else 0, "translation": [i % 100 - 49.5, 0.0, i // 100 - 49.5],
                      "rotation": [0.0, math.sin(a / 2), 0.0, math.cos(a / 2)],
                      "scale": [1.0, 0.6 + 0.4 * ((i * 7) % 10) / 10, 1.0]})
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(n))}],
           "buffers": [{"byteLength": len(blob), "uri": name + ".bin"}], "bufferViews": views,
           "accessors": accessors, "meshes": [mesh] * (n if unique else 1), "nodes": nodes,
           "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.5, 0.3, 1], "metallicFactor": 0.0}}]}
    open(f"{out}/{name}.bin", "wb").write(blob)
    json.dump(doc, open(f"{out}/{name}.gltf", "w"))

write("cubes-shared", cube(), False)
write("cubes-unique", cube(), True)
write("spheres-shared", sphere(), False)
PY

files=(cubes-unique cubes-shared spheres-shared)
if command -v gltfpack >/dev/null; then
    for f in cubes spheres; do
        gltfpack -i "$out/$f-shared.gltf" -o "$out/$f-mi.glb" -mi -noq >/dev/null
        files+=("$f-mi")
    done
else
    echo "(gltfpack is not installed: the EXT_mesh_gpu_instancing files are skipped)"
fi

# `bench frame` of file $1 with options $2...: draw calls, then the medians of the GPU render
# pass and of render() with readback.
frame_ms() {
    local file=$1
    shift
    "$lantern" bench frame "$file" --width "$width" --height "$height" --runs "$runs" "$@" |
        awk '/^draw calls/ { d = $NF } /^render only: GPU/ { g = $(NF - 1) }
             /^render only: render/ { w = $(NF - 1) } END { print d, g, w }'
}

echo "scene            | draws: per node / instanced | GPU pass ms: per node / instanced / ratio | render() ms: per node / instanced / ratio | process s, MB: per node / instanced"
for f in "${files[@]}"; do
    path=$(ls "$out/$f".gl*)
    read -r d1 g1 w1 < <(frame_ms "$path" --no-instancing)
    read -r d2 g2 w2 < <(frame_ms "$path")
    p1=$( { /usr/bin/time -f "%e %M" "$lantern" render "$path" -o "$out/a.png" --width "$width" --height "$height" --no-instancing >/dev/null; } 2>&1 | tail -1)
    p2=$( { /usr/bin/time -f "%e %M" "$lantern" render "$path" -o "$out/b.png" --width "$width" --height "$height" >/dev/null; } 2>&1 | tail -1)
    same=$(cmp -s "$out/a.png" "$out/b.png" && echo identical || echo DIFFERENT)
    printf "%-16s | %5s / %5s | %8s / %8s / %5s | %8s / %8s / %5s | %s / %s (PNGs %s)\n" "$f" "$d1" "$d2" \
        "$g1" "$g2" "$(python3 -c "print(f'{$g1/$g2:.2f}')")" "$w1" "$w2" "$(python3 -c "print(f'{$w1/$w2:.2f}')")" \
        "$(awk '{printf "%.2f, %.0f", $1, $2/1024}' <<<"$p1")" "$(awk '{printf "%.2f, %.0f", $1, $2/1024}' <<<"$p2")" "$same"
done
