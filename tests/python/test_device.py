"""Choosing the device from Python: Renderer(device=...) and LANTERN_DEVICE (an index into
list_devices() or a name), the explicit choice winning, and a choice that matches nothing
refused with the devices found listed."""
import pytest


@pytest.fixture
def devices(lantern_module, renderer):  # renderer: skips without a Vulkan device
    found = lantern_module.list_devices()
    assert found, "a renderer exists, so a device does"
    return found


def test_lantern_device_picks_by_index_and_by_name(lantern_module, devices, monkeypatch):
    monkeypatch.setenv("LANTERN_DEVICE", "0")
    assert lantern_module.Renderer().device["name"] == devices[0]["name"]
    assert lantern_module.list_devices()[0]["chosen"] == devices[0]["usable"]
    name_part = devices[0]["name"].split(" ")[0].upper()  # e.g. LLVMPIPE: case-insensitive
    monkeypatch.setenv("LANTERN_DEVICE", name_part)
    assert lantern_module.Renderer().device["name"] == devices[0]["name"]


def test_a_choice_that_matches_nothing_lists_the_devices(lantern_module, devices, monkeypatch):
    monkeypatch.setenv("LANTERN_DEVICE", "no-such-device")
    with pytest.raises(lantern_module.Error) as e:
        lantern_module.Renderer()
    text = str(e.value)
    assert text.startswith("no-device: LANTERN_DEVICE=no-such-device: ")
    assert "[0] " + devices[0]["name"] in text
    monkeypatch.setenv("LANTERN_DEVICE", "99")
    with pytest.raises(lantern_module.Error, match="there is no device 99"):
        lantern_module.Renderer()
    # The explicit device wins over the environment.
    assert lantern_module.Renderer(device="0").device["name"] == devices[0]["name"]
    assert not any(d["chosen"] for d in lantern_module.list_devices())
