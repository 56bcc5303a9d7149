"""Python where its users work: pictures that notebooks show (_repr_png_, the PNG write_image
writes), lantern.Pool rendering a list of jobs over spawned worker processes, and the same jobs
on a Dask LocalCluster (python3-distributed): every way gives the picture one renderer gives."""
import numpy as np
import pytest

JOBS = [dict(scene="builtin:teapot", width=48, height=32),
        dict(scene="builtin:spheres", width=40, height=40, shading="gouraud"),
        dict(scene="builtin:teapot", width=48, height=32, look_at=((0, 2, 6), (0, 0, 0), (0, 1, 0))),
        dict(scene="builtin:spheres", width=32, height=24, background=(0, 0, 0, 0))]


def serial(lantern_module, renderer):
    out = []
    for job in JOBS:
        options = dict(job)
        out.append(np.asarray(renderer.render(lantern_module.load(options.pop("scene")), **options)))
    return out


def test_a_picture_shows_as_the_png_write_image_writes(lantern_module, renderer, out_dir):
    rgba = renderer.render(lantern_module.load("builtin:teapot"), width=64, height=48,
                           background=(0, 0, 0, 0))
    assert isinstance(rgba, lantern_module.Picture) and isinstance(rgba, np.ndarray)
    png = rgba._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and b"sRGB" in png[:64]
    assert rgba[..., 0]._repr_png_() is None, "a slice is not a picture"
    assert not rgba.flags.owndata, "still the renderer's memory, no copy"
    image = pytest.importorskip("matplotlib.image", reason="matplotlib reads the PNGs back")
    (out_dir / "shown.png").write_bytes(png)
    lantern_module.write_image(str(out_dir / "written.png"), rgba)
    shown = image.imread(str(out_dir / "shown.png"))
    written = image.imread(str(out_dir / "written.png"))
    assert shown.shape == written.shape == (48, 64, 4)
    assert np.abs(shown - written).max() <= 1.0 / 255.0 + 1e-6
    assert shown[..., 3].min() == 0.0 and shown[..., 3].max() == 1.0


def test_the_pool_renders_what_one_renderer_renders(lantern_module, renderer, out_dir):
    expected = serial(lantern_module, renderer)
    with lantern_module.Pool(processes=2) as pool:
        assert pool.processes == 2
        pictures = pool.render(JOBS)
        written = pool.render([dict(job, output=str(out_dir / f"job{k}.png")) for k, job in enumerate(JOBS)])
        with pytest.raises(Exception) as refused:
            pool.render([dict(scene=str(out_dir / "missing.gltf"))])
    assert "missing.gltf" in str(refused.value)
    assert len(pictures) == len(JOBS)
    for k, (got, want) in enumerate(zip(pictures, expected)):
        assert isinstance(got, lantern_module.Picture)
        assert np.array_equal(np.asarray(got), want), f"job {k} differs from one renderer's picture"
    assert written == [str(out_dir / f"job{k}.png") for k in range(len(JOBS))]
    assert all((out_dir / f"job{k}.png").stat().st_size > 100 for k in range(len(JOBS)))


def test_a_dask_local_cluster_renders_the_same_jobs(lantern_module, renderer):
    distributed = pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")
    expected = serial(lantern_module, renderer)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        futures = client.map(lantern_module.render_job, JOBS, pure=False)
        pictures = client.gather(futures)
    for k, (got, want) in enumerate(zip(pictures, expected)):
        assert np.array_equal(np.asarray(got), want), f"job {k} differs from one renderer's picture"


def test_the_dask_example_renders_its_data_set(lantern_module, renderer, out_dir):
    # apps/examples/python/dask_render.py as a user runs it: a LocalCluster of two workers.
    pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")
    import os
    import pathlib
    import subprocess
    import sys

    source = pathlib.Path(os.environ.get("LANTERN_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
    run = subprocess.run([sys.executable, str(source / "apps/examples/python/dask_render.py"),
                          str(out_dir), "builtin:teapot", "builtin:spheres", "--workers", "2",
                          "--size", "48"], capture_output=True, text=True, timeout=240)
    assert run.returncode == 0, run.stderr
    names = sorted(p.name for p in out_dir.glob("*.png"))
    assert names == sorted(f"{k:03d}_{scene}_{shading}.png" for k, scene in enumerate(("teapot", "spheres"))
                           for shading in ("flat", "gouraud", "phong"))
    assert "6 renders in" in run.stdout
    flat = np.asarray(renderer.render(lantern_module.load("builtin:teapot"), width=48, height=48,
                                      shading="flat"))
    image = pytest.importorskip("matplotlib.image", reason="matplotlib reads the PNGs back")
    written = image.imread(str(out_dir / "000_teapot_flat.png"))
    assert np.abs(written - image.imread(_png(lantern_module, flat, out_dir))).max() == 0.0


def _png(lantern_module, rgba, out_dir):
    path = str(out_dir / "reference.png")
    lantern_module.write_image(path, rgba)
    return path
