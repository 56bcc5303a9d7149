#!/usr/bin/env python3
"""memory_loop.py: resident memory (RSS) of one Python process rendering the same small picture
many times through the module, the loop lantern_memory_loop runs through the C++ API. Prints RSS
after renders 1, 100, 1000, 10000 (those within RENDERS) and the last, and the growth after the
first hundred; exits 1 when it exceeds MAX_GROWTH percent (given).

Usage: PYTHONPATH=build/ci/python memory_loop.py [RENDERS] [MAX_GROWTH] [SCENE] [SIZE]"""
import os
import sys

import lantern


def resident_mib():
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE") / 1048576.0


def main(renders="10000", max_growth="-1", scene="builtin:spheres-animated", size="64"):
    renders, max_growth, size = int(renders), float(max_growth), int(size)
    if renders < 100:
        sys.exit("RENDERS must be at least 100")
    renderer = lantern.Renderer()
    loaded = lantern.load(scene)
    checksum = 0.0
    at100 = 0.0
    print(f"python {scene} {size}x{size}: resident MiB after render", end="", flush=True)
    for i in range(1, renders + 1):
        rgba = renderer.render(loaded, time=(i % 60) / 30.0, width=size, height=size)
        checksum += float(rgba[size // 2, size // 2, 0])
        del rgba
        if i == 100:
            at100 = resident_mib()
        if i in (1, 100, 1000, 10000) or i == renders:
            print(f" {i}: {resident_mib():.1f}", end="", flush=True)
    growth = 100.0 * (resident_mib() - at100) / at100
    print(f"\ngrowth after render 100: {growth:+.2f}% (checksum {checksum:g})")
    if 0 <= max_growth < growth:
        print(f"resident memory grew {growth:.2f}% after render 100, more than {max_growth}%",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
