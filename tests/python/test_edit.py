"""Editing a scene between renders without a new renderer (pyrender issue 43): a node
moved, vertices displaced, the picture moves by the pixels the orthographic camera predicts, and
the scene is uploaded once."""
import numpy as np
import pytest

SIZE = 96
# An orthographic box 6 units wide on 96 pixels: 16 pixels per unit, so a move of 0.25 units
# along x is exactly 4 pixels and the coverage is the same, shifted.
VIEW = dict(width=SIZE, height=SIZE, ortho=(-3, 3, -3, 3, 0.1, 100),
            look_at=((0, 0, 10), (0, 0, 0), (0, 1, 0)), background=(0, 0, 0, 0))
PIXELS_PER_UNIT = SIZE / 6.0


def centroid(rgba):
    alpha = rgba[..., 3]
    assert alpha.sum() > 50, "the object is in view"
    ys, xs = np.indices(alpha.shape)
    return (xs * alpha).sum() / alpha.sum(), (ys * alpha).sum() / alpha.sum()


def mesh_node(scene):
    for i, n in enumerate(scene.nodes):
        if n["mesh"] >= 0:
            return i, n
    raise AssertionError("the scene has a mesh node")


@pytest.fixture
def teapot(lantern_module):
    return lantern_module.load("builtin:teapot")  # a fresh one: the tests edit it


def test_moving_a_node_moves_the_picture_without_a_new_upload(renderer, teapot):
    index, node = mesh_node(teapot)
    assert node["matrix"] is None
    before = renderer.render(teapot, **VIEW)
    assert teapot.upload_count == 1
    tx, ty, tz = node["translation"]
    teapot.set_transform(index, translation=(tx + 0.25, ty - 0.5, tz))
    assert teapot.nodes[index]["translation"] == pytest.approx((tx + 0.25, ty - 0.5, tz))
    after = renderer.render(teapot, **VIEW)
    (x0, y0), (x1, y1) = centroid(before), centroid(after)
    assert x1 - x0 == pytest.approx(0.25 * PIXELS_PER_UNIT, abs=0.05)
    assert y1 - y0 == pytest.approx(0.5 * PIXELS_PER_UNIT, abs=0.05), "image rows grow downwards"
    # The coverage is the same, shifted by whole pixels (4 right, 8 down).
    assert np.array_equal(before[:-8, :-4, 3], after[8:, 4:, 3])
    assert teapot.upload_count == 1, "a moved node needs no upload"
    # By name, and as a matrix (rows): back where it was.
    m = np.diag([node["scale"][0], node["scale"][1], node["scale"][2], 1.0])
    m[:3, 3] = (tx, ty, tz)
    teapot.set_transform(node["name"], matrix=m.tolist())
    assert teapot.nodes[index]["matrix"] is not None
    assert np.array_equal(renderer.render(teapot, **VIEW)[..., 3], before[..., 3])


def test_displaced_vertices_move_the_picture_and_only_that_primitive_is_written(renderer,
                                                                                teapot):
    index, node = mesh_node(teapot)
    mesh = node["mesh"]
    before = renderer.render(teapot, **VIEW)
    uploads = teapot.upload_count
    positions = teapot.positions(mesh)
    assert positions.shape[1] == 3 and positions.dtype == np.float32
    # 0.25 world units along x, in the mesh's own units (the node scales it).
    shift = np.float32(0.25 / node["scale"][0])
    teapot.set_vertices(mesh, positions + np.array([shift, 0, 0], dtype=np.float32))
    after = renderer.render(teapot, **VIEW)
    assert centroid(after)[0] - centroid(before)[0] == pytest.approx(4.0, abs=0.05)
    assert teapot.upload_count == uploads, "moved vertices are written, not the whole scene"
    # Squashed to half its width about x = 0 of the mesh: the coverage is about half as wide.
    squashed = positions * np.array([0.5, 1, 1], dtype=np.float32)
    teapot.set_vertices(mesh, squashed, normals=teapot.normals(mesh))
    narrow = renderer.render(teapot, **VIEW)
    width = lambda rgba: np.count_nonzero(rgba[..., 3].max(axis=0) > 0)
    assert width(narrow) == pytest.approx(width(before) / 2, abs=2)
    np.testing.assert_array_equal(teapot.positions(mesh), squashed)
    # Put back: the first picture again, bit for bit.
    teapot.set_vertices(mesh, positions)
    assert np.array_equal(renderer.render(teapot, **VIEW), before)
    assert teapot.upload_count == uploads


def test_a_second_renderer_draws_the_edited_scene(lantern_module, renderer, teapot):
    index, node = mesh_node(teapot)
    positions = teapot.positions(node["mesh"])
    teapot.set_vertices(node["mesh"], positions * np.float32(0.5))
    first = renderer.render(teapot, **VIEW)
    other = lantern_module.Renderer()
    assert np.array_equal(other.render(teapot, **VIEW), first), "the upload carries the edit"


def test_refused_edits_leave_the_scene_as_it_was(renderer, teapot):
    index, node = mesh_node(teapot)
    mesh = node["mesh"]
    positions = teapot.positions(mesh)
    with pytest.raises(ValueError, match="shape"):
        teapot.set_vertices(mesh, positions[:-1])
    bad = positions.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="finite"):
        teapot.set_vertices(mesh, bad)
    with pytest.raises(IndexError, match="mesh 99"):
        teapot.set_vertices(99, positions)
    with pytest.raises(IndexError, match="node 99"):
        teapot.set_transform(99, translation=(0, 0, 0))
    with pytest.raises(ValueError, match="no node is named"):
        teapot.set_transform("no such node", translation=(0, 0, 0))
    with pytest.raises(ValueError, match="zero"):
        teapot.set_transform(index, rotation=(0, 0, 0, 0))
    with pytest.raises(ValueError, match="matrix, or"):
        teapot.set_transform(index, translation=(0, 0, 0), matrix=np.eye(4).tolist())
    assert teapot.nodes[index] == node
    np.testing.assert_array_equal(teapot.positions(mesh), positions)
