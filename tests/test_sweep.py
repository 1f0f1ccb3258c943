"""`rotorlanding sweep`: grid over scenario keys, parallel = serial, failures recorded, resume."""

import csv
import json
from pathlib import Path

import pytest

from rotorlanding.cli import main
from rotorlanding.sweep import load_sweep

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "scenarios" / "landing_7000rpm.toml"


def _sweep_file(tmp_path, grid, extra=""):
    f = tmp_path / "sweep.toml"
    lines = [f'scenario = "{BASE}"', 'mode = "grid"', extra, "[fixed]", '"operating.t_end" = 0.03', "[grid]"]
    lines += [f'"{k}" = {json.dumps(v)}' for k, v in grid.items()]
    f.write_text("\n".join(lines) + "\n")
    return f


def _rows(out):
    with open(out / "sweep.csv") as fh:
        return list(csv.DictReader(fh))


def test_grid_parallel_equals_serial_failure_recorded_and_resume(tmp_path, capsys):
    # exponent 0.5 is rejected by the scenario schema: that case must fail alone
    f = _sweep_file(tmp_path, {"operating.speed_rpm": [3000.0, 7000.0], "contact.exponent": [1.5, 0.5]})
    assert len(load_sweep(f)["cases"]) == 4
    a, b = tmp_path / "a", tmp_path / "b"
    assert main(["sweep", str(f), "--out", str(a), "--workers", "1"]) == 0
    assert main(["sweep", str(f), "--out", str(b), "--workers", "2"]) == 0
    ra, rb = _rows(a), _rows(b)
    assert [r["status"] for r in ra] == ["ok", "failed", "ok", "failed"]
    assert "contact.exponent" in ra[1]["error"]
    for x, y in zip(ra, rb):
        for k in ("status", "whirl_direction", "DE_max_contact_force_n", "final_rotor_rpm"):
            assert x[k] == y[k]
    assert (a / "whirl_map.png").stat().st_size > 5000
    assert (a / "cases" / "case_0001" / "error.txt").is_file()
    # re-running skips the finished cases and retries the failed ones
    capsys.readouterr()
    assert main(["sweep", str(f), "--out", str(a), "--workers", "1"]) == 0
    assert "(2 already done)" in capsys.readouterr().out


def test_bad_sweep_file(tmp_path, capsys):
    f = _sweep_file(tmp_path, {"operating.speed_rpm": []})
    assert main(["sweep", str(f), "--out", str(tmp_path / "o")]) == 2
    assert "grid.operating.speed_rpm" in capsys.readouterr().err


def test_dask_path_matches_local(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    f = _sweep_file(tmp_path, {"operating.speed_rpm": [3000.0, 7000.0]})
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster:
        assert main(["sweep", str(f), "--out", str(tmp_path / "d"), "--scheduler", cluster.scheduler_address]) == 0
    assert main(["sweep", str(f), "--out", str(tmp_path / "l"), "--workers", "1"]) == 0
    # Dask workers run BLAS single-threaded, which changes float summation order: equal to 1e-9
    for x, y in zip(_rows(tmp_path / "d"), _rows(tmp_path / "l")):
        assert x["whirl_direction"] == y["whirl_direction"]
        for k in ("DE_max_contact_force_n", "final_rotor_rpm", "energy_dissipated_j"):
            assert float(x[k]) == pytest.approx(float(y[k]), rel=1e-9)
