"""Exact data passes from Python (docs/aovs.md): aov=[names] gives float32 data planes and
uint32 id planes of the right shapes, viewing the Image's memory; ids match the scene's nodes,
semantic ids come from node extras; unlit_exact gives a label colour back bit for bit."""
import base64
import json
import struct

import numpy as np
import pytest


def owner(array):
    """What finally holds an array's memory (a picture is a view of the module's array)."""
    while isinstance(array.base, np.ndarray):
        array = array.base
    return array.base

SIZE = dict(width=64, height=48)
ALL = ["depth", "range", "normal", "world_normal", "uv", "instance", "primitive", "material",
       "semantic"]


def write_quads(path, colours):
    """One quad per colour side by side in z = 0 (x from -4 to 4), node i with semantic 10 + i."""
    data, accessors, views, meshes, nodes, materials = b"", [], [], [], [], []

    def add(values, fmt, kind, count):
        nonlocal data
        blob = struct.pack("<" + fmt * (len(values) // len(fmt)), *values)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(blob)})
        data += blob + b"\0" * (-len(blob) % 4)
        accessor = {"bufferView": len(views) - 1, "componentType": 5126 if fmt[0] == "f" else 5123,
                    "count": count, "type": kind}
        if kind == "VEC3":
            accessor["min"] = [min(values[i::3]) for i in range(3)]
            accessor["max"] = [max(values[i::3]) for i in range(3)]
        accessors.append(accessor)
        return len(accessors) - 1

    for i, colour in enumerate(colours):
        x0 = -4.0 + 2.0 * i
        x1 = x0 + 1.5
        position = add([x0, -1, 0, x1, -1, 0, x1, 1, 0, x0, 1, 0], "fff", "VEC3", 4)
        normal = add([0, 0, 1] * 4, "fff", "VEC3", 4)
        uv = add([0, 0, 1, 0, 1, 1, 0, 1], "ff", "VEC2", 4)
        indices = add([0, 1, 2, 0, 2, 3], "H", "SCALAR", 6)
        meshes.append({"primitives": [{"attributes": {"POSITION": position, "NORMAL": normal,
                                                      "TEXCOORD_0": uv},
                                       "indices": indices, "material": i}]})
        materials.append({"pbrMetallicRoughness": {"baseColorFactor": list(colour) + [1.0],
                                                   "metallicFactor": 0.5}})
        nodes.append({"mesh": i, "extras": {"semantic_id": 10 + i}})
    doc = {"asset": {"version": "2.0"}, "scene": 0,
           "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
           "materials": materials, "accessors": accessors, "bufferViews": views,
           "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                        + base64.b64encode(data).decode()}]}
    path.write_text(json.dumps(doc))
    return str(path)


CAMERA = dict(look_at=((0, 0, 5), (0, 0, 0), (0, 1, 0)), ortho=(-4, 4, -1.5, 1.5, 0.5, 10))
COLOURS = [(0.1, 0.2, 0.3), (1 / 3, 2 / 7, 0.123456789), (0.7, 1e-6, 0.999999), (0.25, 0.5, 1.0)]


def test_aov_planes_are_numpy_arrays_of_their_dtype_and_shape(lantern_module, renderer, out_dir):
    scene = lantern_module.load(write_quads(out_dir / "quads.gltf", COLOURS))
    rgba, planes = renderer.render(scene, aov=ALL, **CAMERA, **SIZE)
    assert rgba.shape == (48, 64, 4) and rgba.dtype == np.float32
    shapes = {"depth": (48, 64), "range": (48, 64), "normal": (48, 64, 3),
              "world_normal": (48, 64, 3), "uv": (48, 64, 2)}
    for name, shape in shapes.items():
        assert planes[name].shape == shape and planes[name].dtype == np.float32, name
    for name in ("instance", "mesh", "primitive", "material", "semantic"):
        assert planes[name].shape == (48, 64) and planes[name].dtype == np.uint32, name
        assert owner(planes[name]) is owner(rgba), "every plane views the same Image"
    nothing = np.uint32(0xFFFFFFFF)
    assert planes["instance"][0, 0] == nothing and planes["semantic"][0, 0] == 0
    # The quads' centres: x = -3.25 + 2 i of [-4, 4] -> column (x + 4) / 8 * 64.
    for i in range(4):
        column = int((-3.25 + 2 * i + 4) / 8 * 64)
        assert planes["instance"][24, column] == i and planes["material"][24, column] == i
        assert planes["mesh"][24, column] == i and planes["primitive"][24, column] == 0
        assert planes["semantic"][24, column] == 10 + i
        assert abs(planes["depth"][24, column] - 5.0) < 1e-5
        assert abs(planes["uv"][24, column, 0] - 0.5) < 0.05
        assert np.allclose(planes["world_normal"][24, column], (0, 0, 1), atol=1e-6)
    assert set(np.unique(planes["instance"])) == {0, 1, 2, 3, nothing}
    with pytest.raises(ValueError, match="unknown AOV"):
        renderer.render(scene, aov=["depth", "ids"], **SIZE)


def test_unlit_exact_gives_the_label_colours_back_bit_for_bit(lantern_module, renderer, out_dir):
    scene = lantern_module.load(write_quads(out_dir / "labels.gltf", COLOURS))
    rgba = renderer.render(scene, unlit_exact=True, **CAMERA, **SIZE)
    for i, colour in enumerate(COLOURS):
        column = int((-3.25 + 2 * i + 4) / 8 * 64)
        assert (rgba[24, column, :3] == np.array(colour, dtype=np.float32)).all(), (i, colour)
    lit = renderer.render(scene, **CAMERA, **SIZE)
    assert (lit[24, 8, :3] != np.array(COLOURS[0], dtype=np.float32)).any()
    with pytest.raises(ValueError, match="unlit_exact"):
        renderer.render(scene, unlit_exact=True, msaa=4, **SIZE)


def murmur3_32(data, seed=0):
    """MurmurHash3_x86_32 written again from Appleby's reference, to check the module's ids."""
    def rotl(x, r):
        return ((x << r) | (x >> (32 - r))) & 0xFFFFFFFF

    def mix(k):
        return (rotl((k * 0xCC9E2D51) & 0xFFFFFFFF, 15) * 0x1B873593) & 0xFFFFFFFF

    h, blocks = seed, len(data) // 4
    for i in range(blocks):
        h = rotl(h ^ mix(struct.unpack("<I", data[4 * i:4 * i + 4])[0]), 13)
        h = (h * 5 + 0xE6546B64) & 0xFFFFFFFF
    tail = data[4 * blocks:]
    if tail:
        h ^= mix(int.from_bytes(tail, "little"))
    h ^= len(data)
    for shift, factor in ((16, 0x85EBCA6B), (13, 0xC2B2AE35)):
        h = ((h ^ (h >> shift)) * factor) & 0xFFFFFFFF
    return h ^ (h >> 16)


def test_cryptomatte_ranks_hold_name_hashes_and_coverage(lantern_module, renderer, out_dir):
    assert murmur3_32(b"bunny") == 0x13851A76  # the Cryptomatte specification's example
    scene = lantern_module.load(write_quads(out_dir / "crypto.gltf", COLOURS))
    _, planes = renderer.render(scene, aov=["crypto_object", "crypto_material"], **CAMERA, **SIZE)
    assert planes["crypto_object"].shape == (48, 64, 8)
    assert planes["crypto_object"].dtype == np.float32
    for i in range(4):
        column = int((-3.25 + 2 * i + 4) / 8 * 64)
        for plane, name in (("crypto_object", "node %d" % i), ("crypto_material", "material %d" % i)):
            h = murmur3_32(name.encode())
            if (h >> 23) & 0xFF in (0, 255):
                h ^= 1 << 23
            expected = np.array([h], dtype=np.uint32).view(np.float32)[0]
            ranks = planes[plane][24, column]
            assert ranks[0] == expected and ranks[1] == 1.0 and (ranks[2:] == 0).all(), name
    assert (planes["crypto_object"][0, 0] == 0).all()  # the background has no id
