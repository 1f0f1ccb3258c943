"""Every script in examples/ runs (its --short version in the default selection, the full one
marked slow) and writes its figures."""

import resource
import subprocess
import sys
import time
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

CASES = {
    "build_rotor_and_land.py": ["campbell.png", "orbits.png", "displacements.png", "results.h5", "rotor.toml"],
    "paper_forward_whirl.py": ["forward_whirl.png", "spectrum.png", "results.h5"],
    "ross_landing.py": ["rotor.png", "campbell.png", "orbits.png", "displacements.png", "forces.png", "results.h5",
                        "rotor.toml"],
    "whirl_map.py": ["whirl_map.png", "orbits.png", "sweep.csv"],
    "coastdown.py": ["coastdown_overview.png", "speeds.png", "coastdown.png", "results.h5", "summary.json"],
    "diagnose_measured.py": ["measured_vs_model.png", "features.png", "report.md", "report.json"],
}


def _run(script: str, out: Path, *extra) -> str:
    def cpu():
        r = resource.getrusage(resource.RUSAGE_CHILDREN)
        return r.ru_utime + r.ru_stime

    t0, c0 = time.perf_counter(), cpu()
    proc = subprocess.run([sys.executable, str(EXAMPLES / script), "--out", str(out), *extra], cwd=EXAMPLES,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    for name in CASES[script]:
        assert (out / name).stat().st_size > 1000, name
    return proc.stdout, time.perf_counter() - t0, cpu() - c0


def test_every_example_is_tested():
    assert sorted(p.name for p in EXAMPLES.glob("*.py") if not p.name.startswith("_")) == sorted(CASES)


@pytest.mark.parametrize("script", sorted(CASES))
def test_example_short(script, tmp_path):
    stdout, wall, cpu = _run(script, tmp_path, "--short")
    # no time limit asserted: speed is measured in benchmarks/, never in a timed test (a first run
    # compiles the kernel, and a loaded machine inflates even CPU seconds through BLAS spin-waits)
    print(f"{script} --short: {cpu:.1f} s CPU, {wall:.1f} s wall")
    if script == "paper_forward_whirl.py":
        assert "whirl at the DE bearing: forward" in stdout  # the paper's result, from the API
    if script == "ross_landing.py":  # the ROSS file, read without ROSS
        assert "Rotor('compressor rotor from ROSS': 11 sections, 4 disks" in stdout
    if script == "diagnose_measured.py":
        # the paper's story at two speeds: axial rub is what the model without it lacks. On the
        # session-15 rig rotor it is the best candidate and brings back the measured forward whirl
        # at both speeds, but it is not named: Table 2's DE force and displacement stay at twice the
        # measured range with it (the open gap of issue 15), so the gap falls only 2.62 -> 2.16 and
        # its score does not pay for the fitted mu_ax. The naming itself is the strict xfail
        # test_diagnose.py::test_paper_story_short_two_speeds.
        import json

        step = json.loads((tmp_path / "report.json").read_text())["steps"][0]
        best = step["candidates"][0]
        assert (best["effect"], best["kind"]) == ("axial_rub", "effect"), step["candidates"][:3]
        assert best["directions"] == ["forward", "forward"], best
        assert best["gap"] < step["gap_before"]
        assert step["whirl_direction_fixed_at"] == ["rpm_7000", "rpm_10000"]
    if script == "whirl_map.py":  # every case of the grid is a row of the table the Sweep read back
        import rotorlanding as rl

        assert [r["status"] for r in rl.Sweep.load(tmp_path).table] == ["ok"] * 4
        assert "contact.mu_rad" in (tmp_path / "sweep_input.toml").read_text()  # rerunnable from the CLI


@pytest.mark.slow
@pytest.mark.parametrize("script", sorted(CASES))
def test_example_full(script, tmp_path):
    _run(script, tmp_path)


@pytest.mark.parametrize("name", [p.stem for p in sorted(EXAMPLES.glob("*.py")) if not p.name.startswith("_")])
def test_importing_an_example_runs_nothing(name, tmp_path, capsys, monkeypatch):
    """A user can import the example and call ``main(argv)``: importing builds, prints and writes
    nothing (the script's work sits in ``main``)."""
    import importlib

    monkeypatch.syspath_prepend(str(EXAMPLES))
    monkeypatch.chdir(tmp_path)
    mod = importlib.import_module(name)
    assert callable(mod.main) and capsys.readouterr().out == "" and not any(tmp_path.iterdir())
