#!/usr/bin/env python3
"""render_loop.py: renders per second of one scene through the Python module, the loop that
lantern_render_loop runs through the C++ API (benchmarks/python-vs-cpp.sh times the two
interleaved). Usage: render_loop.py [SCENE] [WIDTH] [HEIGHT] [RENDERS] [WARMUP]"""
import sys
import time

import lantern


def main(scene="builtin:teapot", width="256", height="256", renders="200", warmup="10"):
    width, height, renders, warmup = int(width), int(height), int(renders), int(warmup)
    renderer = lantern.Renderer()
    loaded = lantern.load(scene)
    checksum = 0.0  # uses every picture, as the C++ loop does

    def loop(n):
        nonlocal checksum
        for _ in range(n):
            rgba = renderer.render(loaded, width=width, height=height)
            checksum += float(rgba[height // 2, width // 2, 0])

    loop(warmup)
    t0 = time.perf_counter()
    loop(renders)
    seconds = time.perf_counter() - t0
    print(f"python {scene} {width}x{height}: {renders} renders in {seconds:.3f} s: "
          f"{renders / seconds:.2f} renders/s (checksum {checksum:g})")


if __name__ == "__main__":
    main(*sys.argv[1:])
