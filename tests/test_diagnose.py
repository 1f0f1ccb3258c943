"""Model-gap diagnosis on data with a hidden effect (short runs)."""

import json
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.cli import main
from rotorlanding.diagnose_run import _simulate_features, diagnose

sys.path.insert(0, str(Path(__file__).parent))
from sensor_model import THRUST, known_rig_model  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
C = 2e-4
PAPER_TABLE = ROOT / "scenarios" / "measured" / "paper_table2_fig39.toml"
PAPER_MODEL = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
# the hidden-effect cases run on the first rig rotor (a known rig whose effect signatures these
# cases were sized for; the fitted 104 kg rotor slows down three times less from the same windage)
# and with the bearing values they were sized on (tests/known_rig_bearings.toml: the paper rig's
# calibration may move, these cases test the method): sensor_model.known_rig_model


@pytest.fixture
def model_without_windage(tmp_path):
    return known_rig_model(tmp_path / "model.toml", ["windage"])


def test_hidden_windage_is_named_and_the_gap_shrinks(model_without_windage):
    measured = _simulate_features(model_without_windage, ["effects.windage=true", "spin.c_w2=1.5e-6"], C)
    # the effects only: a true missing effect against the default parameter candidates is
    # test_cli_with_csv_data's case (and the bench's, benchmarks/diagnose_bench.py)
    res = diagnose(measured, model_without_windage, clearance=C, workers=1, maxiter=8, parameters=[])
    assert res["named_effect"] == "windage"
    assert res["gap_after"] <= 0.5 * res["gap_before"]
    c_w2 = float(res["calibrated_overrides"][-1].split("=")[1])
    assert c_w2 == pytest.approx(1.5e-6, rel=0.1)
    # the fit's own uncertainty names the scenario key and holds the truth
    span = res["steps"][0]["fit_span"]
    assert span["keys"] == ["spin.c_w2"] and any(lo <= 1.5e-6 <= hi for lo, hi in span["ranges"]), span


def test_clean_data_gives_no_false_alarm(model_without_windage):
    measured = _simulate_features(model_without_windage, [], C)
    res = diagnose(measured, model_without_windage, clearance=C, workers=1, maxiter=4)
    assert res["named_effect"] is None and res["gap_before"] < 0.1


def test_cli_with_csv_data(model_without_windage, tmp_path, capsys):
    # measured CSV from a run with the hidden effect, drop instant shifted by 5 s, one channel dropped
    run = tmp_path / "truth"
    assert main(["run", str(model_without_windage), "--out", str(run), "--quiet", "--no-plots",
                 "--set", "effects.windage=true", "--set", "spin.c_w2=1.5e-6"]) == 0
    from rotorlanding.results import read_results

    r = read_results(run / "results.h5")
    s = r["series"]
    cols = np.column_stack([r["time_s"] + 5.0, s["DE_y_m"], s["DE_z_m"], s["rotor_speed_rpm"],
                            s["DE_race_speed_rpm"]])
    csv = tmp_path / "rig.csv"
    np.savetxt(csv, cols, delimiter=",", header="time_s,DE_y_m,DE_z_m,rotor_speed_rpm,DE_inner_race_speed_rpm",
               comments="")
    out = tmp_path / "diag"
    assert main(["diagnose", "--measured", str(csv), "--scenario", str(model_without_windage), "--out", str(out),
                 "--workers", "1", "--time-offset-s", "5.0", "--maxiter", "4", "--ensemble", "1"]) == 0
    rep = json.loads((out / "report.json").read_text())
    assert rep["named_effect"] == "windage"
    assert "windage" in capsys.readouterr().out
    assert (out / "report.md").read_text().count("windage") >= 2 and (out / "overlay.png").stat().st_size > 10000


@pytest.mark.parametrize("hidden, value", [("windage", 1.2e-6), ("ball_drag", 1.5e-2)])
def test_similar_signatures_told_apart(tmp_path, hidden, value):
    """Windage (rotor) and ball drag (inner races) both slow things down; the model lacks both."""
    from rotorlanding.benchdata import make_hidden_effect_data
    from rotorlanding.features import extract_features
    from rotorlanding.measured import detect_drop, load_measurement

    model = known_rig_model(tmp_path / "model.toml", ["windage", "ball_drag"])
    truth = make_hidden_effect_data(model, hidden, tmp_path / "rig.csv", seed=3, value=value, drop_channel="NDE_y_m")
    m = load_measurement(tmp_path / "rig.csv")
    assert not m.has("NDE_y_m")
    t_drop = detect_drop(m, C)
    assert t_drop == pytest.approx(truth["drop_at_s"], abs=2e-3)
    feats = extract_features(m.shifted(t_drop), clearance=C)
    res = diagnose(feats, model, clearance=C, candidates=["windage", "ball_drag"], parameters=[], workers=2,
                   maxiter=8)
    assert res["named_effect"] == hidden, res["steps"]
    assert res["gap_after"] <= 0.5 * res["gap_before"]


# issue 20: the noise gate is measured now (diagnose._noise_gate). On this rig the model without
# ribbon cross-coupling, dropped from 4 points of a 5 um circle, differs from its centred drop by gaps
# of 0.04-0.38 (gate, the 95 % prediction bound: 0.61); ribbon cross-coupling at eta 0.4 leaves a gap
# of 0.48, inside it. The fit that named it under the old constant gate 0.3 landed on eta 0.07 for the
# true 0.4 (a needle of a chaotic landing's gap, not a recovery). Kept as strict expected failures
# until the features are ensemble statistics (issue 20, point 1): if they pass, the gate or the case moved.
RIBBON_WITHIN_NOISE = pytest.mark.xfail(strict=True, reason="ribbon cross-coupling at eta 0.4: gap 0.48 within the "
                                        "measured noise gate 0.55-0.61 of this chaotic landing (issue 20)")


@pytest.mark.parametrize("hidden, value, thrust", [
    pytest.param("ribbon_cross_coupling", 0.4, False, marks=RIBBON_WITHIN_NOISE),
    ("radial_friction", 0.3, False),
    ("axial_rub", 0.3, True),
    ("outer_race_coulomb", 0.3, True),
])
def test_more_hidden_effects_named(tmp_path, hidden, value, thrust):
    """With windage and ball drag above: six effects recovered from noisy, resampled, shifted data."""
    from rotorlanding.benchdata import make_hidden_effect_data
    from rotorlanding.features import extract_features
    from rotorlanding.measured import detect_drop, load_measurement

    model = known_rig_model(tmp_path / "model.toml", [hidden], extra=THRUST if thrust else "")
    make_hidden_effect_data(model, hidden, tmp_path / "rig.csv", seed=1, value=value)
    m = load_measurement(tmp_path / "rig.csv")
    feats = extract_features(m.shifted(detect_drop(m, C)), clearance=C)
    res = diagnose(feats, model, clearance=C, workers=2, maxiter=8, parameters=[])
    assert res["named_effect"] == hidden, res["steps"]
    assert res["gap_after"] <= 0.5 * res["gap_before"]


@pytest.mark.slow  # duplicates coverage: the pair is test_diagnose_refit.py's, ribbon-within-noise the ribbon case above
@RIBBON_WITHIN_NOISE
def test_two_missing_effects_found_with_max_effects_2(tmp_path):
    """Windage is named (gap 0.99 -> 0.46, -54 %); the ribbon part left after it (0.46) is below the
    measured gate 0.55 of the model as given, so it is not named (it would take the gap to 0.16).
    The pair of similar size found by the joint re-fit: tests/test_diagnose_refit.py."""
    from rotorlanding.benchdata import make_hidden_effect_data
    from rotorlanding.features import extract_features
    from rotorlanding.measured import detect_drop, load_measurement

    model = known_rig_model(tmp_path / "model.toml", ["windage", "ribbon_cross_coupling"])
    make_hidden_effect_data(model, "windage", tmp_path / "rig.csv", seed=2, value=1.2e-6,
                            extra=["effects.ribbon_cross_coupling=true", "bearings.DE.eta=0.4", "bearings.NDE.eta=0.4"])
    m = load_measurement(tmp_path / "rig.csv")
    feats = extract_features(m.shifted(detect_drop(m, C)), clearance=C)
    res = diagnose(feats, model, clearance=C, workers=2, maxiter=8, max_effects=2, parameters=[])
    assert set(res["named_effects"]) == {"windage", "ribbon_cross_coupling"}, res["steps"]
    assert res["gap_after"] <= 0.5 * res["gap_before"]


def test_diagnose_bad_data_clear_errors(model_without_windage, tmp_path, capsys):
    t = np.arange(0, 0.05, 1e-4)
    short = tmp_path / "short.csv"
    np.savetxt(short, np.column_stack([t, 0 * t, -C * (t > 0.01)]), delimiter=",", header="time_s,DE_y_m,DE_z_m",
               comments="")
    other = tmp_path / "other.csv"
    t2 = np.arange(0, 0.5, 1e-4)
    np.savetxt(other, np.column_stack([t2, 0 * t2, -5e-3 * (t2 > 0.01)]), delimiter=",",
               header="time_s,DE_y_m,DE_z_m", comments="")
    mm = tmp_path / "mm.csv"
    mm.write_text("time_s,DE_y_mm\n0,1\n0.1,2\n")
    for f, word in ((short, "too short"), (other, "different rotor"), (mm, "DE_y_mm")):
        assert main(["diagnose", "--measured", str(f), "--scenario", str(model_without_windage),
                     "--out", str(tmp_path / "o")]) == 2
        err = capsys.readouterr().err
        assert word in err and "Traceback" not in err and err.count("\n") == 1


def _whirl_fixed(rep):
    return [p["name"] for p in rep["points"] if p["whirl_before"] != p["whirl_measured"] == p["whirl_after"]]


def test_paper_story_short_two_speeds(tmp_path, capsys):
    """The paper's story, short: the forward-whirl combined landing without axial rub (and without
    windage, the competing candidate) vs the paper's experimental features at 7000 and 10000 rpm
    (taken from scenarios/measured/paper_table2_fig39.toml), 0.5 s runs.

    Strict xfail from session 15 to 27 (on the session-15 rotor axial rub brought the whirl back but
    took the gap only from 2.62 to 2.16: Table 2's DE force stayed at the distance cap); it passes on
    the session-28 rotor, whose Table 2 force and displacement lie nearer the paper's.

    Measured on the rig of 2026-11 (not yet calibrated to the paper's frequencies): gap 2.71 ->
    1.83 (-32 %), axial_rub named (mu_ax at its lower bound 0.05), whirl none -> forward at both
    speeds (78 / 79 Hz vs 65 / 77 Hz); windage leaves the gap at 2.71. 34 simulations, ~40 s on 2
    workers under load."""
    data = tomllib.loads(PAPER_TABLE.read_text())
    data["points"] = {k: v for k, v in data["points"].items() if k in ("rpm_7000", "rpm_10000")}
    table = tmp_path / "paper_two_speeds.json"
    table.write_text(json.dumps(data))
    out = tmp_path / "diag"
    assert main(["diagnose", "--measured", str(table), "--scenario", str(PAPER_MODEL), "--set", "effects.axial_rub=false",
                 "--set", "effects.windage=false", "--candidates", "axial_rub,windage", "--parameters", "none",
                 "--t-end", "0.5",
                 "--maxiter", "3", "--out", str(out)]) == 0
    rep = json.loads((out / "report.json").read_text())
    assert rep["named_effect"] == "axial_rub", rep["steps"]
    assert rep["gap_after"] <= 0.75 * rep["gap_before"]
    assert _whirl_fixed(rep) == ["rpm_7000", "rpm_10000"]
    windage = next(c for c in rep["steps"][0]["candidates"] if c["effect"] == "windage")
    assert windage["gap"] >= 0.95 * rep["gap_before"]
    assert {r["point"] for r in rep["features_after"]} == {"rpm_7000", "rpm_10000"}
    md = (out / "report.md").read_text()
    assert "| rpm_7000 | DE_force_z_max_n |" in md and "axial_rub" in md and (out / "features.png").stat().st_size > 10000
    assert "rpm_10000: forward / none / forward" in capsys.readouterr().out


@pytest.mark.paper
def test_paper_story_full(tmp_path):
    """The acceptance item on the paper's numbers, the full run: `rotorlanding diagnose --measured
    scenarios/measured/paper_table2_fig39.toml --scenario scenarios/paper/forward_whirl_landing.toml
    --set effects.axial_rub=false` (3 speeds, 1 s runs, candidates: every effect the model lacks).

    Measured on the rig of 2026-11: gap 2.77 -> 2.18 (-21 %), axial_rub named (mu_ax at its lower
    bound 0.05; by the whirl-direction rule: the 30 % relative rule alone would not name it), whirl
    none -> forward at 7000 and 10000 rpm (79 / 81 Hz vs 65 / 77 Hz), still none at 3000 rpm;
    unbalance is not applicable (no [unbalance] table). 48 simulations, 166 s wall on 2 workers
    (load ~4)."""
    out = tmp_path / "diag"
    assert main(["diagnose", "--measured", str(PAPER_TABLE), "--scenario", str(PAPER_MODEL),
                 "--set", "effects.axial_rub=false", "--out", str(out)]) == 0
    rep = json.loads((out / "report.json").read_text())
    assert rep["named_effect"] == "axial_rub", rep["steps"]
    assert rep["gap_after"] <= 0.85 * rep["gap_before"]
    fixed = _whirl_fixed(rep)
    assert {"rpm_7000", "rpm_10000"} <= set(fixed) and not rep["steps"][0]["whirl_direction_broken_at"]


def test_faults_are_candidates_only_on_request(tmp_path):
    """A worn bearing is tried only when named; named, it is applicable (the probe supplies the
    torque it is about to fit), and a clean model stays clean (no fault invented)."""
    from rotorlanding.effects import CATALOGUE

    assert CATALOGUE["worn_bearing_drag"].fault and not CATALOGUE["windage"].fault
    model = known_rig_model(tmp_path / "model.toml", t_end=0.2)
    feats = {"whirl_direction": ("none", 0.0)}
    # the effect candidates are the point: no parameter candidates (each would cost ~13 landings)
    res = diagnose(feats, model, clearance=C, workers=1, maxiter=2, parameters=[])
    tried = {c["effect"] for s in res["steps"] for c in s["candidates"]}
    assert "worn_bearing_drag" not in tried
    res = diagnose(feats, model, clearance=C, workers=1, maxiter=2, candidates=["worn_bearing_drag"], parameters=[])
    cand = res["steps"][0]["candidates"][0]
    assert cand["effect"] == "worn_bearing_drag" and "not_applicable" not in cand
