"""Issue 18: a wired coast-down that runs away and one that does not, on the two sides of the
threshold that the law layer predicts (docs/designer_models.md sections 2 and 5).

The bearing: the rig's NDE catcher (it carries ~480 N of the session-28 rotor) mounted with zero internal
clearance (thermal_internal_clearance_m = 0: a tight fit of a bearing ordered without clearance)
and thermal feedback on. What decides runaway is the axial stiffness that holds the rings against
the thermal preload: a clamp against the housing (2e9 N/m, inside axial.k_h's bound 2e8-5e9; with the lighter
NDE load of the session-28 rotor the threshold rose from between 8e7 and 5e8 to ~7e8 N/m) or a stiff
support (8e7 N/m). The threshold k* is the stiffness at which ``user_forces.thermal_growth.
steady_with_feedback`` (the same network conductances, geometry, Harris-Palmgren constants; the
load and race speed measured in the run) stops finding a stable steady state: below it the steady
preload stays under the Harris-Palmgren floor (F_beta = max(0.9 F_a cot a - 0.1 F_r, F_r): the drag
does not see the preload, loop gain 0); above it there is no fixed point below 200 degC.

Scaled, to run in about a minute: every heat capacity of the network is divided by 100
(``thermal_states.network_for`` wrapped). Steady states, hence the threshold, do not depend on the
capacities; the thermal times shrink 100x (the network's fastest time constant 21.8 s -> 0.218 s,
against 0.1 s chunks: the feedback lags half of it). The landing's slip heat (~150 J into the
sleeve) is a fixed energy and heats the scaled network 100x more than the real one: the safe run's
preload peaks near the floor during the landing and then settles. At full scale the same runaway
needs ~25-45 min at constant speed (law-level transient), longer than the rig's coast-down holds
its speed (docs/designer_models.md section 5).
"""

import dataclasses
import math
from pathlib import Path

import h5py
import numpy as np
import pytest

import rotorlanding as rl
import rotorlanding.thermal_states as ts
from rotorlanding.landing import build_spec
from rotorlanding.coastdown_run import load_coastdown
from rotorlanding.verdict import verdict_from_results
from rotorlanding.thermal_feedback import geometry
from user_forces.thermal_growth import FeedbackModel, steady_with_feedback

ROOT = Path(__file__).resolve().parents[1]
SCEN = ROOT / "scenarios" / "coastdown_7000rpm.toml"
SCALE = 100.0
K_SAFE, K_CLAMP = 8.0e7, 2.0e9       # N/m (5e8 on the session-15 rotor, whose NDE carried ~830 N)
TAU_SLOW_S = 7.9                     # s: the scaled network's slowest time constant
SETS = {"effects.thermal_feedback": True, "coastdown.chunk_s": 0.1, "coastdown.decimate_every": 10,
        "bearings.NDE.thermal_internal_clearance_m": 0.0}
NODES = ("sleeve", "inner_ring", "ball_set", "outer_ring", "housing")


@pytest.fixture
def scaled_capacities(monkeypatch):
    orig = ts.network_for

    def scaled(laws):
        net = orig(laws)
        return dataclasses.replace(net, capacity=tuple(c / SCALE for c in net.capacity))

    monkeypatch.setattr(ts, "network_for", scaled)


def _run(tmp_path, k, t_end):
    cd = rl.coastdown(SCEN, tmp_path / f"k{k:g}", overwrite=True, t_end=t_end,
                      set=dict(SETS, **{"bearings.NDE.thermal_axial_mount_stiffness_n_m": k}))
    with h5py.File(tmp_path / f"k{k:g}" / "results.h5", "r") as h5:
        t = h5["time_s"][()]
        s = {k2: h5["series"][k2][()] for k2 in h5["series"] if k2.startswith("NDE_")}
    return cd.summary, t, s


def _model(laws, omega, f_r, k):
    """The law layer's steady model of the same bearing (the network here has the scaled
    capacities, which do not enter a steady state: C dT/dt = 0)."""
    return FeedbackModel(ts.network_for(laws), geometry(laws), laws.hp, omega, f_r, 0.0,
                         laws.extra["thermal_internal_clearance_m"], laws.extra["thermal_ambient_k"], 11.9e-6, k)


def _critical_stiffness(laws, omega, f_r, lo=1e6, hi=1e11):
    for _ in range(30):  # bisection on a log axis: k* to ~1e-8 relative
        mid = math.sqrt(lo * hi)
        if steady_with_feedback(_model(laws, omega, f_r, mid), np.zeros(5))["status"] == "stable":
            lo = mid
        else:
            hi = mid
    return lo


def test_clamped_catcher_runs_away_and_the_stiffly_supported_one_settles(tmp_path, scaled_capacities):
    scenario, _ = load_coastdown(SCEN, [f"{k}={str(v).lower()}" for k, v in SETS.items()])
    laws = build_spec(scenario).bearings[1].laws
    assert laws.extra["thermal_internal_clearance_m"] == 0.0

    # the safe side: runs to t_end and settles at the law's steady state
    summary, t, s = _run(tmp_path, K_SAFE, 40.0)
    fb = summary["thermal"]["NDE"]["feedback"]
    assert not fb["runaway"] and summary["stop_reason"].startswith("t_end")

    def load_and_speed(t_at):  # the load and race speed of the 2 s before t_at
        w = (t > t_at - 2.0) & (t <= t_at)
        return (float(np.mean(np.hypot(s["NDE_ball_force_y_n"][w], s["NDE_ball_force_z_n"][w]))),
                float(np.mean(s["NDE_race_speed_rpm"][w])) * math.pi / 30)

    f_r, omega = load_and_speed(t[-1])
    k_star = _critical_stiffness(laws, omega, f_r)
    assert K_SAFE < k_star < K_CLAMP   # the two runs lie on the two sides of the predicted threshold
    steady = steady_with_feedback(_model(laws, omega, f_r, K_SAFE), np.zeros(5))
    assert steady["status"] == "stable" and steady["loop_gain"] < 1.0
    # the network lags its input by its slowest time constant, 7.9 s (scaled): the rotor decelerates
    # (0.24 %/s on the session-28 rotor), so the temperatures at the end are the steady state of the
    # load and speed 7.9 s earlier (against the end's they lay 1.4-2.3 % of the rise high after 60 s,
    # 7.9 s earlier 0.5 % at most; session 28)
    f_lag, omega_lag = load_and_speed(t[-1] - TAU_SLOW_S)
    lagged = steady_with_feedback(_model(laws, omega_lag, f_lag, K_SAFE), np.zeros(5))
    run = np.array([s[f"NDE_temperature_{n}_k"][-1] for n in NODES])
    rise = lagged["t_nodes"] - laws.extra["thermal_ambient_k"]
    # what is left after 40 s beyond the lag: the landing's slip heat decays with the slowest scaled
    # time constant (exp(-40/7.9) = 0.6 % of its excess): within 2 % of the rise, node by node
    assert np.all(np.abs(run - lagged["t_nodes"]) <= 0.02 * rise), (run - 273.15, lagged["t_nodes"] - 273.15)
    assert s["NDE_thermal_preload_n"][-1] == pytest.approx(lagged["preload"], rel=0.05)

    # the runaway side: the run stops at the runaway, which the summary and the verdict report
    summary, t, s = _run(tmp_path, K_CLAMP, 25.0)
    fb = summary["thermal"]["NDE"]["feedback"]
    assert fb["runaway"] and fb["t_runaway_s"] < 25.0
    assert summary["stop_reason"].startswith("thermal runaway of NDE")
    assert summary["t_reached_s"] < 25.0 and summary["t_reached_s"] - fb["t_runaway_s"] <= 0.1 + 1e-9
    # past the Harris-Palmgren floor: 0.9 F_a cot a - 0.1 F_r > F_r
    assert fb["max_thermal_preload_n"] > 1.1 * f_r * math.tan(math.radians(laws.contact_angle_deg)) / 0.9
    v = verdict_from_results(tmp_path / f"k{K_CLAMP:g}" / "results.h5", plots=False)
    assert v["verdict"] == "fail" and "thermal runaway (NDE)" in v["failed"]
