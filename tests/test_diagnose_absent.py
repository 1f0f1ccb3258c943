"""Issue 20, point 2: a feature the data show and the model cannot produce is charged, not dropped
(the race that never spins up in a model without radial friction is the clearest sign of it)."""

import math

import numpy as np

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
    # independent: every other feature is identical (distance 0), so the gap is sqrt(3^2 / n_rows)
    assert all(r["distance"] == 0.0 for r in rows if r is not row)
    assert math.isclose(g, math.sqrt(ABSENT_FEATURE_DISTANCE ** 2 / len(rows)), rel_tol=1e-12)
    # before issue 20 the row was dropped and the gap was 0: the missing spin-up was invisible
    assert g > 0.5
    # the other way round (the data's race never spins up, the model's does): charged as well
    g2, rows2 = gap(model, measured)
    assert next(r for r in rows2 if r["feature"] == "DE_race_spinup_s")["absent_in"] == "measurement"
    assert math.isclose(g2, g, rel_tol=1e-12)


def test_a_feature_missing_from_the_model_features_is_charged_and_a_shared_absence_is_not():
    measured = {"DE_first_rebound_m": (3e-5, 1e-5), "DE_vertical_min_m": (-2e-4, 2e-5)}
    g, rows = gap(measured, {"DE_vertical_min_m": (-2.2e-4, 2e-5)})
    d_min = soft_cap(2e-5 / 2e-5)
    assert math.isclose(g, math.sqrt((ABSENT_FEATURE_DISTANCE ** 2 + d_min ** 2) / 2), rel_tol=1e-12)
    g0, rows0 = gap({"DE_race_spinup_s": (None, 0.02)}, {"DE_race_spinup_s": (None, 0.02)})
    assert rows0 == [] and math.isnan(g0)
