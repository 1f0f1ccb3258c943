"""The race's lag behind the rotor (``*_race_lag_s``, session 50): the integral over a fixed window
after the drop of the slip 1 - race / rotor speed. Checked against closed forms for a linear and an
exponential spin-up, the limits (a race that never turns, one turning with the rotor), and the
feature as extract_features gives it from channels."""
import math

import numpy as np
import pytest

from rotorlanding.features import RACE_LAG_WINDOW_S, extract_features, race_lag, scale_of
from rotorlanding.measured import Measurement

W = RACE_LAG_WINDOW_S


def _t(fs=5000.0, t0=-0.1, t1=0.3):
    return np.arange(t0, t1, 1.0 / fs)


def test_linear_spin_up_lags_half_its_ramp():
    """Race 0 -> rotor speed linearly over T = 0.1 s from the drop: lag = T / 2."""
    t = _t()
    rotor = np.full_like(t, 7000.0)
    race = np.clip(t / 0.1, 0.0, 1.0) * 7000.0
    assert race_lag(t, race, rotor, 0.0) == pytest.approx(0.05, rel=1e-3)


def test_exponential_spin_up_against_its_closed_form():
    """race = rotor (1 - exp(-t / tau)), the rotor decelerating (the ratio is what counts):
    lag = tau (1 - exp(-W / tau))."""
    t = _t(fs=10000.0)
    tau = 0.04
    rotor = 7000.0 - 150.0 * np.clip(t, 0.0, None)
    race = np.where(t < 0, 0.0, rotor * (1.0 - np.exp(-np.clip(t, 0.0, None) / tau)))
    assert race_lag(t, race, rotor, 0.0) == pytest.approx(tau * (1.0 - math.exp(-W / tau)), rel=1e-3)


def test_limits_and_a_record_too_short():
    t = _t()
    rotor = np.full_like(t, 7000.0)
    assert race_lag(t, np.zeros_like(t), rotor, 0.0) == pytest.approx(W, rel=1e-3)     # never turns
    assert race_lag(t, rotor, rotor, 0.0) == pytest.approx(0.0, abs=1e-12)           # turns with it
    assert race_lag(t, 1.02 * rotor, rotor, 0.0) == pytest.approx(0.0, abs=1e-12)    # faster: no negative slip
    assert race_lag(t, np.zeros_like(t), rotor, 0.15) is None                        # ends inside the window
    assert race_lag(t[t > 0.01], np.zeros(np.sum(t > 0.01)), rotor[t > 0.01], 0.0) is None  # starts after it


def test_extract_features_gives_the_lag_with_its_scale():
    t = _t()
    rotor = np.full_like(t, 7000.0)
    race = np.clip((t - 0.02) / 0.1, 0.0, 1.0) * 7000.0   # contact 20 ms after the drop, then a 0.1 s ramp
    z = np.where(t > 0, -2.2e-4, 0.0)
    m = Measurement({"DE_y_m": (t, np.zeros_like(t)), "DE_z_m": (t, z), "rotor_speed_rpm": (t, rotor),
                     "DE_inner_race_speed_rpm": (t, race)})
    f = extract_features(m, clearance=2e-4, t_drop=0.0)
    lag, scale = f["DE_race_lag_s"]
    assert lag == pytest.approx(0.02 + 0.05, rel=1e-3)
    assert scale == scale_of("DE_race_lag_s", lag, 2e-4) == pytest.approx(max(2e-3, 0.03 * lag))


def test_diagnose_leaves_the_datas_lag_out_when_the_model_run_ends_inside_its_window(tmp_path):
    """A model run of 0.15 s has no lag over the 0.2 s window: diagnose leaves the data's lag rows
    out with a warning naming them, instead of charging them as a feature the model cannot produce.
    Checked against the same diagnosis of the data given without those rows: the same gap, and the
    lag neither among the rows nor among the features absent from the model."""
    from sensor_model import C, known_rig_model

    from rotorlanding.diagnose_run import _simulate_features, diagnose

    long_run = known_rig_model(tmp_path / "long.toml", ["windage"], t_end=0.3)
    data = _simulate_features(long_run, [], C)
    lag = sorted(k for k in data if k.endswith("_race_lag_s"))
    assert lag == ["DE_race_lag_s", "NDE_race_lag_s"] and data["DE_race_lag_s"][0] > 0.0   # NDE: not compared
    short = known_rig_model(tmp_path / "short.toml", ["windage"], t_end=0.15)
    kw = dict(clearance=C, candidates=["windage"], parameters=[], noise_gap=0.5, workers=1, maxiter=1, ensemble=1)
    res = diagnose(data, short, **kw)
    without = diagnose({k: v for k, v in data.items() if k not in lag}, short, **kw)
    said = [w for w in res["warnings"] if "DE_race_lag_s left out" in w]
    assert len(said) == 1 and "0.15 s" in said[0] and "0.2 s" in said[0], res["warnings"]
    assert not any("race_lag" in w for w in without["warnings"])
    assert res["gap_before"] == without["gap_before"] and res["gap_after"] == without["gap_after"]
    assert "DE_race_lag_s" not in res["absent_in_model_before"]
    assert [r["feature"] for r in res["features_before"]] == [r["feature"] for r in without["features_before"]]
    assert all(r["feature"] != "DE_race_lag_s" for r in res["features_before"] + res["features_after"])
