"""The same frame from Python as from the `ssrt` command: every plane, to the bit."""

import pytest

import ssrt
from conftest import TEXTURED_GLTF, SOURCE, plane_hash, run_cli


def frame_hashes(frame):
    return {name: plane_hash(frame[name]) for name in frame.layers}


def file_hashes(path):
    """The file's planes by name, less R, G, B: the colour layer again, for viewers."""
    layers = ssrt.read_layers(path)
    for c in "RGB":
        assert plane_hash(layers.pop(c)) == plane_hash(layers[f"color.{c}"])
    return {name: plane_hash(plane) for name, plane in layers.items()}


@pytest.mark.parametrize("scene", ["cornell", "spheres", str(TEXTURED_GLTF)])
def test_every_plane_matches_the_cli(scene, small, tmp_path):
    exr = tmp_path / "cli.exr"
    run_cli("render", "--scene", scene, "--width", small["width"], "--height", small["height"],
            "-o", exr)
    frame = ssrt.Renderer(ssrt.RenderSettings(**small)).render(ssrt.Scene(scene))
    expected = file_hashes(exr)
    assert len(expected) >= 40
    assert frame_hashes(frame) == expected


@pytest.mark.parametrize("mode", ["mixed", "world"])
def test_ssr_and_ssgi_traced_in_world_space_match_the_cli(mode, small, tmp_path):
    """The renderer builds the scene's world rays itself, as `ssrt render` does."""
    exr = tmp_path / "cli.exr"
    run_cli("render", "--scene", "cornell", "--ssr-trace", mode, "--ssgi-trace", mode,
            "--width", small["width"], "--height", small["height"], "-o", exr)
    scene = ssrt.Scene("cornell")
    renderer = ssrt.Renderer(ssrt.RenderSettings(**small, ssr_trace=mode, ssgi_trace=mode))
    frame = renderer.render(scene)
    expected = file_hashes(exr)
    assert frame_hashes(frame) == expected
    # A second render reuses the scene's world rays, to the same bits.
    assert frame_hashes(renderer.render(scene)) == expected
    screen = ssrt.Renderer(ssrt.RenderSettings(**small)).render(scene)
    assert plane_hash(screen["color.R"]) != plane_hash(frame["color.R"])


def test_a_shot_sequence_matches_the_cli(small, tmp_path):
    shot_file = SOURCE / "examples" / "shots" / "spheres_orbit.json"
    out = tmp_path / "orbit.exr"
    run_cli("render", "--shot", shot_file, "--frames", 3, "--warmup-frames", 1,
            "--width", small["width"], "--height", small["height"], "-o", out)
    shot = ssrt.Shot(shot_file)
    settings = shot.settings.replace(**small)
    frames = list(ssrt.Renderer(settings).sequence(shot.scene, 3, warmup_frames=1))
    assert [f.index for f in frames] == [shot.first_frame + i for i in range(3)]
    for i, frame in enumerate(frames):
        assert frame_hashes(frame) == file_hashes(tmp_path / f"orbit_{i:04d}.exr"), i


def test_written_exr_is_the_cli_file(small, tmp_path):
    run_cli("render", "--width", small["width"], "--height", small["height"],
            "-o", tmp_path / "cli.exr")
    frame = ssrt.Renderer(ssrt.RenderSettings(**small)).render(ssrt.Scene("cornell"))
    ssrt.write(frame, tmp_path / "py.exr")
    assert (tmp_path / "py.exr").read_bytes() == (tmp_path / "cli.exr").read_bytes()
