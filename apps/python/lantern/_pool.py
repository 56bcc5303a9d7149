"""Rendering many jobs over processes: lantern.render_job (one job, on the process's own
renderer: what a Pool worker or a Dask task calls) and lantern.Pool (worker processes started
with `spawn`, each holding its own Renderer)."""
import multiprocessing as _mp

_scenes = {}
_renderer = None
_device = ""


def _worker_renderer():
    global _renderer
    if _renderer is None:
        from ._lantern import Renderer

        _renderer = Renderer(device=_device)
    return _renderer


def render_job(job):
    """Renders one job on this process's renderer (made on first use and kept): `job` is a dict
    with "scene" (a path or builtin:NAME; loaded once per process and kept), optionally "output"
    (a .png or .exr path to write) and any keyword of Renderer.render. Returns the output's path
    when one was given, else what Renderer.render returns."""
    from ._lantern import load, write_image

    if not isinstance(job, dict) or "scene" not in job:
        raise ValueError("a job is a dict with at least \"scene\"")
    options = dict(job)
    path = options.pop("scene")
    output = options.pop("output", None)
    scene = _scenes.get(path)
    if scene is None:
        scene = _scenes[path] = load(path)
    result = _worker_renderer().render(scene, **options)
    if output is None:
        return result
    rgba = result[0] if isinstance(result, tuple) else result
    write_image(str(output), rgba)
    return str(output)


def _init_worker(device):
    global _device
    _device = device


class Pool:
    """Renders a list of jobs (dicts, as lantern.render_job takes) over `processes` worker
    processes (default: one per core), each with its own Renderer and Vulkan device, started with
    `spawn` so that no device is ever shared with a forked child. Results come back in the jobs'
    order: pictures (copied from the worker) or, for jobs with "output", the paths written.

        with lantern.Pool(processes=2) as pool:
            pictures = pool.render([{"scene": "builtin:teapot", "width": 64, "height": 64}] * 8)
    """

    def __init__(self, processes=None, device=""):
        self._pool = _mp.get_context("spawn").Pool(processes, initializer=_init_worker,
                                                    initargs=(device,))
        self.processes = self._pool._processes

    def render(self, jobs, chunksize=1):
        """Every job rendered; a list of results in the jobs' order. An error in a job is
        raised here, as it was raised in the worker."""
        return self._pool.map(render_job, list(jobs), chunksize)

    def imap(self, jobs, chunksize=1):
        """The results one by one, in the jobs' order, as they are done."""
        return self._pool.imap(render_job, jobs, chunksize)

    def close(self):
        """Waits for the workers to finish and lets them go."""
        self._pool.close()
        self._pool.join()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if exc[0] is None:
            self.close()
        else:
            self._pool.terminate()
            self._pool.join()
        return False
