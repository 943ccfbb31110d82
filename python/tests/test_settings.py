"""RenderSettings: keywords, attributes and help from the settings' field table."""

import pytest

import ssrt


def test_every_field_is_a_keyword_and_an_attribute():
    fields = ssrt.RenderSettings.fields()
    assert len(fields) > 50
    defaults = ssrt.RenderSettings()
    for f in fields:
        assert getattr(defaults, f["name"]) == f["default"], f["name"]
        assert f["help"] in ssrt.RenderSettings.__doc__, f["name"]
        assert f["expected"] in ssrt.RenderSettings.__doc__, f["name"]


def test_keywords_set_fields_and_replace_copies():
    s = ssrt.RenderSettings(width=320, shadow_map_size=512, marcher="dda", ssr=False, exposure=2)
    assert (s.width, s.shadow_map_size, s.marcher, s.ssr, s.exposure) == (320, 512, "dda", False, 2.0)
    t = s.replace(height=200)
    assert (t.width, t.height, s.height) == (320, 200, 720)
    assert repr(t) == "RenderSettings(width=320, height=200, shadow_map_size=512, exposure=2.0, ssr=False, marcher='dda')"
    assert t == s.replace(height=200) and t != s


def test_quality_is_applied_before_the_other_keywords():
    low = ssrt.RenderSettings(quality="low")
    ultra = ssrt.RenderSettings(quality="ultra")
    assert low != ultra
    assert ssrt.RenderSettings(quality="ultra", ssr_spp=3).ssr_spp == 3


def test_attributes_are_checked_when_set():
    s = ssrt.RenderSettings()
    s.width = 64
    assert s.width == 64
    with pytest.raises(ValueError, match=r"^width: invalid value 0 \(expected an integer from 1 to 8192\)$"):
        s.width = 0
    assert s.width == 64
    s.isa = "scalar"
    assert s.isa == "scalar"
