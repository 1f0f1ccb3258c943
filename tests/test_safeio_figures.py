"""Figures are written atomically (safeio.save_figure): a kill while one is written leaves the
previous picture, never a truncated PNG, and no temporary behind a failed write."""

import os
import subprocess
import sys

import pytest


def _figure(path, label):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rotorlanding.safeio import save_figure

    fig, ax = plt.subplots(figsize=(2, 2))
    ax.plot([0, 1], [0, len(label)], label=label)  # the label changes the picture
    try:
        return save_figure(fig, path, dpi=50)
    finally:
        plt.close(fig)


def test_save_figure_writes_a_png_and_leaves_no_temporary(tmp_path):
    from PIL import Image

    p = _figure(tmp_path / "a.png", "first")
    with Image.open(p) as im:
        assert im.format == "PNG" and im.size == (100, 100)
    assert sorted(x.name for x in tmp_path.iterdir()) == ["a.png"]
    # a write that fails (a folder that does not exist) raises and leaves nothing behind
    with pytest.raises(OSError):
        _figure(tmp_path / "missing" / "b.png", "second")
    assert sorted(x.name for x in tmp_path.iterdir()) == ["a.png"]


def test_a_kill_while_a_figure_is_written_keeps_the_previous_one(tmp_path):
    from rotorlanding.safeio import FAULT_ENV

    p = _figure(tmp_path / "a.png", "first")
    before = p.read_bytes()
    code = ("import sys; sys.path.insert(0, %r); from test_safeio_figures import _figure; "
            "_figure(%r, 'second, longer label')") % (os.path.dirname(__file__), str(p))
    r = subprocess.run([sys.executable, "-c", code], env={**os.environ, FAULT_ENV: "figure"}, timeout=120)
    assert r.returncode == -9                      # killed between the render and the rename
    assert p.read_bytes() == before                # the previous picture, whole
    _figure(p, "second, longer label")             # and a later write goes through
    assert p.read_bytes() != before
