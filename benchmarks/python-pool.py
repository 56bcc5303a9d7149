"""Renders per second of lantern.Pool at 1, 2, ... processes (docs/python.md): N jobs of one
scene at SIZE x SIZE, each picture sent back to the parent, rounds interleaved; the pool's start
(spawned workers, each creating its device) is timed apart.

    PYTHONPATH=build/dev/python python3 benchmarks/python-pool.py [--jobs 96] [--size 256]
        [--processes 1,2] [--rounds 2] [--scene builtin:teapot]
"""
import argparse
import os
import time

import lantern


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--jobs", type=int, default=96)
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--processes", default=f"1,{os.cpu_count()}")
    p.add_argument("--rounds", type=int, default=2)
    p.add_argument("--scene", default="builtin:teapot")
    a = p.parse_args()
    jobs = [dict(scene=a.scene, width=a.size, height=a.size, time=k / 24.0) for k in range(a.jobs)]
    counts = sorted({int(n) for n in a.processes.split(",")})
    print(f"{a.jobs} jobs of {a.scene} at {a.size}x{a.size}, {os.cpu_count()} cores")
    for r in range(a.rounds):
        for n in counts:
            start = time.perf_counter()
            with lantern.Pool(processes=n) as pool:
                pool.render(jobs[:n])  # every worker makes its device and loads the scene
                started = time.perf_counter()
                pool.render(jobs)
                done = time.perf_counter()
            print(f"round {r + 1}: {n} processes: {a.jobs / (done - started):.1f} renders/s "
                  f"(start {started - start:.2f} s)")


if __name__ == "__main__":
    main()
