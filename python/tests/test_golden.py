"""Golden-image tests written the way a user of the module writes them: a frame's planes
against hashes kept in the test, and a rendered image against a golden EXR with thresholds."""

import json
import subprocess

import pytest

import ssrt
from conftest import CLI, plane_hash

# cornell, 64x36, default settings. Any ISA and thread count gives these bits (the
# determinism contract); a change to the renderer's output changes them, on purpose only.
GOLDEN = {
    "display.R": "7537be3faa614b77",
    "display.G": "6ca60cde93802c23",
    "display.B": "472b7fa48740262e",
    "viewZ": "0a8b3a199928fc8e",
    "normal.Y": "fa5ef2bd704aea39",
    "ssgi.R": "4ff6fc2ca3973a36",
    "ssr.G": "e294f21a6aa280b8",
}


@pytest.mark.parametrize("isa,threads", [("auto", 0), ("scalar", 1)])
def test_cornell_planes_match_their_golden_hashes(isa, threads):
    settings = ssrt.RenderSettings(width=64, height=36, isa=isa, threads=threads)
    frame = ssrt.Renderer(settings).render(ssrt.Scene("cornell"))
    assert {name: plane_hash(frame[name])[:16] for name in GOLDEN} == GOLDEN


@pytest.fixture(scope="module")
def golden(tmp_path_factory):
    """The golden image a project would commit: here written once from frame 0."""
    path = tmp_path_factory.mktemp("golden") / "cornell.exr"
    frame = ssrt.Renderer(ssrt.RenderSettings(width=64, height=36)).render(ssrt.Scene("cornell"))
    ssrt.write(frame, path, layers=["color"])
    return path


def render_to(path, **settings):
    scene = ssrt.Scene("cornell")
    renderer = ssrt.Renderer(ssrt.RenderSettings(width=64, height=36, **settings.pop("render", {})))
    frame = renderer.render(scene, ssrt.FrameInput.still(scene, settings.pop("frame", 0)))
    ssrt.write(frame, path, layers=["color"])
    return path


def test_the_same_frame_is_identical(golden, tmp_path):
    result = ssrt.diff(render_to(tmp_path / "a.exr"), golden)
    assert result["identical"] and result["passed"]


def test_other_noise_passes_within_thresholds(golden, tmp_path):
    # Another frame index: other random numbers, the same image up to noise.
    result = ssrt.diff(render_to(tmp_path / "b.exr", frame=7), golden, layers=["color"],
                       max_rel_mse=0.05, max_share=1.0)
    assert not result["identical"]
    assert result["passed"], result["layers"]["color"]


def test_a_real_change_fails(golden, tmp_path):
    result = ssrt.diff(render_to(tmp_path / "c.exr", render={"exposure": 1.5}), golden,
                       layers=["color"], max_rel_mse=0.05, max_share=1.0)
    assert not result["passed"]
    assert result["layers"]["color"]["why"] == "relMSE"


def tuples_to_lists(value):
    """A module dict as json.loads would give it: its tuples (max_at) as lists."""
    if isinstance(value, dict):
        return {k: tuples_to_lists(v) for k, v in value.items()}
    if isinstance(value, (tuple, list)):
        return [tuples_to_lists(v) for v in value]
    return value


def test_diff_is_the_clis_json(golden, tmp_path):
    # ssrt.diff() and `ssrt diff --json` are one document: the same keys and values.
    image = render_to(tmp_path / "d.exr", frame=3)
    result = ssrt.diff(image, golden, max_rel_mse=0.05, max_share=1.0)
    done = subprocess.run([CLI, "diff", str(image), str(golden), "--max-relmse", "0.05",
                           "--max-share", "1", "--json"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    document = json.loads(done.stdout)
    assert {k: document[k] for k in result} == tuples_to_lists(result)
    assert list(ssrt.builtin_scenes().items()) == list(
        json.loads(subprocess.run([CLI, "scenes", "--json"], capture_output=True,
                                  text=True).stdout).items())
