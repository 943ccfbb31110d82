"""examples/make_training_data.py runs and writes what it says."""

import os
import subprocess
import sys

import numpy as np

from conftest import SOURCE


def test_training_data_example(tmp_path):
    done = subprocess.run(
        [sys.executable, SOURCE / "examples" / "make_training_data.py", "--frames", "2",
         "--width", "48", "--height", "27", "--spp", "4", "--out", tmp_path],
        capture_output=True, text=True, env=os.environ)
    assert done.returncode == 0, done.stderr
    assert done.stdout.count("noisy relMSE") == 2
    for i in range(2):
        data = np.load(tmp_path / f"frame_{i:04d}.npz")
        assert data["noisy"].shape == (3, 27, 48)
        assert data["guides"].shape == (11, 27, 48)
        assert data["reference"].shape == (3, 27, 48)
        assert np.isfinite(data["reference"]).all()
        assert not np.array_equal(data["noisy"], data["reference"])
