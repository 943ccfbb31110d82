"""Bad arguments and bad files raise Python exceptions with one-line messages (the CLI's where
the CLI has the same mistake); none crashes the interpreter."""

import subprocess

import pytest

import ssrt
from conftest import CLI, TEXTURED_GLTF


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("bad")
    (d / "garbage.gltf").write_text("this is not JSON {")
    (d / "truncated.glb").write_bytes(TEXTURED_GLTF.with_name("textured_quad.glb").read_bytes()[:100])
    (d / "no_buffer.gltf").write_text(
        '{"asset": {"version": "2.0"}, "buffers": [{"uri": "missing.bin", "byteLength": 36}]}')
    (d / "garbage.json").write_text("{ not json")
    (d / "unknown_key.json").write_text('{"render": {"widht": 64}}')
    (d / "size_a.exr").touch()
    return d


@pytest.fixture(scope="module")
def frame():
    return ssrt.Renderer(ssrt.RenderSettings(width=32, height=18)).render(ssrt.Scene("cornell"))


@pytest.fixture(scope="module")
def exr(frame, tmp_path_factory):
    path = tmp_path_factory.mktemp("exr") / "a.exr"
    ssrt.write(frame, path)
    return path


S, R = ssrt.RenderSettings, ssrt.Renderer
# (id, call, exception, message regex): the call takes the fixtures' values.
CASES = [
    ("width 0", lambda d, f, e: S(width=0), ValueError,
     r"^width: invalid value 0 \(expected an integer from 1 to 8192\)$"),
    ("width text", lambda d, f, e: S(width="64"), TypeError, r"^width: invalid value '64'"),
    ("width float", lambda d, f, e: S(width=1.5), TypeError, r"^width: invalid value 1.5"),
    ("width bool", lambda d, f, e: S(width=True), TypeError, r"^width: invalid value True"),
    ("width huge", lambda d, f, e: S(width=2**70), ValueError, r"^width: invalid value 1180"),
    ("exposure nan", lambda d, f, e: S(exposure=float("nan")), ValueError, r"^exposure: invalid value nan"),
    ("exposure inf", lambda d, f, e: S(exposure=float("inf")), ValueError, r"^exposure: invalid value inf"),
    ("exposure negative", lambda d, f, e: S(exposure=-1), ValueError, r"^exposure: invalid value -1 \(expected a"),
    ("bool as text", lambda d, f, e: S(ssr="yes"), TypeError, r"^ssr: invalid value 'yes' \(expected True or False\)$"),
    ("unknown choice", lambda d, f, e: S(marcher="bogus"), ValueError,
     r"^marcher: invalid value 'bogus' \(expected one of linear, dda, hiz\)$"),
    ("choice as int", lambda d, f, e: S(marcher=2), TypeError, r"^marcher: invalid value 2"),
    ("unknown keyword", lambda d, f, e: S(widht=64), TypeError, r"^RenderSettings: unknown keyword 'widht'; did you mean width\? \(known: "),
    ("unknown preset", lambda d, f, e: S(quality="insane"), ValueError, r"^quality: invalid value 'insane'"),
    ("unknown isa", lambda d, f, e: S(isa="mmx"), ValueError, r"^isa: "),
    ("fields that disagree", lambda d, f, e: S(hiz_most_detailed_level=3, hiz_start_level=1), ValueError,
     r"^MarchSettings.hizStartLevel: expected a level >= hizMostDetailedLevel"),
    ("unknown scene", lambda d, f, e: ssrt.Scene("nosuch"), ValueError, r"^--scene: unknown scene 'nosuch'"),
    ("missing glTF", lambda d, f, e: ssrt.Scene(d / "missing.gltf"), FileNotFoundError, r"missing.gltf"),
    ("scene not a path", lambda d, f, e: ssrt.Scene(42), TypeError, r"^Scene: name: expected a str"),
    ("glTF not JSON", lambda d, f, e: ssrt.Scene(d / "garbage.gltf"), ValueError, r"garbage.gltf: "),
    ("truncated glb", lambda d, f, e: ssrt.Scene(d / "truncated.glb"), ValueError, r"truncated.glb: "),
    ("glTF buffer missing", lambda d, f, e: ssrt.Scene(d / "no_buffer.gltf"), ValueError, r"no_buffer.gltf: "),
    ("missing shot", lambda d, f, e: ssrt.Shot(d / "missing.json"), FileNotFoundError, r"missing.json"),
    ("shot not JSON", lambda d, f, e: ssrt.Shot(d / "garbage.json"), ValueError, r"garbage.json"),
    ("shot unknown key", lambda d, f, e: ssrt.Shot(d / "unknown_key.json"), ValueError, r"widht"),
    ("renderer of text", lambda d, f, e: R("fast"), TypeError, r"incompatible"),
    ("render a name", lambda d, f, e: R().render("cornell"), TypeError, r"incompatible"),
    ("no frames", lambda d, f, e: R().sequence(f.settings and ssrt.Scene("cornell"), 0), ValueError,
     r"^frames: invalid value 0"),
    ("negative frame index", lambda d, f, e: ssrt.FrameInput.still(ssrt.Scene("cornell"), -1), TypeError,
     r"incompatible"),
    ("unknown plane", lambda d, f, e: f["nosuch"], KeyError, r"no plane 'nosuch'"),
    ("write to a missing folder", lambda d, f, e: ssrt.write(f, d / "no" / "x.exr"), FileNotFoundError, r"x.exr"),
    ("write an unknown format", lambda d, f, e: ssrt.write(f, d / "x.bmp"), ValueError, r"x.bmp"),
    ("unknown compression", lambda d, f, e: ssrt.write(f, d / "x.exr", compression="lzma"), ValueError,
     r"^compression: invalid value 'lzma'"),
    ("unknown layer group", lambda d, f, e: ssrt.write(f, d / "x.exr", layers=["bogus"]), ValueError,
     r"^layers: invalid value 'bogus'"),
    ("diff a missing file", lambda d, f, e: ssrt.diff(d / "missing.exr", e), FileNotFoundError, r"missing.exr"),
    ("diff an empty file", lambda d, f, e: ssrt.diff(d / "size_a.exr", e), RuntimeError, r"size_a.exr"),
    ("negative threshold", lambda d, f, e: ssrt.diff(e, e, threshold=-1), ValueError, r"^threshold"),
    ("compare with no rays", lambda d, f, e: ssrt.compare(f, spp=0), ValueError, r"spp"),
    ("compare with 257 bounces", lambda d, f, e: ssrt.compare(f, spp=1, bounces=257), ValueError,
     r"bounces must be between 1 and 256, or converged"),
    ("compare without ssr", lambda d, f, e: ssrt.compare(R(S(width=16, height=16, ssr=False)).render(
        ssrt.Scene("cornell"))), ValueError, r"ssr and ssgi"),
]


@pytest.mark.parametrize("call,exception,message", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_raises(call, exception, message, files, frame, exr):
    with pytest.raises(exception, match=message) as caught:
        call(files, frame, exr)
    # One line, but for pybind11's own TypeError for arguments of the wrong class, which lists
    # the signatures the function takes.
    if message != r"incompatible":
        assert "\n" not in str(caught.value)


def test_at_least_thirty_bad_inputs():
    assert len(CASES) >= 30


@pytest.mark.parametrize("args,call", [
    (["--scene", "nosuch"], lambda d: ssrt.Scene("nosuch")),
    (["--scene", "{d}/garbage.gltf"], lambda d: ssrt.Scene(d / "garbage.gltf")),
    (["--scene", "{d}/truncated.glb"], lambda d: ssrt.Scene(d / "truncated.glb")),
    (["--scene", "{d}/missing.gltf"], lambda d: ssrt.Scene(d / "missing.gltf")),
    (["--shot", "{d}/unknown_key.json"], lambda d: ssrt.Shot(d / "unknown_key.json")),
], ids=["unknown scene", "glTF not JSON", "truncated glb", "missing glTF", "shot unknown key"])
def test_messages_are_the_clis(args, call, files):
    done = subprocess.run([CLI, "render", *[a.format(d=files) for a in args], "-o", str(files / "x.png")],
                          capture_output=True, text=True)
    assert done.returncode != 0
    with pytest.raises(Exception) as caught:
        call(files)
    assert done.stderr == f"ssrt: error: {caught.value}\n"
