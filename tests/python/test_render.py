"""Rendering from Python: NumPy arrays without a copy, the same picture `lantern render` makes,
options as keywords, lights, depth, animation frames, and the device's limits as errors."""
import os
import subprocess

import numpy as np
import pytest


def owner(array):
    """What finally holds an array's memory (a picture is a view of the module's array)."""
    while isinstance(array.base, np.ndarray):
        array = array.base
    return array.base

SIZE = dict(width=64, height=48)


@pytest.fixture(scope="module")
def teapot(lantern_module):
    return lantern_module.load("builtin:teapot")


def test_render_is_float32_rgba_viewing_the_images_memory(renderer, teapot):
    rgba = renderer.render(teapot, **SIZE)
    assert rgba.shape == (48, 64, 4) and rgba.dtype == np.float32
    assert rgba.flags.c_contiguous
    assert not rgba.flags.owndata and rgba.base is not None, "the Image's buffer, not a copy"
    assert np.isfinite(rgba).all()
    assert (rgba[..., 3] == 1.0).all(), "the background is opaque black by default"
    assert rgba[24, 32, :3].max() > 0.05, "the teapot is in the middle"
    assert (rgba[0, 0] == (0, 0, 0, 1)).all()


def test_transparent_background_gives_coverage_in_alpha(renderer, teapot):
    rgba = renderer.render(teapot, background=(0, 0, 0, 0), **SIZE)
    alpha = rgba[..., 3]
    assert alpha[0, 0] == 0.0 and alpha[24, 32] == 1.0
    grey = renderer.render(teapot, background=(0.5, 0.5, 0.5), **SIZE)
    assert (grey[0, 0] == (0.5, 0.5, 0.5, 1.0)).all()


def test_same_picture_as_the_command_line(lantern_module, renderer, teapot, out_dir):
    cli = os.environ.get("LANTERN_CLI")
    if not cli:
        pytest.skip("LANTERN_CLI is not set (run through ctest)")
    args = ["--width", "64", "--height", "48", "--shading", "gouraud", "--msaa", "4"]
    subprocess.run([cli, "render", "builtin:teapot", "-o", str(out_dir / "cli.png")] + args,
                   check=True, capture_output=True)
    rgba = renderer.render(teapot, shading="gouraud", msaa=4, **SIZE)
    lantern_module.write_image(str(out_dir / "python.png"), rgba)
    assert (out_dir / "cli.png").read_bytes() == (out_dir / "python.png").read_bytes()


def test_options_change_the_picture(renderer, teapot):
    base = renderer.render(teapot, **SIZE)
    for options in (dict(shading="flat"), dict(specular="phong"), dict(msaa=4),
                    dict(look_at=((0, 0, 6), (0, 0, 0), (0, 1, 0)), perspective=(30, 0.1, 100)),
                    dict(ortho=(-3, 3, -2, 2, 0.1, 100), look_at=((0, 0, 6), (0, 0, 0), (0, 1, 0))),
                    dict(time=0.0, gl_compat=True, shading="flat")):
        other = renderer.render(teapot, **options, **SIZE)
        assert np.abs(other - base).max() > 1e-3, options


def test_shadows_only_darken(renderer, teapot):
    # The teapot's spout and handle shadow its body: shadows=True darkens some pixels and
    # brightens none (a shadow takes a light's diffuse and specular terms away).
    lit = renderer.render(teapot, width=128, height=96)
    shadowed = renderer.render(teapot, width=128, height=96, shadows=True)
    assert np.isfinite(shadowed).all()
    assert (shadowed[..., :3] <= lit[..., :3] + 1e-5).all()
    assert (shadowed[..., :3] < lit[..., :3] - 0.02).any(), "no pixel is in a shadow"


def test_shadow_filter_and_cascades(renderer, teapot):
    # Each filter and cascade count shadows the teapot (it darkens some pixels, brightens
    # none); a soft filter's picture differs from PCF's; bad values raise ValueError.
    lit = renderer.render(teapot, width=128, height=96)
    pictures = {}
    for kwargs in ({"shadow_filter": "hardware"}, {"shadow_filter": "pcss"},
                   {"shadow_cascades": 1}, {"shadow_cascades": 8}):
        shadowed = renderer.render(teapot, width=128, height=96, shadows=True, **kwargs)
        assert np.isfinite(shadowed).all(), kwargs
        assert (shadowed[..., :3] <= lit[..., :3] + 1e-5).all(), kwargs
        assert (shadowed[..., :3] < lit[..., :3] - 0.02).any(), kwargs
        pictures[str(kwargs)] = shadowed
    pcf = renderer.render(teapot, width=128, height=96, shadows=True)
    assert not np.array_equal(pictures[str({"shadow_filter": "pcss"})], pcf)
    with pytest.raises(ValueError, match="shadow_filter"):
        renderer.render(teapot, shadows=True, shadow_filter="vsm", **SIZE)
    with pytest.raises(ValueError, match="shadow_cascades"):
        renderer.render(teapot, shadows=True, shadow_cascades=9, **SIZE)


def test_culling_and_level_of_detail(renderer, teapot):
    # Culling changes no pixel; a level-of-detail bound keeps the picture close; a negative
    # bound raises ValueError.
    exact = renderer.render(teapot, width=128, height=96)
    everything = renderer.render(teapot, width=128, height=96, culling=False)
    assert np.array_equal(exact, everything)
    coarse = renderer.render(teapot, width=128, height=96, lod_error=2.0)
    assert np.isfinite(coarse).all()
    assert np.abs(coarse - exact).mean() < 0.02
    with pytest.raises(ValueError, match="lod_error"):
        renderer.render(teapot, lod_error=-1.0, **SIZE)


def test_transparency_methods(renderer, teapot):
    # The teapot blends nothing: every method gives the same picture (it pays for none);
    # tests/image/TransparencyTest.cpp holds where they differ.
    base = renderer.render(teapot, **SIZE)
    for method in ("sorted", "exact", "weighted"):
        assert np.array_equal(renderer.render(teapot, transparency=method, **SIZE), base), method
    with pytest.raises(ValueError, match="transparency"):
        renderer.render(teapot, transparency="depth-peeling", **SIZE)


def test_bad_keywords_raise_value_error(renderer, teapot):
    with pytest.raises(ValueError, match="shading"):
        renderer.render(teapot, shading="toon", **SIZE)
    with pytest.raises(ValueError, match="look_at"):
        renderer.render(teapot, look_at=((0, 0, 0), (0, 0, 0), (0, 1, 0)), **SIZE)
    with pytest.raises(ValueError, match="camera 3"):
        renderer.render(teapot, camera=3, **SIZE)
    with pytest.raises(TypeError):
        renderer.render(teapot, widht=64)


def test_point_size_widens_a_point_cloud(lantern_module, renderer, out_dir):
    """A glTF POINTS primitive without normals: unlit points, one pixel each by default."""
    import base64
    import json
    import struct

    points = [(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (0.0, 0.5, 0.0)]
    data = b"".join(struct.pack("<3f", *p) for p in points)
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 0}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [-0.5, -0.5, 0.0], "max": [0.5, 0.5, 0.0]}],
        "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    }
    path = out_dir / "points.gltf"
    path.write_text(json.dumps(doc))
    scene = lantern_module.load(str(path))
    assert scene.summary["points"] == 3 and scene.summary["triangles"] == 0
    lit = lambda rgba: int((rgba[..., :3].max(axis=2) > 0).sum())
    one = renderer.render(scene, **SIZE)
    assert lit(one) == 3, "three one-pixel points"
    five = renderer.render(scene, point_size=5, **SIZE)
    assert lit(five) == 75, "three 5x5 points"
    with pytest.raises(ValueError, match="point_size"):
        renderer.render(scene, point_size=0.5, **SIZE)
    with pytest.raises(ValueError, match="line_width"):
        renderer.render(scene, line_width=300, **SIZE)


def test_msaa_the_device_lacks_names_the_ones_it_has(renderer, teapot):
    supported = renderer.device["msaa"]
    missing = [m for m in (2, 8, 16) if m not in supported]
    if not missing:
        pytest.skip(f"{renderer.device['name']} supports every sample count tried")
    with pytest.raises(ValueError, match="supports " + ", ".join(map(str, supported))):
        renderer.render(teapot, msaa=missing[0], **SIZE)


def test_depth_and_normal_planes(renderer, teapot):
    rgba, depth = renderer.render(teapot, depth=True, **SIZE)
    assert depth.shape == (48, 64) and depth.dtype == np.float32
    # Nothing there is the largest float (every plane is free of Inf and NaN).
    assert depth[0, 0] == np.finfo(np.float32).max and 1.0 < depth[24, 32] < 100.0
    rgba2, depth2, normal = renderer.render(teapot, depth=True, normal=True, **SIZE)
    assert normal.shape == (48, 64, 3)
    assert abs(np.linalg.norm(normal[24, 32]) - 1.0) < 1e-3
    assert owner(depth2) is owner(rgba2), "every plane views the same Image"


def test_lights_edited_between_renders(lantern_module, renderer):
    scene = lantern_module.load("builtin:teapot")
    lit = renderer.render(scene, **SIZE)
    scene.clear_lights()
    # A black light: only the global ambient and emission, and no default light (the scene has
    # one). The red light adds red alone.
    scene.add_light("directional", direction=(0, 0, -1), color=(0, 0, 0))
    dark = renderer.render(scene, **SIZE)
    scene.clear_lights()
    scene.add_light("directional", direction=(0, 0, -1), color=(1, 0, 0))
    red = renderer.render(scene, **SIZE)
    added = red[24, 32] - dark[24, 32]
    assert added[0] > 0.05 and abs(added[1]) < 1e-6 and abs(added[2]) < 1e-6, added
    assert np.abs(red - lit).max() > 0.05


def test_frames_of_an_animation(lantern_module, renderer):
    scene = lantern_module.load("builtin:spheres-animated")
    got = list(renderer.frames(scene, first=0, last=2, fps=12, **SIZE))
    assert [k for k, _ in got] == [0, 1, 2]
    assert np.abs(got[0][1] - got[2][1]).max() > 1e-3, "the spheres move"
    again = renderer.render(scene, time=2 / 12, **SIZE)
    assert (again == got[2][1]).all(), "frame k is the picture at time k / fps"


def test_module_level_render_keeps_one_renderer(lantern_module):
    try:
        first = lantern_module.render("builtin:teapot", **SIZE)
    except lantern_module.Error as e:
        pytest.skip(f"no Vulkan device: {e}")
    kept = lantern_module._default_renderer
    second = lantern_module.render("builtin:teapot", **SIZE)
    assert lantern_module._default_renderer is kept
    assert (first == second).all()


def _opencv_camera():
    """An off-centre OpenCV camera for 64 x 48: K and world_to_camera [R | t] looking at the
    teapot from (2, 1.5, 6)."""
    K = np.array([[70.0, 0.0, 29.3], [0.0, 55.0, 25.1], [0.0, 0.0, 1.0]])
    eye, target = np.array([2.0, 1.5, 6.0]), np.array([0.0, 0.5, 0.0])
    z = (target - eye) / np.linalg.norm(target - eye)        # forward
    x = np.cross(z, (0.0, 1.0, 0.0))                           # right
    x /= np.linalg.norm(x)
    y = np.cross(z, x)                                         # down: OpenCV's y
    Rt = np.eye(4)
    Rt[:3, :3] = np.stack([x, y, z])
    Rt[:3, 3] = -Rt[:3, :3] @ eye
    return K, Rt


def test_opencv_and_gltf_cameras_render_the_same_picture(renderer, teapot):
    K, Rt = _opencv_camera()
    cv = renderer.render(teapot, intrinsics=K, world_to_camera=Rt, near=0.1, far=100, **SIZE)
    assert cv[..., :3].max() > 0.05, "the teapot is in view"
    # glTF's camera_to_world: the camera's world matrix with y and z flipped.
    gltf = np.linalg.inv(Rt) @ np.diag([1.0, -1.0, -1.0, 1.0])
    other = renderer.render(teapot, intrinsics=(70.0, 55.0, 29.3, 25.1), camera_to_world=gltf,
                            near=0.1, far=100, **SIZE)
    assert (cv == other).all()


def test_camera_file_is_the_same_as_the_keywords(lantern_module, renderer, teapot, out_dir):
    import json

    K, Rt = _opencv_camera()
    path = out_dir / "camera.json"
    path.write_text(json.dumps({"width": 64, "height": 48, "K": K.tolist(),
                                "world_to_camera": Rt.tolist(), "near": 0.1, "far": 100}))
    from_file = renderer.render(teapot, camera=str(path), **SIZE)
    keywords = renderer.render(teapot, intrinsics=K, world_to_camera=Rt, near=0.1, far=100,
                               **SIZE)
    assert (from_file == keywords).all()
    with pytest.raises(ValueError, match="64x48"):
        renderer.render(teapot, camera=str(path), width=32, height=48)


def test_bad_camera_keywords_raise_value_error(renderer, teapot):
    K, Rt = _opencv_camera()
    with pytest.raises(ValueError, match="skew"):
        renderer.render(teapot, intrinsics=[[70, 1, 29], [0, 55, 25], [0, 0, 1]], **SIZE)
    with pytest.raises(ValueError, match="world_to_camera"):
        renderer.render(teapot, intrinsics=K, world_to_camera=2 * Rt, **SIZE)
    with pytest.raises(ValueError, match="intrinsics"):
        renderer.render(teapot, intrinsics=(0, 55, 29, 25), **SIZE)
    with pytest.raises(ValueError, match="not both"):
        renderer.render(teapot, world_to_camera=Rt, camera_to_world=Rt, **SIZE)
