#!/usr/bin/env python3
"""Writes the mesh-format benchmark files: a torus of SEGMENTS x RINGS quads (2 x SEGMENTS x
RINGS triangles; the defaults make 1,000,000) as OBJ (v, vt, vn; an MTL with Ka, Kd, Ks, Ns),
binary little-endian PLY (float x y z nx ny nz, uchar red green blue, list uchar int faces),
binary STL and OFF. docs/performance.md ("Loading mesh files") times Lantern and F3D on them.

Usage: benchmarks/make-meshes.py [--out DIR] [--segments 1000] [--rings 500]
"""
import argparse
import pathlib
import struct

import numpy as np


def torus(segments, rings, big=1.0, small=0.35):
    """Positions, normals, texture coordinates ((segments+1) x (rings+1): the seams doubled)
    and the quads' corner indices into them."""
    u = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    v = np.linspace(0.0, 2.0 * np.pi, rings + 1)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    normal = np.stack([np.cos(vv) * np.cos(uu), np.cos(vv) * np.sin(uu), np.sin(vv)], axis=-1)
    centre = np.stack([big * np.cos(uu), big * np.sin(uu), np.zeros_like(uu)], axis=-1)
    pos = (centre + small * normal).reshape(-1, 3).astype(np.float32)
    nrm = normal.reshape(-1, 3).astype(np.float32)
    tex = np.stack([uu / (2 * np.pi), vv / (2 * np.pi)], axis=-1).reshape(-1, 2).astype(np.float32)
    i, j = np.meshgrid(np.arange(segments), np.arange(rings), indexing="ij")
    a = i * (rings + 1) + j
    quads = np.stack([a, a + rings + 1, a + rings + 2, a + 1], axis=-1).reshape(-1, 4)
    return pos, nrm, tex, quads.astype(np.int32)


def write_obj(path, pos, nrm, tex, quads):
    (path.with_suffix(".mtl")).write_text(
        "newmtl torus\nKa 0.1 0.1 0.1\nKd 0.8 0.5 0.2\nKs 0.5 0.5 0.5\nNs 64\nillum 2\n")
    with open(path, "w") as f:
        f.write(f"mtllib {path.with_suffix('.mtl').name}\no torus\n")
        f.write("".join("v %.6f %.6f %.6f\n" % tuple(p) for p in pos))
        f.write("".join("vt %.6f %.6f\n" % tuple(t) for t in tex))
        f.write("".join("vn %.6f %.6f %.6f\n" % tuple(n) for n in nrm))
        f.write("usemtl torus\n")
        q = quads + 1
        tris = np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]], axis=0)
        f.write("".join("f %d/%d/%d %d/%d/%d %d/%d/%d\n" % (a, a, a, b, b, b, c, c, c)
                        for a, b, c in tris))


def triangles(quads):
    return np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]], axis=0)


def write_ply(path, pos, nrm, quads):
    tris = triangles(quads)
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\n"
            "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
            % (len(pos), len(tris)))
    vert = np.zeros(len(pos), dtype=[("p", "<f4", 3), ("n", "<f4", 3), ("c", "u1", 3)])
    vert["p"], vert["n"] = pos, nrm
    vert["c"] = np.clip(nrm * 127 + 128, 0, 255).astype(np.uint8)
    face = np.zeros(len(tris), dtype=[("k", "u1"), ("i", "<i4", 3)])
    face["k"], face["i"] = 3, tris
    with open(path, "wb") as f:
        f.write(head.encode())
        f.write(vert.tobytes())
        f.write(face.tobytes())


def write_stl(path, pos, quads):
    tris = triangles(quads)
    p = pos[tris]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
    rec = np.zeros(len(tris), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["n"], rec["v"] = n, p
    with open(path, "wb") as f:
        f.write(b"binary STL written by benchmarks/make-meshes.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        f.write(rec.tobytes())


def write_off(path, pos, quads):
    tris = triangles(quads)
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(pos), len(tris)))
        f.write("".join("%.6f %.6f %.6f\n" % tuple(p) for p in pos))
        f.write("".join("3 %d %d %d\n" % tuple(t) for t in tris))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="build/meshes")
    ap.add_argument("--segments", type=int, default=1000)
    ap.add_argument("--rings", type=int, default=500)
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    pos, nrm, tex, quads = torus(a.segments, a.rings)
    write_obj(out / "torus.obj", pos, nrm, tex, quads)
    write_ply(out / "torus.ply", pos, nrm, quads)
    write_stl(out / "torus.stl", pos, quads)
    write_off(out / "torus.off", pos, quads)
    for name in ("torus.obj", "torus.ply", "torus.stl", "torus.off"):
        print(f"{out / name}: {(out / name).stat().st_size} bytes, {2 * len(quads)} triangles")


if __name__ == "__main__":
    main()
