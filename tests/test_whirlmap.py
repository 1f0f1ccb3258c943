"""`rotorlanding whirl-map`: per cell the share of drops in each whirl class, its table, JSON and
figure; bad map files are one line (exit 2) before any drop runs."""

import csv
import json
from pathlib import Path

import pytest

from rotorlanding.cli import main

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"


def _map(tmp_path, axes: str, extra: str = "") -> Path:
    f = tmp_path / "map.toml"
    f.write_text(f'scenario = "{BASE}"\ndrops = 2\n{extra}\n[fixed]\n"operating.t_end" = 0.02\n[axes]\n{axes}\n')
    return f


def test_map_cells_probabilities_and_outputs(tmp_path, capsys):
    f = _map(tmp_path, '"operating.speed_rpm" = [3000.0, 7000.0]\n"contact.mu_rad" = [0.15]')
    out = tmp_path / "o"
    assert main(["whirl-map", str(f), "--out", str(out), "--workers", "2"]) == 0
    assert "2 cells x 2 drops = 4 drops" in capsys.readouterr().out
    r = json.loads((out / "whirl_map.json").read_text())
    assert r["drops"] == 4 and len(r["cells"]) == 2
    for c in r["cells"]:
        assert c["n"] == 2 and sum(c["counts"].values()) == 2
        assert sum(c["probability"].values()) == pytest.approx(1.0)
        assert sorted(m["drop"] for m in c["members"]) == [0, 1]
        assert c["peak_force_n"] > 0
    rows = list(csv.DictReader((out / "whirl_map.csv").open()))
    assert [float(x["operating.speed_rpm"]) for x in rows] == [3000.0, 7000.0]
    assert (out / "whirl_map.png").stat().st_size > 1000


@pytest.mark.parametrize("axes,extra,field", [
    ('"operating.speed_rpm" = [3000.0]', "", "axes"),                         # one key
    ('"operating.speed_rpm" = [3000.0]\n"contact.mu_rad" = []', "", "axes.contact.mu_rad"),
    ('"operating.speed_rpm" = [3000.0]\n"contact.no_such_key" = [1.0]', "", "axes.contact.no_such_key"),
    ('"operating.speed_rpm" = [3000.0]\n"contact.mu_rad" = [0.1]', "drops = 0", "drops"),
])
def test_bad_map_file_is_one_line(tmp_path, capsys, axes, extra, field):
    f = _map(tmp_path, axes)
    if extra:
        f.write_text(f.read_text().replace("drops = 2", extra))
    assert main(["whirl-map", str(f), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and field in err and str(f) in err
    assert not (tmp_path / "o").exists()
