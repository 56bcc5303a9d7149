"""Lantern from Python: render glTF scenes (or the built-in ones) headless into NumPy arrays.

    import lantern
    renderer = lantern.Renderer()                 # the Vulkan device, created once
    scene = lantern.load("builtin:teapot")        # or a .gltf/.glb/.obj/.ply/.stl/.off path
    rgba = renderer.render(scene, width=256, height=256)   # (256, 256, 4) float32, linear
    lantern.write_image("teapot.png", rgba)

Keep one Renderer for many renders: it keeps the device, the compiled pipelines and the scene's
upload between calls. A rendered picture shows itself in a notebook (lantern.Picture);
lantern.Pool renders a list of jobs over worker processes. docs/python.md is the guide.
"""
import atexit as _atexit
import functools as _functools

from ._lantern import (  # noqa: F401  (the module's API)
    Error,
    Renderer,
    Scene,
    __version__,
    build_info,
    builtin_scenes,
    list_devices,
    load,
    write_image,
)

from ._pool import Pool, render_job  # noqa: F401

try:  # NumPy is what a render returns; without it the rest of the module still imports
    from ._picture import Picture, as_picture as _as_picture, png_bytes  # noqa: F401
except ImportError:  # pragma: no cover
    Picture = png_bytes = None

    def _as_picture(array):
        return array

__all__ = ["Error", "Picture", "Pool", "Renderer", "Scene", "build_info", "builtin_scenes",
           "frames", "list_devices", "load", "png_bytes", "render", "render_job", "write_image"]

Error.__doc__ = ("Raised when rendering fails: no Vulkan device, the device lost, out of memory "
                 "(a RuntimeError; a refused scene or option is a ValueError, a file an OSError)")

_render_arrays = Renderer.render


@_functools.wraps(_render_arrays)
def _render_pictures(self, scene, **options):
    result = _render_arrays(self, scene, **options)
    if isinstance(result, tuple):
        return (_as_picture(result[0]),) + tuple(result[1:])
    return _as_picture(result)


Renderer.render = _render_pictures


def frames(renderer, scene, first=None, last=None, fps=24.0, **options):
    """Renders frames first..last (inclusive) of the scene's animation, frame k at time k / fps,
    as `lantern render --frames first-last --fps fps` does; yields (k, picture) where picture is
    what renderer.render returns for those options. Without first and last: the frames the
    animation spans (0 to round(end * fps))."""
    start, end = scene.animation_range
    if first is None:
        first = max(0, int(round(start * fps)))
    if last is None:
        last = max(first, int(round(end * fps)))
    for k in range(first, last + 1):
        yield k, renderer.render(scene, time=k / fps, **options)


Renderer.frames = frames
Renderer.frames.__doc__ = frames.__doc__

_default_renderer = None


def render(scene, **options):
    """Renders with a process-wide Renderer made on first use (and kept, so a loop of calls does
    not create the device again). `scene` is a Scene or a path / builtin:NAME (loaded on every
    call: load it once with lantern.load for loops). Keywords as Renderer.render."""
    global _default_renderer
    if _default_renderer is None:
        _default_renderer = Renderer()
    if not isinstance(scene, Scene):
        scene = load(scene)
    return _default_renderer.render(scene, **options)


@_atexit.register
def _release_default_renderer():
    # The device goes before the interpreter tears its modules down.
    global _default_renderer
    _default_renderer = None
