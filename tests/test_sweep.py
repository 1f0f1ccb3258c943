"""`rotorlanding sweep`: grid over scenario keys, parallel = serial, failures recorded, resume."""

import csv
import importlib.util
import json
import os
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from rotorlanding import sweep_run
from rotorlanding.cli import main
from rotorlanding.sweep_run import load_sweep

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "scenarios" / "landing_7000rpm.toml"


@pytest.fixture(autouse=True)
def _keep_environment():
    """Dask's LocalCluster writes OMP_NUM_THREADS=1 (and the OpenBLAS / MKL twins) into this
    process's os.environ for its workers. Left there, every later subprocess of the test session
    runs BLAS single-threaded while this process does not, and results that must match bit for
    bit (test_coastdown's kill-and-resume) differ in the 8th digit."""
    before = dict(os.environ)
    yield
    os.environ.clear()
    os.environ.update(before)


def _sweep_file(tmp_path, grid, extra=""):
    f = tmp_path / "sweep.toml"
    lines = [f'scenario = "{BASE}"', 'mode = "grid"', extra, "[fixed]", '"operating.t_end" = 0.03', "[grid]"]
    lines += [f'"{k}" = {json.dumps(v)}' for k, v in grid.items()]
    f.write_text("\n".join(lines) + "\n")
    return f


def _rows(out):
    with open(out / "sweep.csv") as fh:
        return list(csv.DictReader(fh))


def _summary(row):
    return {k: v for k, v in row.items() if k != "wall_s"}


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
    # summaries do not depend on the number of workers: every column but the wall time is equal
    assert [_summary(r) for r in ra] == [_summary(r) for r in rb]
    for x in (a, b):
        assert json.loads((x / "cases" / "case_0000" / "summary.json").read_text())["complete"]
        assert not list(x.glob("cases/*/.running"))
    assert (a / "whirl_map.png").stat().st_size > 5000
    assert (a / "cases" / "case_0001" / "error.txt").is_file()
    # re-running skips the finished cases and retries the failed ones
    capsys.readouterr()
    assert main(["sweep", str(f), "--out", str(a), "--workers", "1"]) == 0
    assert "(2 already done)" in capsys.readouterr().out


def test_a_case_whose_values_changed_is_run_again_not_reused(tmp_path, capsys):
    """Case folders are matched by their inputs, not by number alone: the same folder swept again
    with another value for case 0 runs it (it used to report the old result under the new value);
    swept again unchanged, it is reused."""
    out = tmp_path / "s"
    for rpm, done in ((3000.0, 0), (7000.0, 0), (7000.0, 1)):
        f = _sweep_file(tmp_path, {"operating.speed_rpm": [rpm]})
        capsys.readouterr()
        assert main(["sweep", str(f), "--out", str(out), "--workers", "1"]) == 0
        assert f"({done} already done)" in capsys.readouterr().out
        row = _rows(out)[0]
        assert float(row["operating.speed_rpm"]) == rpm
        assert abs(float(row["final_rotor_rpm"]) - rpm) < 0.05 * rpm   # the result of that speed


def test_bad_sweep_file(tmp_path, capsys):
    f = _sweep_file(tmp_path, {"operating.speed_rpm": []})
    assert main(["sweep", str(f), "--out", str(tmp_path / "o")]) == 2
    assert "grid.operating.speed_rpm" in capsys.readouterr().err


def test_dask_path_matches_local(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    # exponent 0.5 is rejected by the scenario schema: cases 1 and 3 fail, on Dask as locally
    f = _sweep_file(tmp_path, {"operating.speed_rpm": [3000.0, 7000.0], "contact.exponent": [1.5, 0.5]})
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster:
        assert main(["sweep", str(f), "--out", str(tmp_path / "d"), "--scheduler", cluster.scheduler_address]) == 0
    assert main(["sweep", str(f), "--out", str(tmp_path / "l"), "--workers", "1"]) == 0
    # local workers run BLAS single-threaded like Dask's: identical summaries, not just close ones
    d, loc = _rows(tmp_path / "d"), _rows(tmp_path / "l")
    assert [r["status"] for r in d] == ["ok", "failed", "ok", "failed"]
    assert [_summary(r) for r in d] == [_summary(r) for r in loc]
    assert "contact.exponent" in d[1]["error"]
    assert (tmp_path / "d" / "cases" / "case_0001" / "error.txt").is_file()


def test_dask_task_error_recorded_as_failed_case(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    from rotorlanding.distributed import map_on_dask

    jobs = [(0, str(BASE), [], str(tmp_path), False), (1, str(BASE), [], str(tmp_path), False)]
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False) as cluster:
        rows = map_on_dask(_raise_for_case_1, jobs, cluster.scheduler_address,
                           on_error=lambda job, err: sweep_run._failed_row(job[0], err, job[3]))
    rows = sorted(rows, key=lambda r: r["case"])
    assert rows[0] == {"case": 0, "status": "ok"}
    assert rows[1]["status"] == "failed" and "RuntimeError: worker lost" in rows[1]["error"]
    assert (tmp_path / "cases" / "case_0001" / "error.txt").is_file()


def _raise_for_case_1(job):
    if job[0] == 1:
        raise RuntimeError("worker lost")
    return {"case": job[0], "status": "ok"}


def _crash_case_1(job):
    """Stand-in for run_case: case 1 kills its worker process (like a segfault in the solver)."""
    sweep_run._marker(job).parent.mkdir(parents=True, exist_ok=True)
    sweep_run._marker(job).write_text("")
    if job[0] == 1:
        os._exit(3)
    time.sleep(0.2)
    sweep_run._marker(job).unlink()
    return {"case": job[0], "status": "ok", "error": ""}


def test_worker_crash_is_recorded_and_the_others_complete(tmp_path, monkeypatch):
    monkeypatch.setattr(sweep_run, "run_case", _crash_case_1)
    jobs = [(i, str(BASE), [], str(tmp_path), False) for i in range(5)]
    rows = sorted(sweep_run._run_local(jobs, 2), key=lambda r: r["case"])
    assert [r["case"] for r in rows] == [0, 1, 2, 3, 4]
    assert [r["status"] for r in rows] == ["ok", "failed", "ok", "ok", "ok"]
    assert "worker process died" in rows[1]["error"]
    assert (tmp_path / "cases" / "case_0001" / "error.txt").is_file()
    assert not list(tmp_path.glob("cases/*/.running"))


def test_scheduler_errors_are_one_line(tmp_path, capsys, monkeypatch):
    f = _sweep_file(tmp_path, {"operating.speed_rpm": [3000.0]})
    if importlib.util.find_spec("distributed") is not None:
        monkeypatch.setattr("rotorlanding.distributed.CONNECT_TIMEOUT_S", 2)
        # nothing listens there: a clear one-line error, no traceback
        assert main(["sweep", str(f), "--out", str(tmp_path / "o"), "--scheduler", "tcp://127.0.0.1:9"]) == 2
        err = capsys.readouterr().err
        assert "cannot connect to a Dask scheduler" in err and len(err.strip().splitlines()) == 1
    # dask missing
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    assert main(["sweep", str(f), "--out", str(tmp_path / "o"), "--scheduler", "tcp://127.0.0.1:9"]) == 2
    err = capsys.readouterr().err
    assert "needs dask.distributed" in err and len(err.strip().splitlines()) == 1


def test_craig_bampton_cache_gives_the_same_numbers():
    from rotorlanding import landing
    from rotorlanding.reduction import craig_bampton
    from rotorlanding.scenario import load_scenario

    cache = sweep_run._CraigBamptonCache(craig_bampton)
    sc = load_scenario(BASE)
    fe = landing.assemble(sc.rotor)
    red = sc.rotor.reduction
    a = cache(fe, red.boundary_stations, red.modes)
    b = cache(landing.assemble(sc.rotor), red.boundary_stations, red.modes)
    c = craig_bampton(fe, red.boundary_stations, red.modes)
    assert cache.hits == 1 and a.M is not b.M
    for m in ("M", "K", "C", "G", "T"):
        assert np.array_equal(getattr(a, m), getattr(c, m)) and np.array_equal(getattr(b, m), getattr(c, m))
    assert cache(fe, red.boundary_stations, red.modes - 1).n == c.n - 1  # other settings: recomputed
