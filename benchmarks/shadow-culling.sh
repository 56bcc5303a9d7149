#!/usr/bin/env bash
# What culling per shadow map buys (render/ShadowLists.cpp): 1,600 spheres (2,304 triangles
# each, 3.7 M in all) on a 40 x 40 grid over a 60 x 60 plane, lit by one point light 3 above the
# grid's centre that casts shadows (LANTERN_lights_shadow), so each of the cube's six faces sees
# only its own share of the spheres. Drawn one draw per node (`--no-instancing`: an instanced
# draw is kept whole by any map one of its instances reaches), with and without `--no-culling`,
# alternately, by `lantern bench frame` at WIDTHxHEIGHT (median of RUNS frames, GPU render pass),
# and the pictures compared bit for bit. The file is written here (python3, no other module).
# Usage: benchmarks/shadow-culling.sh   (LANTERN=path/to/lantern, default build/dev/apps/lantern/lantern;
#        WIDTH, HEIGHT default 1920 1080; RUNS default 3; RESOLUTION default 1024)
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
width=${WIDTH:-1920} height=${HEIGHT:-1080} runs=${RUNS:-3} resolution=${RESOLUTION:-1024}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

python3 - "$out" <<'PY'
import sys
import json, struct, math
seg, rings = 48, 24
pos, idx = [], []
for r in range(rings + 1):
    th = math.pi * r / rings
    for s in range(seg + 1):
        ph = 2 * math.pi * s / seg
        pos.append((0.4 * math.sin(th) * math.cos(ph), 0.4 * math.cos(th), 0.4 * math.sin(th) * math.sin(ph)))
for r in range(rings):
    for s in range(seg):
        a = r * (seg + 1) + s; b = a + seg + 1
        idx += [a, a + 1, b, a + 1, b + 1, b]
plane = [(-30, 0, -30), (30, 0, -30), (30, 0, 30), (-30, 0, 30)]
pidx = [0, 2, 1, 0, 3, 2]
buf = b''.join(struct.pack('<3f', *p) for p in pos) + b''.join(struct.pack('<I', i) for i in idx)
off2 = len(buf)
buf += b''.join(struct.pack('<3f', *p) for p in plane) + b''.join(struct.pack('<I', i) for i in pidx)
n = 40
nodes = [{"mesh": 0, "translation": [(i - n / 2 + 0.5) * 1.4, 0.5, (j - n / 2 + 0.5) * 1.4]} for i in range(n) for j in range(n)]
nodes.append({"mesh": 1})
nodes.append({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 3, 0]})
nodes.append({"camera": 0, "translation": [0, 12, 30], "rotation": [-0.1908, 0, 0, 0.9816]})
def acc(bv, count, typ, ctype, mn=None, mx=None):
    a = {"bufferView": bv, "count": count, "type": typ, "componentType": ctype}
    if mn: a["min"], a["max"] = mn, mx
    return a
g = {"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual", "LANTERN_lights_shadow"],
     "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 30, "extensions": {"LANTERN_lights_shadow": {"castShadows": True}}}]}},
     "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
     "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}, {"primitives": [{"attributes": {"POSITION": 2}, "indices": 3}]}],
     "buffers": [{"uri": "grid.bin", "byteLength": len(buf)}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * len(pos)}, {"buffer": 0, "byteOffset": 12 * len(pos), "byteLength": 4 * len(idx)},
                     {"buffer": 0, "byteOffset": off2, "byteLength": 48}, {"buffer": 0, "byteOffset": off2 + 48, "byteLength": 24}],
     "accessors": [acc(0, len(pos), "VEC3", 5126, [-0.4, -0.4, -0.4], [0.4, 0.4, 0.4]), acc(1, len(idx), "SCALAR", 5125),
                   acc(2, 4, "VEC3", 5126, [-30, 0, -30], [30, 0, 30]), acc(3, 6, "SCALAR", 5125)]}
open(sys.argv[1] + "/grid.bin", 'wb').write(buf)
json.dump(g, open(sys.argv[1] + "/grid.gltf", 'w'))
print(len(idx) // 3 * n * n, "triangles")
PY

"$lantern" render "$out/grid.gltf" --no-instancing --explain -o "$out/culled.exr" \
    --width "$width" --height "$height" --shadow-resolution "$resolution" | grep shadow-maps
"$lantern" render "$out/grid.gltf" --no-instancing --no-culling -o "$out/all.exr" \
    --width "$width" --height "$height" --shadow-resolution "$resolution" >/dev/null
cmp "$out/culled.exr" "$out/all.exr" && echo "the pictures are the same, bit for bit"
for round in 1 2; do
    for culling in "" --no-culling; do
        printf 'round %s %-13s ' "$round" "${culling:-culled}"
        "$lantern" bench frame "$out/grid.gltf" --no-instancing $culling --shadow-resolution "$resolution" \
            --width "$width" --height "$height" --runs "$runs" --warmup 1 | grep -i "render pass"
    done
done
