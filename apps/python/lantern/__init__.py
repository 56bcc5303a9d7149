"""Lantern from Python: render glTF scenes (or the built-in ones) headless into NumPy arrays.

    import lantern
    renderer = lantern.Renderer()                 # the Vulkan device, created once
    scene = lantern.load("builtin:teapot")        # or a .gltf/.glb/.obj/.ply/.stl/.off path
    rgba = renderer.render(scene, width=256, height=256)   # (256, 256, 4) float32, linear
    lantern.write_image("teapot.png", rgba)

Keep one Renderer for many renders: it keeps the device, the compiled pipelines and the scene's
upload between calls. docs/python.md is the guide.
"""
import atexit as _atexit

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

__all__ = ["Error", "Renderer", "Scene", "build_info", "builtin_scenes", "frames",
           "list_devices", "load", "render", "write_image"]


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
