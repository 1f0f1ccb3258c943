"""Offline picture of a landing (``rotorlanding animate``, ``Landing.animate``): frame counts,
what the pixels show, the MP4 decoding to its frames, bad input."""

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import rotorlanding as rl
from rotorlanding.animate import frame_indices
from rotorlanding.cli import main

ROOT = Path(__file__).resolve().parents[1]
T_END = 0.02


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    out = tmp_path_factory.mktemp("run")
    assert main(["run", str(ROOT / "scenarios" / "landing_7000rpm.toml"), "--out", str(out), "--t-end", str(T_END),
                 "--quiet", "--no-plots"]) == 0
    return out / "results.h5"


def _gif_frames(path):
    im = Image.open(path)
    frames = []
    for k in range(im.n_frames):
        im.seek(k)
        frames.append(np.asarray(im.convert("RGB"), dtype=int))
    return frames


def test_frame_times_are_one_per_fps_step():
    t = np.linspace(0.0, 1.0, 1001)
    idx = frame_indices(t, 20.0)
    assert len(idx) == 21  # floor(1.0 s x 20) + 1
    assert np.allclose(t[idx], np.arange(21) / 20.0)
    assert len(frame_indices(t, 20.0, max_frames=6)) == 6


def test_gif_frame_count_and_motion(results, tmp_path):
    gif = tmp_path / "a.gif"
    assert main(["animate", str(results), "--out", str(gif), "--fps", "200", "--size", "640x360"]) == 0
    frames = _gif_frames(gif)
    assert len(frames) == int(T_END * 200) + 1  # 5 frames: 0, 5, 10, 15, 20 ms
    assert frames[0].shape == (360, 640, 3)
    assert np.abs(frames[-1] - frames[0]).sum() > 0  # the rotor moved
    assert not list(tmp_path.glob(".*"))  # no temporary file left


def test_still_shows_rotor_clearance_circle_and_contact_force(results, tmp_path):
    png = tmp_path / "still.png"
    info = rl.Landing.load(results).animate(png, at=T_END)
    im = np.asarray(Image.open(png).convert("RGB"), dtype=int)
    assert im.shape == (720, 1280, 3) and info["frames"] == 1
    # the 3D part holds the rotor: a good share of non-white, grey-blue steel pixels
    left = im[:, :info["left_width_px"]]
    assert (left.sum(axis=2) < 600).mean() > 0.05
    dark = im.sum(axis=2) < 300
    for name, (cx, cy, r) in info["clearance_circles_px"].items():
        ang = np.linspace(0, 2 * np.pi, 720, endpoint=False)

        def dark_share(radius):
            hits = 0
            for a in ang:
                c, w = int(round(cx + radius * np.cos(a))), int(round(cy - radius * np.sin(a)))
                hits += dark[w - 1:w + 2, c - 1:c + 2].any()
            return hits / len(ang)

        assert dark_share(r) > 0.4, name          # the dashed clearance circle is where expected
        assert dark_share(1.2 * r) < 0.05, name    # and nothing dark just outside it
    # landed by 20 ms: a contact force arrow (pure red) in the orbit panels
    right = im[:, info["left_width_px"]:]
    red = (right[..., 0] > 180) & (right[..., 1] < 60) & (right[..., 2] < 60)
    assert red.sum() > 50


def test_mp4_decodes_to_its_frames(results, tmp_path):
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    mp4 = tmp_path / "a.mp4"
    assert main(["animate", str(results), "--out", str(mp4), "--fps", "150", "--size", "640x360",
                 "--view", "DE"]) == 0
    reader = imageio_ffmpeg.read_frames(str(mp4))
    meta = next(reader)
    n = sum(1 for _ in reader)
    assert tuple(meta["size"]) == (640, 360)
    assert n == int(T_END * 150) + 1  # 4 frames


def test_bad_animate_input_exit_2(results, tmp_path, capsys):
    cases = [(["--view", "side"], "--view"), (["--fps", "0"], "--fps"), (["--out", str(tmp_path / "a.txt")], "--out"),
             (["--size", "big"], "--size"), (["--size", "641x360"], "--size"),
             (["--out", str(tmp_path / "s.png"), "--at", "5"], "--at"), (["--play-fps", "0"], "--play-fps")]
    for args, field in cases:
        capsys.readouterr()
        assert main(["animate", str(results), "--out", str(tmp_path / "x.gif"), *args]) == 2, args
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and field in err[0], (args, err)
    assert main(["animate", str(tmp_path / "missing.h5")]) == 2
    assert not list(tmp_path.iterdir())


def test_failed_render_leaves_no_file(results, tmp_path, monkeypatch):
    import rotorlanding.animate as an

    calls = {"n": 0}
    draw = an._Frame.draw

    def failing(self, k, image):
        calls["n"] += 1
        if calls["n"] == 2:
            raise RuntimeError("disk gone")
        return draw(self, k, image)

    monkeypatch.setattr(an._Frame, "draw", failing)
    with pytest.raises(RuntimeError):
        an.animate(results, tmp_path / "a.gif", fps=200, size=(640, 360))
    assert not list(tmp_path.iterdir())  # neither the target nor its temporary name
