"""Rendering a data set on a Dask cluster: every scene named (a path or builtin:NAME) in each
shading mode, each render a task that a worker runs on its own Lantern renderer
(lantern.render_job keeps one per worker process, so a worker creates its device once).

    python3 dask_render.py OUT_DIR [--workers N] [--scheduler ADDRESS] [SCENE ...]

Without --scheduler a LocalCluster of N worker processes runs on this machine (Debian:
python3-distributed); with it, the tasks go to that cluster's workers, which need the lantern
module and the scenes at the same paths. Prints each file written and the renders per second.
"""
import argparse
import pathlib
import time

import lantern
from distributed import Client, LocalCluster

SHADINGS = ("flat", "gouraud", "phong")


def jobs_for(scenes, out_dir, size):
    """A job per scene and shading mode, each framed automatically as `lantern render` frames a
    scene without a camera, written as a PNG."""
    return [dict(scene=str(path), width=size, height=size, shading=shading,
                 output=str(out_dir / f"{k:03d}_{pathlib.Path(str(path).replace('builtin:', '')).stem}_{shading}.png"))
            for k, path in enumerate(scenes) for shading in SHADINGS]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir", type=pathlib.Path)
    parser.add_argument("scenes", nargs="*", default=["builtin:teapot", "builtin:spheres"])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--scheduler", default=None)
    parser.add_argument("--size", type=int, default=128)
    a = parser.parse_args()
    a.out_dir.mkdir(parents=True, exist_ok=True)
    jobs = jobs_for(a.scenes, a.out_dir, a.size)
    cluster = None if a.scheduler else LocalCluster(n_workers=a.workers, threads_per_worker=1,
                                                     processes=True, dashboard_address=None)
    with Client(a.scheduler or cluster) as client:
        start = time.perf_counter()
        written = client.gather(client.map(lantern.render_job, jobs, pure=False))
        seconds = time.perf_counter() - start
    if cluster is not None:
        cluster.close()
    for path in written:
        print(path)
    print(f"{len(written)} renders in {seconds:.2f} s ({len(written) / seconds:.1f} renders/s)")


if __name__ == "__main__":
    main()
