#!/usr/bin/env bash
# Installs the Debian package with apt on THIS machine, uses it as a user would, removes it and
# checks that nothing is left behind. Meant for a throwaway Debian 12, after scripts/package.sh:
#   ../shared/tools/fresh-machine.sh --timeout 4000 /work/main /work/shared 'scripts/package.sh && scripts/test-package.sh'
# Checks: `lantern render builtin:teapot -o t.png`, `man lantern`, the bash completion, the
# thumbnailer entry run as a file manager runs it, `python3 -c "import lantern"` and the Python
# tests against the installed module, a CMake consumer (apps/examples/headless) and a
# pkg-config consumer built against /usr; then `apt-get purge` and every path gone.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
deb=$(realpath "${1:-$(ls "$src"/build/package/lantern_*.deb)}")
step() { echo "== $*" >&2; }
export DEBIAN_FRONTEND=noninteractive
step "install $deb"
apt-get install -y --no-install-recommends "$deb" >&2
apt-get install -y --no-install-recommends man-db python3-pytest python3-matplotlib python3-distributed pkg-config g++ cmake bash-completion >&2
echo "installed size: $(dpkg-query -W -f '${Installed-Size}' lantern) KiB; package $(stat -c %s "$deb") bytes"
mapfile -t files < <(dpkg -L lantern | while read -r p; do [[ -f $p ]] && echo "$p"; done)
work=$(mktemp -d)
cd "$work"
step "lantern render"
lantern render builtin:teapot -o t.png --width 64 --height 64 >/dev/null
test -s t.png
step "man lantern"
man -P cat lantern | grep -q "lantern-render(1)"
man -P cat lantern-thumbnail | grep -q -- "--time-limit"
step "bash completion"
bash -c 'source /usr/share/bash-completion/bash_completion; _completion_loader lantern; complete -p lantern' | grep -q _lantern
step "thumbnailer entry"
exec_line=$(sed -n 's/^Exec=//p' /usr/share/thumbnailers/lantern.thumbnailer)
box="$src/../shared/assets/gltf-samples/Box/glTF-Binary/Box.glb"
cmd=${exec_line//%s/64}; cmd=${cmd//%i/$box}; cmd=${cmd//%o/$work/thumb.png}
eval "$cmd"
test -s "$work/thumb.png"
step "python"
python3 -c "import lantern, sys; print(lantern.__file__); r = lantern.render('builtin:teapot', width=32, height=24); assert r.shape == (24, 32, 4); assert lantern.Picture is not None"
python3 -c "import lantern; assert lantern.__file__.startswith('/usr/lib/python3/dist-packages/')"
for t in test_module test_render test_aov test_edit test_pool test_stubs; do
    env -u PYTHONPATH LANTERN_PYTHON_BUILT=1 LANTERN_CLI=/usr/bin/lantern LANTERN_SOURCE_DIR="$src" LANTERN_TEST_OUTPUT="$work/py" \
        python3 "$src/tests/python/run_pytest.py" "$src/tests/python/$t.py" --needs-module >&2
done
step "CMake consumer"
cmake -S "$src/apps/examples/headless" -B "$work/cmake" >&2
cmake --build "$work/cmake" >&2
(cd "$work" && "$work/cmake/lantern-headless-example" >&2)
step "pkg-config consumer"
cat >"$work/pc.cpp" <<'CPP'
#include <lantern/Lantern.h>
#include <cstdio>
int main() {
    auto r = lantern::Renderer::create(lantern::RendererDesc{});
    if (!r) return 1;
    auto scene = lantern::loadScene("builtin:teapot");
    lantern::RenderOptions o;
    o.width = 32;
    o.height = 24;
    auto image = r->render(*scene, o, 0.0);
    std::printf("%dx%d\n", image->width, image->height);
    return image && image->width == 32 ? 0 : 1;
}
CPP
g++ "$work/pc.cpp" -o "$work/pc" $(pkg-config --cflags --libs lantern)
"$work/pc" | grep -q 32x24
step "purge"
apt-get purge -y lantern >&2
left=0
for f in "${files[@]}"; do
    if [[ -e $f ]]; then echo "left behind: $f" >&2; left=1; fi
done
for d in /usr/include/lantern /usr/lib/python3/dist-packages/lantern /usr/share/doc/lantern /usr/lib/x86_64-linux-gnu/cmake/Lantern; do
    if [[ -e $d ]]; then echo "left behind: $d" >&2; left=1; fi
done
((left == 0))
echo "test-package: every check passed; ${#files[@]} files installed and removed"
