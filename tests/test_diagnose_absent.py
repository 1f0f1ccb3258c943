"""Issue 20, point 2: a feature the data show and the model cannot produce is charged, not dropped
(the race that never spins up in a model without radial friction is the clearest sign of it)."""

import math

import numpy as np
import pytest

from rotorlanding.features import ABSENT_FEATURE_DISTANCE, MAX_DISTANCE, extract_features, gap, soft_cap
from rotorlanding.measured import Measurement

C = 2e-4


def _record(race_rate_rpm_s):
    """A landing record: rotor slowing 100 rpm/s from 7000 rpm, the DE inner race accelerated at
    ``race_rate_rpm_s`` (0: it never spins up), journal resting on the race."""
    t = np.arange(0.0, 0.5, 2e-4)
    rotor = 7000.0 - 100.0 * t
    race = np.minimum(rotor, race_rate_rpm_s * t)
    y, z = 0.0 * t, np.maximum(-0.5 * 9.80665 * t ** 2, -C)
    return Measurement({"DE_y_m": (t, y), "DE_z_m": (t, z), "rotor_speed_rpm": (t, rotor),
                        "DE_inner_race_speed_rpm": (t, race)})


def test_race_that_never_spins_up_is_a_measurable_absence():
    spins = extract_features(_record(70000.0), clearance=C)
    still = extract_features(_record(0.0), clearance=C)
    # 90 % of the rotor speed: 70000 t = 0.9 (7000 - 100 t) -> t = 6300 / 70090 (independent arithmetic)
    assert math.isclose(spins["DE_race_spinup_s"][0], 6300.0 / 70090.0, abs_tol=2e-4)
    assert still["DE_race_spinup_s"] == (None, 0.02)


def test_feature_the_model_cannot_produce_is_charged_with_the_stated_penalty():
    measured = extract_features(_record(70000.0), clearance=C)   # the race spins up in the data
    model = extract_features(_record(0.0), clearance=C)          # the model's race never does
    g, rows = gap(measured, model)
    row = next(r for r in rows if r["feature"] == "DE_race_spinup_s")
    assert row["absent_in"] == "model" and row["distance"] == ABSENT_FEATURE_DISTANCE == MAX_DISTANCE
    # the race's lag (session 50) is a value on both sides: the window, 0.2 s, for the race that never
    # turns; for the data's, closed form: the slip 1 - 70000 t / (7000 - 100 t) = 701 - 4.9e6 / (7000 -
    # 100 t) until T = 7000 / 70100, integrated: 701 T - 4.9e4 ln(7000 / (7000 - 100 T))
    T = 7000.0 / 70100.0
    lag_data = 701.0 * T - 4.9e4 * math.log(7000.0 / (7000.0 - 100.0 * T))
    lag_row = next(r for r in rows if r["feature"] == "DE_race_lag_s")
    assert math.isclose(lag_row["measured"], lag_data, rel_tol=2e-3) and math.isclose(lag_row["simulated"], 0.2)
    d_lag = soft_cap((0.2 - lag_data) / max(2e-3, 0.03 * lag_data))
    assert math.isclose(lag_row["distance"], d_lag, rel_tol=1e-3)
    # independent: every other feature is identical (distance 0), so the gap is sqrt((3^2 + d_lag^2) / n_rows)
    assert all(r["distance"] == 0.0 for r in rows if r is not row and r is not lag_row)
    assert math.isclose(g, math.sqrt((ABSENT_FEATURE_DISTANCE ** 2 + d_lag ** 2) / len(rows)), rel_tol=1e-3)
    # before issue 20 the row was dropped and the gap was 0: the missing spin-up was invisible
    assert g > 0.5
    # the other way round (the data's race never spins up, the model's does): charged as well
    g2, rows2 = gap(model, measured)
    assert next(r for r in rows2 if r["feature"] == "DE_race_spinup_s")["absent_in"] == "measurement"
    # the lag's scale is the measured side's (3 % of 0.2 s there): its own closed form
    d_lag2 = soft_cap((0.2 - lag_data) / max(2e-3, 0.03 * 0.2))
    assert math.isclose(g2, math.sqrt((ABSENT_FEATURE_DISTANCE ** 2 + d_lag2 ** 2) / len(rows2)), rel_tol=1e-3)


def test_a_feature_missing_from_the_model_features_is_charged_and_a_shared_absence_is_not():
    measured = {"DE_first_rebound_m": (3e-5, 1e-5), "DE_vertical_min_m": (-2e-4, 2e-5)}
    g, rows = gap(measured, {"DE_vertical_min_m": (-2.2e-4, 2e-5)})
    d_min = soft_cap(2e-5 / 2e-5)
    assert math.isclose(g, math.sqrt((ABSENT_FEATURE_DISTANCE ** 2 + d_min ** 2) / 2), rel_tol=1e-12)
    g0, rows0 = gap({"DE_race_spinup_s": (None, 0.02)}, {"DE_race_spinup_s": (None, 0.02)})
    assert rows0 == [] and math.isnan(g0)


def test_ensemble_features_are_majority_and_medians():
    """Features of an ensemble of drops (issue 20, point 1), against hand-computed statistics."""
    from rotorlanding.features import ensemble_features

    members = [
        {"whirl_direction": ("forward", None), "whirl_frequency_hz": (60.0, 2.0), "DE_vertical_min_m": (-1e-4, 2e-5),
         "DE_race_spinup_s": (0.05, 0.02), "DE_first_rebound_m": (1e-5, 1e-5)},
        {"whirl_direction": ("forward", None), "whirl_frequency_hz": (64.0, 2.0), "DE_vertical_min_m": (-3e-4, 2e-5),
         "DE_race_spinup_s": (None, 0.02)},
        {"whirl_direction": ("none", None), "DE_vertical_min_m": (-2e-4, 2e-5), "DE_race_spinup_s": (None, 0.02)},
        {"whirl_direction": ("forward", None), "whirl_frequency_hz": (80.0, 2.4), "DE_vertical_min_m": (-5e-4, 2e-5),
         "DE_race_spinup_s": (0.07, 0.02)},
    ]
    f = ensemble_features(members)
    assert f["whirl_direction"] == ("forward", None)
    assert f["whirl_frequency_hz"] == (68.0, 2.0)                  # mean of 60, 64, 80 (forward members)
    assert math.isclose(f["DE_vertical_min_m"][0], -2.75e-4)        # mean of -1, -3, -2, -5 (x 1e-4)
    assert f["DE_vertical_min_m"][1] == 2e-5
    by = f["__whirl_by_direction__"]
    assert by["forward"]["share"] == 0.75 and by["none"]["share"] == 0.25 and by["forward"]["whirl_frequency_hz"][0] == 68.0
    assert f["DE_race_spinup_s"] == (None, 0.02)                   # 2 of 4 reached: not a majority
    assert "DE_first_rebound_m" not in f                          # 1 of 4 produce it
    tie = ensemble_features(members[:2] + [members[2], {**members[2]}])
    assert tie["whirl_direction"] == ("forward", None)            # a tie goes to the whirl class


def test_ensemble_whirl_is_charged_by_the_share_of_members_that_miss_it():
    """Across a whirl threshold the charge follows the share of members that whirl as measured
    (smooth), not the majority (a jump of 3)."""
    from rotorlanding.features import DIRECTION_MISMATCH, ensemble_features

    measured = {"whirl_direction": ("forward", None), "whirl_frequency_hz": (65.0, 2.0)}
    fwd = {"whirl_direction": ("forward", None), "whirl_frequency_hz": (65.0, 2.0)}
    calm = {"whirl_direction": ("none", None)}
    for k in range(5):  # 0..4 of 4 members whirl forward at 65 Hz
        ens = ensemble_features([fwd] * k + [calm] * (4 - k))
        g, rows = gap(measured, ens)
        miss = DIRECTION_MISMATCH * (1 - k / 4)
        assert math.isclose(g, miss, abs_tol=1e-12), (k, rows)   # both rows charge 3 x the missing share


def test_cli_names_the_feature_the_model_cannot_produce_first(tmp_path, capsys):
    """Hidden radial friction (mu_rad 0.3, own sensor model): the model without it never spins its
    race up; the report says so first, and the named effect produces the feature."""
    import json
    import sys
    from pathlib import Path

    from rotorlanding.cli import main

    sys.path.insert(0, str(Path(__file__).parent))
    from sensor_model import write_record

    root = Path(__file__).resolve().parents[1]
    model = tmp_path / "model.toml"
    model.write_text(f'include = ["{root / "scenarios" / "landing_7000rpm.toml"}", '
                     f'"{root / "scenarios" / "rig_rotor_first.toml"}", "{root / "tests" / "known_rig_bearings.toml"}"]\n'
                     '[effects]\nradial_friction = false\n[operating]\nspeed_rpm = 7000.0\nt_end = 0.3\n')
    csv = tmp_path / "rig.csv"
    write_record(model, ["effects.radial_friction=true", "contact.mu_rad=0.3"], csv, clearance=C, seed=4)
    out = tmp_path / "diag"
    assert main(["diagnose", "--measured", str(csv), "--scenario", str(model), "--out", str(out),
                 "--candidates", "radial_friction", "--parameters", "none", "--maxiter", "3", "--ensemble", "1"]) == 0
    rep = json.loads((out / "report.json").read_text())
    assert rep["absent_in_model_before"] == ["DE_race_spinup_s"] and rep["absent_in_model_after"] == []
    assert rep["named_effect"] == "radial_friction"
    row = next(r for r in rep["features_before"] if r["feature"] == "DE_race_spinup_s")
    assert row["simulated"] is None and row["distance"] == ABSENT_FEATURE_DISTANCE and row["measured"] > 0
    md = (out / "report.md").read_text()
    assert md.index("First hint") < md.index("Named effect") and "DE_race_spinup_s (absent in the model)" in md
    assert "the model cannot produce: DE_race_spinup_s" in capsys.readouterr().out


def test_decisive_features_are_the_rows_whose_squared_distance_fell_most():
    from rotorlanding.diagnose_run import decisive_features

    before = [{"point": "p", "feature": "a", "distance": 2.0, "weight": 1.0},
              {"point": "p", "feature": "b", "distance": 1.0, "weight": 1.0},
              {"point": "p", "feature": "c", "distance": 0.5, "weight": 1.0},
              {"point": "q", "feature": "a", "distance": 0.1, "weight": 1.0}]
    after = [{"point": "p", "feature": "a", "distance": 0.0, "weight": 1.0},   # fall 4
             {"point": "p", "feature": "b", "distance": 0.0, "weight": 1.0},   # fall 1
             {"point": "p", "feature": "c", "distance": 1.5, "weight": 1.0},   # rose: not decisive
             {"point": "q", "feature": "a", "distance": 0.1, "weight": 1.0}]   # unchanged
    d = decisive_features(before, after)
    assert [(x["point"], x["feature"]) for x in d] == [("p", "a"), ("p", "b")]
    assert [x["share"] for x in d] == pytest.approx([0.8, 0.2])
    assert decisive_features(after, after) == []
