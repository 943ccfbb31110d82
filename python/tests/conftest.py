"""Shared by the ssrt module's tests: the built `ssrt` command and the source tree.

ctest runs these with PYTHONPATH at build/python, SSRT_CLI naming build/ssrt and
SSRT_SOURCE_DIR the checkout (tests/CMakeLists.txt); by hand:
    PYTHONPATH=build/python SSRT_CLI=build/ssrt /usr/bin/python3 -m pytest python/tests
"""

import hashlib
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("SSRT_SOURCE_DIR", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("SSRT_CLI", str(SOURCE / "build" / "ssrt"))
TEXTURED_GLTF = SOURCE / "tests" / "fuzz" / "seeds" / "gltf" / "material_maps_datauri.gltf"


def plane_hash(array):
    """SHA-256 of a plane's float bits, row by row (padding excluded)."""
    return hashlib.sha256(np.ascontiguousarray(array, dtype=np.float32).tobytes()).hexdigest()


def run_cli(*args):
    """Runs `ssrt ARGS...` quietly; fails the test with its stderr when it fails."""
    done = subprocess.run([CLI, *map(str, args), "--quiet"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done


@pytest.fixture(scope="session")
def small():
    """The size every test renders at unless it needs another."""
    return {"width": 96, "height": 54}
