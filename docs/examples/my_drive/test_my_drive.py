"""Golden tests of one scenario with pytest (docs/testing-your-scenario.md):
    BELTSIM=/path/to/beltsim python3 -m pytest test_my_drive.py
The scenario runs once for the module; each test compares one output with the stored one
(expected/) and shows beltsim compare's one-line reason when it fails."""
import os
import pathlib
import subprocess

import pytest

HERE = pathlib.Path(__file__).resolve().parent
BELTSIM = os.environ.get("BELTSIM", "beltsim")


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    folder = tmp_path_factory.mktemp("my_drive")
    # the same pixels on every machine: Mesa's software renderer
    env = dict(os.environ, GALLIUM_DRIVER="llvmpipe")
    subprocess.run([BELTSIM, "run", str(HERE / "my_drive.lua"), "--out", str(folder)], check=True, env=env)
    return folder


def compare(actual, expected, *options):
    p = subprocess.run([BELTSIM, "compare", str(actual), str(expected), *options], capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr


def test_timeseries(out):
    # rtol 1e-2 (atol by unit) and 1e-3 on the creep columns: over the step one element more in a
    # gross-slip arc makes (docs/testing-your-scenario.md)
    compare(out / "timeseries.csv", HERE / "expected" / "timeseries.csv", "--rtol", "1e-2", "--atol", "1=1e-3")


def test_frame(out):
    # without its text: another machine's font draws the same drive's digits a few pixels differently
    compare(out / "frames" / "frame_00015.png", HERE / "expected" / "frame_00015.png", "--ignore-text")
