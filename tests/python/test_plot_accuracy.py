"""benchmarks/plot_accuracy.py: the accuracy plot drawn with matplotlib from the CSV that
`lantern bench accuracy` writes, with a legend naming every curve it draws."""
import csv
import os
import pathlib
import subprocess
import sys

import pytest

SCRIPT = pathlib.Path(os.environ.get("LANTERN_SOURCE_DIR", pathlib.Path(__file__).parents[2])) \
    / "benchmarks" / "plot_accuracy.py"
COLUMNS = ["scene", "shininess", "width", "height", "shading", "segments", "msaa",
           "ms_per_frame", "rmse", "interior_rmse", "pareto_interior", "pareto_whole"]


def write_csv(path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for mode, cost in (("flat", 1.0), ("phong", 2.0)):
            for msaa in (1, 4):
                for seg in (8, 32):
                    ms = cost * msaa * seg / 8
                    err = 0.1 / seg / msaa / cost
                    w.writerow(["sphere", 128, 64, 48, mode, seg, msaa, ms, err, err / 2,
                                int(mode == "phong" and msaa == 1), int(seg == 32)])


def test_plot_has_a_legend_entry_for_every_curve(tmp_path):
    pytest.importorskip("matplotlib", reason="python3-matplotlib is not installed")
    csv_path = tmp_path / "accuracy.csv"
    write_csv(csv_path)
    svg, png = tmp_path / "accuracy.svg", tmp_path / "accuracy.png"
    run = subprocess.run([sys.executable, str(SCRIPT), str(csv_path), "-o", str(svg), "-o",
                          str(png)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    text = svg.read_text()
    for label in ("flat, 1x MSAA", "flat, 4x MSAA", "phong, 1x MSAA", "phong, 4x MSAA",
                  "Pareto front", "1e-3 acceptance", "sphere, shininess 128, 64x48",
                  "interior RMSE", "whole-image RMSE"):
        assert label in text, label
    assert "gouraud" not in text, "no legend entry for a curve that is not drawn"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # The same CSV gives the same SVG (no date in it).
    again = tmp_path / "again.svg"
    subprocess.run([sys.executable, str(SCRIPT), str(csv_path), "-o", str(again)], check=True,
                   capture_output=True)
    assert again.read_text() == text


def test_an_empty_csv_is_refused(tmp_path):
    pytest.importorskip("matplotlib", reason="python3-matplotlib is not installed")
    csv_path = tmp_path / "empty.csv"
    csv_path.write_text(",".join(COLUMNS) + "\n")
    run = subprocess.run([sys.executable, str(SCRIPT), str(csv_path), "-o",
                          str(tmp_path / "x.svg")], capture_output=True, text=True)
    assert run.returncode == 1 and "no rows" in run.stderr
