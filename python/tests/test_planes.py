"""A frame's planes: named as the EXR layers, float32 of the frame's shape, read-only views of
the renderer's memory that keep the frame alive."""

import gc

import numpy as np
import pytest

import ssrt


@pytest.fixture(scope="module")
def frame():
    return ssrt.Renderer(ssrt.RenderSettings(width=96, height=54)).render(ssrt.Scene("cornell"))


def test_shapes_and_dtypes(frame):
    planes = frame.planes()
    assert list(planes) == frame.layers
    assert {"color.R", "display.B", "viewZ", "normal.X", "motion.Y", "ssr.R", "ssgi.G"} <= set(planes)
    for name, plane in planes.items():
        assert plane.shape == (54, 96), name
        assert plane.dtype == np.float32, name
        assert plane.ndim == 2 and plane.strides[1] == 4, name


def test_views_are_read_only(frame):
    plane = frame["viewZ"]
    assert not plane.flags.writeable
    with pytest.raises(ValueError):
        plane[0, 0] = 1.0
    with pytest.raises(ValueError):
        plane.flags.writeable = True


def test_views_share_the_frames_memory(frame):
    a, b = frame["color.R"], frame["color.R"]
    assert a.__array_interface__["data"][0] == b.__array_interface__["data"][0]
    assert np.shares_memory(a, b)
    assert not a.flags.owndata
    # Rows are the plane's, 64-byte aligned: a view, not a packed copy.
    assert a.strides[0] % 64 == 0 and a.__array_interface__["data"][0] % 64 == 0


def test_a_view_keeps_its_frame_alive():
    frame = ssrt.Renderer(ssrt.RenderSettings(width=32, height=18)).render(ssrt.Scene("spheres"))
    plane = frame["viewZ"]
    expected = plane.copy()
    del frame
    gc.collect()
    assert np.array_equal(plane, expected)


def test_values_are_what_the_planes_say(frame):
    view_z, material = frame["viewZ"], frame["materialId"]
    surface = material >= 0
    assert surface.any() and (view_z[surface] > 0).all()
    display = np.stack([frame[f"display.{c}"] for c in "RGB"])
    assert (display >= 0).all() and (display <= 1).all()
    assert "viewZ" in frame and "nosuch" not in frame


def test_pass_times_and_properties(frame):
    assert frame.width == 96 and frame.height == 54 and frame.index == 0
    assert frame.settings.width == 96
    assert all(ms >= 0 for ms in frame.pass_times.values()) and frame.pass_times


def test_compare_is_against_all_the_light_by_default(frame):
    # The default reference's SSGI paths go on until negligible (bounces=0, as `ssrt compare`):
    # more incoming diffuse light than one bounce's, the reflections the same.
    full = ssrt.compare(frame, spp=2)
    one = ssrt.compare(frame, spp=2, bounces=1)
    assert full["reference"]["ref.ssgi.R"].mean() > 1.1 * one["reference"]["ref.ssgi.R"].mean()
    assert np.array_equal(full["reference"]["ref.ssr.G"], one["reference"]["ref.ssr.G"])
