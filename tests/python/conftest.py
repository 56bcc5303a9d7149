"""conftest.py: what the Python tests share: one Renderer for the whole run (the device is made
once, as the module intends), skipping without a Vulkan device, and a fresh output folder."""
import os
import pathlib

import pytest


@pytest.fixture(scope="session")
def lantern_module():
    import lantern

    return lantern


@pytest.fixture(scope="session")
def renderer(lantern_module):
    try:
        r = lantern_module.Renderer(validation=True)
    except lantern_module.Error as e:  # no Vulkan device: what the GPU tests skip on
        pytest.skip(f"no Vulkan device: {e}")
    if not r.validation_enabled:
        print("note: VK_LAYER_KHRONOS_validation is not installed; validation not checked")
    yield r
    assert r.validation_messages == 0, \
        "the Vulkan validation layer reported messages during the Python tests (see stderr)"


@pytest.fixture
def out_dir(request):
    base = pathlib.Path(os.environ.get("LANTERN_TEST_OUTPUT", "/tmp/lantern-python-tests"))
    folder = base / request.node.name
    folder.mkdir(parents=True, exist_ok=True)
    for old in folder.iterdir():
        old.unlink()
    return folder
