"""`rotorlanding run`: outputs, re-run from results.h5, bad input, failure part-way."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.cli import main
from rotorlanding.results import read_results

sys.path.insert(0, str(Path(__file__).parent))
from span_checks import assert_span_matches_the_journal_series  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SCEN = ROOT / "scenarios" / "landing_7000rpm.toml"


def test_run_writes_results_summary_and_figures(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", str(SCEN), "--out", str(out), "--t-end", "0.06", "--quiet"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["complete"] is True
    assert summary["whirl"]["direction"] in ("none", "backward", "forward")
    for b in ("DE", "NDE"):
        bb = summary["bearings"][b]
        assert bb["max_contact_force_n"] > 100.0  # it landed
        lo, hi = bb["vertical_displacement_range_m"]
        assert lo < -0.9 * bb["clearance_m"] and hi < 2 * bb["clearance_m"]  # landed, stayed in the bearing
    assert set(summary["energy"]["dissipated_j"]) >= {"radial_friction", "ball_drag", "windage"}
    assert summary["performance"]["simulated_s"] == pytest.approx(0.06)
    # the deflection along the span, rebuilt from the reduced states, is the stored series at the sleeves
    res0 = read_results(out / "results.h5")
    span = summary["rotor_deflection"]
    assert_span_matches_the_journal_series(span, res0["series"])
    # the envelope along the span (span.png): its largest is the peak, at each station the station's
    nodes = dict(zip(span["x_m"], span["node_peak_m"]))
    assert max(span["node_peak_m"]) == span["peak_m"] and nodes[span["peak_x_m"]] == span["peak_m"]
    assert all(nodes[span["station_x_m"][s]] == p for s, p in span["station_peak_m"].items())
    assert np.all(np.diff(span["x_m"]) > 0) and span["close_clearances_m"] == {"NDE_AMB": 4e-4, "DE_AMB": 4e-4}
    for fig in ("displacements.png", "forces.png", "orbits.png", "speeds.png", "spectrum.png", "energy.png",
                "span.png"):
        assert (out / fig).stat().st_size > 5000
    res = read_results(out / "results.h5")
    assert res["attrs"]["complete"] and res["attrs"]["package_version"]
    assert res["q"].shape == (len(res["time_s"]), len(res["names"]))
    units = json.loads(__import__("h5py").File(out / "results.h5")["states/q"].attrs["units"])
    assert units[0] == "m" and "theta" in res["names"]
    assert res["scenario"]["operating"]["t_end"] == 0.06
    assert not any("close_clearances_m" in w for w in summary["warnings"])  # inside the rig's 0.4 mm AMB gaps
    # the stored scenario reproduces the run; a close clearance is judged after the solve and changes nothing in it,
    # but a gap the rotor runs past is a warning naming it (the model has no contact there)
    out2 = tmp_path / "rerun"
    assert main(["run", str(out / "results.h5"), "--out", str(out2), "--quiet", "--no-plots",
                 "--set", "limits.close_clearances_m.DE_AMB=1e-5"]) == 0
    res2 = read_results(out2 / "results.h5")
    np.testing.assert_allclose(res2["q"], res["q"], atol=1e-12)
    warned = [w for w in json.loads((out2 / "summary.json").read_text())["warnings"] if "close_clearances_m" in w]
    assert len(warned) == 1 and "at DE_AMB, past its 0.01 mm gap" in warned[0]
    assert f"{span['station_peak_m']['DE_AMB'] * 1e3:.3f} mm" in warned[0]
    assert "whirl" in capsys.readouterr().out


@pytest.mark.parametrize("args, field", [
    (["--set", "effects.axial_rubb=true"], "effects.axial_rubb"),
    (["--set", "bearings.DE.clearance=-2e-4"], "bearings.DE.clearance"),
    (["--set", "contact.mu_rad=-0.1"], "contact.mu_rad"),
    (["--set", "amb.t_drop=0.5", "--t-end", "0.4"], "operating.t_end"),
    (["--set", "contact.nonexistent=1"], "contact.nonexistent"),
    (["--set", "contact.mu_rad=abc"], "contact.mu_rad"),
    (["--set", "contact.mu_rad"], "--set"),
    (["--t-end", "-1"], "operating.t_end"),
])
def test_bad_run_input_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys, args, field):
    out = tmp_path / "never"
    assert main(["run", str(SCEN), "--out", str(out), "--quiet"] + args) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and field in err and "Traceback" not in err
    assert not out.exists()


def test_solver_failure_keeps_results_and_exits_nonzero(tmp_path, capsys, monkeypatch):
    import rotorlanding.bearing_kernel as kernel

    calls = {"n": 0}
    real = kernel.landing_rhs

    def poisoned(*args):  # the run diverges after a few thousand residual evaluations
        calls["n"] += 1
        out = real(*args)
        if calls["n"] > 3000:
            out[0] = float("nan")
        return out

    monkeypatch.setattr(kernel, "landing_rhs", poisoned)
    out = tmp_path / "fail"
    assert main(["run", str(SCEN), "--out", str(out), "--t-end", "0.05", "--quiet", "--no-plots"]) == 1
    summary = json.loads((out / "summary.json").read_text())
    assert summary["complete"] is False
    assert 0 < summary["t_reached_s"] < 0.05
    assert "stopped at t =" in summary["message"]
    res = read_results(out / "results.h5")
    assert not res["attrs"]["complete"] and res["time_s"][-1] == pytest.approx(summary["t_reached_s"])
    assert "incomplete" in capsys.readouterr().err


def test_solver_stop_names_the_extreme_quantities_and_the_likely_input(tmp_path, capsys):
    # k_hertz 1e18 is within the plausibility limit at this step (the limit sits where the solver
    # can no longer see the race at all) but the impacts are far harder than any landing's: Exudyn
    # stops after ~0.03 s with "SolveDynamic terminated". The message must say what was extreme.
    paper = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
    rc = main(["run", str(paper), "--set", "contact.k_hertz=1e18", "--t-end", "0.05", "--no-plots", "--quiet",
               "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert rc == 1
    assert "SolveDynamic terminated" in err and "x rotor weight" in err and "step" in err
    assert "likely input: contact.k_hertz" in err
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["complete"] is False and "likely input" in summary["message"]
