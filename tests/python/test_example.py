"""apps/examples/python/turntable.py, the module's example, run as a user runs it: it writes a
PNG per frame and an EXR with depth, and prints each frame's coverage."""
import os
import pathlib
import re
import subprocess
import sys

import pytest

SOURCE = pathlib.Path(os.environ.get("LANTERN_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


def test_turntable_writes_its_frames(lantern_module, renderer, out_dir):
    # `renderer` makes the test skip without a Vulkan device; the example makes its own.
    run = subprocess.run([sys.executable, str(SOURCE / "apps/examples/python/turntable.py"),
                          str(out_dir), "3"], capture_output=True, text=True, timeout=240)
    assert run.returncode == 0, run.stderr
    pngs = sorted(p.name for p in out_dir.glob("teapot_*.png"))
    assert pngs == ["teapot_00.png", "teapot_01.png", "teapot_02.png"]
    for name in pngs:
        assert (out_dir / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    exr = out_dir / "teapot_last.exr"
    assert exr.read_bytes()[:4] == b"\x76\x2f\x31\x01", "an OpenEXR file"
    coverage = [float(c) for c in re.findall(r"(\d+(?:\.\d+)?)% of the pixels covered", run.stdout)]
    assert len(coverage) == 3 and all(1.0 < c < 90.0 for c in coverage), run.stdout
