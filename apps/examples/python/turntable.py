#!/usr/bin/env python3
"""turntable.py: Lantern from Python: the Utah teapot seen from a camera circling it, rendered
into NumPy arrays by one Renderer (the device is made once), with a red key light added to the
scene; each frame's coverage is measured in NumPy and the frames are written as PNG (and the
last one as EXR with its depth).

Usage: PYTHONPATH=<build>/python python3 turntable.py [OUTPUT_FOLDER] [FRAMES]
(an installed Lantern puts the module on Python's path: no PYTHONPATH needed).
"""
import math
import pathlib
import sys

import numpy as np

import lantern


def main(out_dir="turntable", frames=8):
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    renderer = lantern.Renderer()
    print(f"device: {renderer.device['name']}")
    scene = lantern.load("builtin:teapot")
    scene.add_light("directional", direction=(-1, -0.5, -1), color=(0.6, 0.1, 0.1), name="key")
    for k in range(frames):
        angle = 2 * math.pi * k / frames
        eye = (5 * math.sin(angle), 2.0, 5 * math.cos(angle))
        rgba, depth = renderer.render(scene, width=256, height=256, shading="phong", msaa=4,
                                      look_at=(eye, (0, 0.5, 0), (0, 1, 0)),
                                      perspective=(35, 0.1, 100), background=(0, 0, 0, 0),
                                      depth=True)
        coverage = float(rgba[..., 3].mean())
        nearest = float(depth[np.isfinite(depth)].min())
        path = out / f"teapot_{k:02d}.png"
        lantern.write_image(str(path), rgba)
        print(f"{path}: {coverage:.1%} of the pixels covered, nearest surface {nearest:.2f}")
    lantern.write_image(str(out / "teapot_last.exr"), rgba, depth=depth)
    print(out / "teapot_last.exr")


if __name__ == "__main__":
    main(*(sys.argv[1:2] or ["turntable"]), *(map(int, sys.argv[2:3])))
