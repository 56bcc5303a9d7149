#!/usr/bin/env bash
# Thumbnail time and peak memory per file: `lantern thumbnail -s 256` against F3D's thumbnail
# path (`f3d --dry-run --no-background --output OUT --resolution 256,256`, what F3D's own
# thumbnailer entry runs; Debian's F3D 1.3.1 needs an X display, so it runs under Xvfb) for every
# glTF file under ASSETS, each run ROUNDS times interleaved, the median wall time and the
# largest peak resident set (/usr/bin/time %M) printed per file, then the totals.
# Usage: benchmarks/thumbnails.sh   (LANTERN=path/to/lantern; ASSETS=../shared/assets/gltf-samples;
#        ROUNDS default 3)
set -euo pipefail
cd "$(dirname "$0")/.."
lantern=$(realpath "${LANTERN:-build/dev/apps/lantern/lantern}")
assets=$(realpath "${ASSETS:-../shared/assets/gltf-samples}")
rounds=${ROUNDS:-3}
command -v f3d >/dev/null || { echo "thumbnails.sh: needs f3d (apt install f3d)" >&2; exit 2; }
command -v Xvfb >/dev/null || { echo "thumbnails.sh: needs Xvfb (apt install xvfb)" >&2; exit 2; }
out=$(mktemp -d)
Xvfb :97 -screen 0 1280x1024x24 >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; rm -rf "$out"' EXIT
sleep 1
python3 - "$lantern" "$assets" "$rounds" "$out" <<'PY'
import pathlib, statistics, subprocess, sys
lantern, assets, rounds, out = sys.argv[1], pathlib.Path(sys.argv[2]), int(sys.argv[3]), pathlib.Path(sys.argv[4])
files = sorted(p for p in assets.rglob("*") if p.suffix in (".gltf", ".glb"))
def run(cmd, env=None):
    subprocess.run(["/usr/bin/time", "-f", "%e %M %x", "-o", str(out / "time")] + cmd,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    s, kib, code = (out / "time").read_text().split()[-3:]
    return float(s), int(kib), int(code)
import os
env = dict(os.environ, DISPLAY=":97")
tools = {"lantern": lambda f: [lantern, "thumbnail", "-s", "256", str(f), str(out / "l.png")],
         "f3d": lambda f: ["f3d", "--dry-run", "--no-background", "--output", str(out / "f.png"),
                           "--resolution", "256,256", str(f)]}
print(f"{'file':<56} {'lantern s':>9} {'MiB':>6} {'f3d s':>7} {'MiB':>6}  exit")
totals = {t: [0.0, 0] for t in tools}
for f in files:
    row = {}
    for t, cmd in tools.items():
        times, peak, codes = [], 0, set()
        for r in range(rounds):
            for p in (out / "l.png", out / "f.png"):
                p.unlink(missing_ok=True)
            s, kib, code = run(cmd(f), env)
            times.append(s); peak = max(peak, kib); codes.add(code)
        row[t] = (statistics.median(times), peak / 1024, codes)
        totals[t][0] += row[t][0]; totals[t][1] = max(totals[t][1], peak)
    name = str(f.relative_to(assets))
    print(f"{name[-56:]:<56} {row['lantern'][0]:9.3f} {row['lantern'][1]:6.0f} {row['f3d'][0]:7.3f} "
          f"{row['f3d'][1]:6.0f}  {sorted(row['lantern'][2])} {sorted(row['f3d'][2])}")
print(f"{len(files)} files: lantern {totals['lantern'][0]:.2f} s in all, peak {totals['lantern'][1] / 1024:.0f} MiB; "
      f"f3d {totals['f3d'][0]:.2f} s, peak {totals['f3d'][1] / 1024:.0f} MiB; "
      f"time ratio {totals['lantern'][0] / totals['f3d'][0]:.2f}")
PY
