"""The Python module without a device: what it is, scenes, errors, and writing images."""
import struct
import zlib

import numpy as np
import pytest


def test_build_info_names_what_a_bug_report_needs(lantern_module):
    info = lantern_module.build_info()
    for key in ("version", "commit", "build_type", "compiler", "library", "vulkan_loader"):
        assert info[key], key
    assert info["version"] == lantern_module.__version__


def test_builtin_scenes_load_and_describe_themselves(lantern_module):
    names = lantern_module.builtin_scenes()
    assert "teapot" in names and "spheres-animated" in names
    scene = lantern_module.load("builtin:teapot")
    assert scene.path == "builtin:teapot"
    assert scene.summary["triangles"] > 1000
    start, end = lantern_module.load("builtin:spheres-animated").animation_range
    assert end > start


def test_refused_input_raises_value_or_os_error_naming_it(lantern_module):
    with pytest.raises(ValueError, match="nope"):
        lantern_module.load("builtin:nope")
    # A missing scene file is refused input (exit 1 on the command line): ValueError.
    with pytest.raises((OSError, ValueError), match="nothing.gltf"):
        lantern_module.load("/nonexistent/nothing.gltf")


def test_mesh_files_load_through_the_same_loader_with_their_up_axis(lantern_module, out_dir):
    # lantern.load is loadScene: OBJ, PLY, STL and OFF load as glTF does, refusals included.
    (out_dir / "tri.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (out_dir / "tri.off").write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 0 1\n3 0 1 2\n")
    assert lantern_module.load(str(out_dir / "tri.obj")).summary["triangles"] == 1
    assert lantern_module.load(str(out_dir / "tri.off"), up="z").summary["triangles"] == 1
    with pytest.raises(ValueError, match="up must be"):
        lantern_module.load(str(out_dir / "tri.off"), up="x")
    (out_dir / "bad.obj").write_text("v 0 nan 0\n")
    with pytest.raises(ValueError, match=r"bad\.obj: vertex 1"):
        lantern_module.load(str(out_dir / "bad.obj"))


def test_lights_are_added_and_cleared(lantern_module):
    scene = lantern_module.load("builtin:teapot")
    scene.clear_lights()
    assert scene.lights == []
    scene.add_light("directional", direction=(0, 0, -1), color=(1, 0.5, 0.25), name="key")
    scene.add_light("point", position=(0, 2, 2))
    assert [(l["name"], l["type"]) for l in scene.lights] == [("key", "directional"),
                                                              ("", "point")]
    assert scene.lights[0]["color"] == (1.0, 0.5, 0.25)
    with pytest.raises(ValueError, match="position"):
        scene.add_light("spot", direction=(0, -1, 0))
    with pytest.raises(ValueError, match="directional, point or spot"):
        scene.add_light("area", position=(0, 0, 0))
    assert len(scene.lights) == 2, "a refused light leaves the scene as it was"


def png_chunks(data):
    chunks, at = [], 8
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind = data[at + 4:at + 8].decode("ascii")
        chunks.append((kind, data[at + 8:at + 8 + length]))
        at += 12 + length
    return chunks


def test_write_image_png_is_srgb_and_straight_alpha(lantern_module, out_dir):
    rgba = np.zeros((2, 3, 4), dtype=np.float32)
    rgba[0, 1] = (0.25, 0.25, 0.25, 0.5)  # premultiplied: 0.5 linear at half coverage
    path = out_dir / "a.png"
    lantern_module.write_image(str(path), rgba)
    chunks = png_chunks(path.read_bytes())
    kinds = [k for k, _ in chunks]
    assert "sRGB" in kinds and kinds.index("sRGB") < kinds.index("IDAT")
    assert "gAMA" in kinds and "cHRM" in kinds
    header = dict(chunks)["IHDR"]
    width, height = struct.unpack(">II", header[:8])
    assert (width, height) == (3, 2)
    raw = zlib.decompress(b"".join(d for k, d in chunks if k == "IDAT"))
    row = raw[1:1 + 3 * 4]  # the first row, after its filter byte
    if raw[0] == 0:  # unfiltered: the pixel bytes as they are
        assert tuple(row[4:8]) == (188, 188, 188, 128)


def test_write_image_refuses_bad_shapes_and_types(lantern_module, out_dir):
    with pytest.raises(ValueError, match="height, width, 4"):
        lantern_module.write_image(str(out_dir / "b.png"), np.zeros((4, 4, 3), np.float32))
    with pytest.raises(ValueError, match="unknown image type"):
        lantern_module.write_image(str(out_dir / "b.tiff"), np.zeros((4, 4, 4), np.float32))
    with pytest.raises(ValueError, match="depth"):
        lantern_module.write_image(str(out_dir / "b.exr"), np.zeros((4, 4, 4), np.float32),
                                   depth=np.zeros((3, 4), np.float32))
