"""Offline Exudyn animation: frame count and moving frames."""

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from rotorlanding.cli import main

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    out = tmp_path_factory.mktemp("run")
    assert main(["run", str(ROOT / "scenarios" / "landing_7000rpm.toml"), "--out", str(out), "--t-end", "0.05",
                 "--quiet", "--no-plots"]) == 0
    return out / "results.h5"


def _frames(path):
    im = Image.open(path)
    frames = []
    for k in range(im.n_frames):
        im.seek(k)
        frames.append(np.asarray(im.convert("RGB"), dtype=int))
    return frames


@pytest.mark.parametrize("view", ["DE", "NDE", "rotor"])
def test_gif_has_expected_frames_that_move(results, tmp_path, view):
    gif = tmp_path / f"{view}.gif"
    assert main(["animate", str(results), "--out", str(gif), "--fps", "200", "--max-frames", "6", "--view", view]) == 0
    frames = _frames(gif)
    assert len(frames) == 6  # 0.05 s x 200 fps = 11 frames, capped at 6
    assert frames[0].shape[2] == 3 and frames[0].shape[0] > 100
    assert np.abs(frames[-1] - frames[0]).sum() > 0  # the rotor moved


def test_bad_animate_input_exit_2(results, tmp_path, capsys):
    assert main(["animate", str(results), "--out", str(tmp_path / "x.gif"), "--view", "side"]) == 2
    assert "--view" in capsys.readouterr().err
    assert main(["animate", str(tmp_path / "missing.h5")]) == 2
    assert main(["animate", str(results), "--fps", "0"]) == 2
