#!/usr/bin/env python3
"""Writes a glTF grid of spheres for the frame-cost benchmarks (benchmarks/cluster-culling.sh).

Each sphere is its own mesh, its vertices baked at its place (as a CAD assembly or a scan
has its own triangles), unless --shared, where every node places one mesh (instanced draws).
A sphere of --segments segments and half as many rings has 2 x segments x rings triangles
(64: 4,096). The grid is n x n spheres on the ground, n the square root of --triangles over
that, rounded; a light and no camera (Lantern frames the bounds).

Usage: make-grid.py OUT.gltf --triangles 8.1e6 [--segments 64] [--shared]
python3 only, no other module."""
import argparse
import array
import json
import math
import os
import sys


def sphere(segments):
    rings = segments // 2
    pos, nrm, idx = array.array('f'), array.array('f'), array.array('I')
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(segments + 1):
            ph = 2 * math.pi * s / segments
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            nrm.extend(n)
            pos.extend(0.4 * c for c in n)
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            idx.extend((a, b, a + 1, a + 1, b, b + 1))
    return pos, nrm, idx


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('out')
    ap.add_argument('--triangles', type=float, required=True)
    ap.add_argument('--segments', type=int, default=64)
    ap.add_argument('--shared', action='store_true')
    a = ap.parse_args()
    pos, nrm, idx = sphere(a.segments)
    per = len(idx) // 3
    n = max(1, round(math.sqrt(a.triangles / per)))
    base = os.path.splitext(a.out)[0]
    binName = os.path.basename(base) + '.bin'
    views, accessors, meshes, nodes = [], [], [], []
    offset = 0
    with open(base + '.bin', 'wb') as f:
        def put(data, target):
            nonlocal offset
            data.tofile(f)
            views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data) * 4, "target": target})
            offset += len(data) * 4
            return len(views) - 1

        def vec3(view, values):
            xs, ys, zs = values[0::3], values[1::3], values[2::3]
            accessors.append({"bufferView": view, "count": len(values) // 3, "type": "VEC3", "componentType": 5126,
                              "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]})
            return len(accessors) - 1

        normals = vec3(put(nrm, 34962), nrm)
        indices = put(idx, 34963)
        accessors.append({"bufferView": indices, "count": len(idx), "type": "SCALAR", "componentType": 5125})
        indexAccessor = len(accessors) - 1
        for i in range(n):
            for j in range(n):
                x, z = (i - n / 2 + 0.5) * 1.0, (j - n / 2 + 0.5) * 1.0
                if a.shared and meshes:
                    nodes.append({"mesh": 0, "translation": [x, 0.4, z]})
                    continue
                moved = pos if a.shared else array.array('f', (v + (x, 0.4, z)[k % 3] for k, v in enumerate(pos)))
                positions = vec3(put(moved, 34962), moved)
                meshes.append({"primitives": [{"attributes": {"POSITION": positions, "NORMAL": normals},
                                               "indices": indexAccessor, "material": 0}]})
                nodes.append({"mesh": len(meshes) - 1, "translation": [x, 0.4, z]} if a.shared
                             else {"mesh": len(meshes) - 1})
    g = {"asset": {"version": "2.0", "generator": "lantern benchmarks/make-grid.py"},
         "extensionsUsed": ["KHR_lights_punctual"],
         "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3}]}},
         "scene": 0, "scenes": [{"nodes": list(range(len(nodes) + 1))}],
         "nodes": nodes + [{"extensions": {"KHR_lights_punctual": {"light": 0}},
                            "rotation": [-0.3535534, 0.3535534, 0.1464466, 0.8535534]}],
         "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.3, 1], "metallicFactor": 0,
                                                 "roughnessFactor": 0.5}}],
         "meshes": meshes, "buffers": [{"uri": binName, "byteLength": offset}],
         "bufferViews": views, "accessors": accessors}
    with open(a.out, 'w') as f:
        json.dump(g, f)
    print(f"{n} x {n} spheres, {n * n * per} triangles, {offset / 2**20:.0f} MiB -> {a.out}")


if __name__ == '__main__':
    sys.exit(main())
