"""Tests of user_forces.thermal_growth (growth, clearances, preload, drag feedback, runaway)."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from user_forces.ball_bearing import harris_palmgren_constants, harris_palmgren_torque
from user_forces.contact_stress import BEARING_7212BE_ASSUMED as G, ball_stiffness_kn
from user_forces.thermal import catcher_bearing_network, steady_state
from user_forces.thermal_growth import (FeedbackModel, drag_state, internal_clearance_change,
                                        journal_clearance_change, linear_growth, preloaded_drag_torque,
                                        steady_with_feedback, thermal_preload, transient_with_feedback)

HP_KW = dict(contact_angle_deg=40.0, C_s=4.5e4, d_m=0.085, z_hp=0.001, y_hp=0.33)
HP = harris_palmgren_constants(40.0, 4.5e4, 0.085, 0.001, 0.33)
ALPHA = 11.9e-6
TA = 293.15


def test_linear_growth_of_a_ring():
    """60 mm bore, +50 K: 11.9e-6 * 0.060 * 50 = 35.7 um."""
    assert linear_growth(0.060, ALPHA, 50.0) == pytest.approx(35.7e-6, rel=1e-12)
    with pytest.raises(ValueError, match="alpha = -1"):
        linear_growth(0.06, -1e-6, 1.0)


def test_clearance_changes_hand_values():
    """Internal: d_m 85, D 15.875 -> d_i 69.125, d_o 100.875 mm; dT_i 40, dT_o 10, dT_b 30 K:
    dP_d = 11.9e-6 (0.100875*10 - 0.069125*40 - 2*0.015875*30) = 11.9e-6 (1.00875 - 2.765 - 0.9525)
         = -32.23 um.  Journal: bore 30.0 mm at +40 K, sleeve 29.8 mm at +100 K:
    dc = 11.9e-6 (0.030*40 - 0.0298*100) = -21.18 um."""
    d = internal_clearance_change(0.085, 0.015875, 40.0, 10.0, 30.0, ALPHA)
    assert d == pytest.approx(11.9e-6 * (1.00875 - 2.765 - 0.9525), rel=1e-12)
    assert d == pytest.approx(-32.23e-6, abs=0.01e-6)
    assert journal_clearance_change(0.030, 0.0298, 40.0, 100.0, ALPHA) == pytest.approx(-21.182e-6, rel=1e-4)
    # uniform heating of everything (same alpha) opens the clearance: d_o - d_i - 2D = 0 at the
    # groove bottoms, so dP_d = 0 exactly; a hotter outer ring opens it
    assert internal_clearance_change(0.085, 0.015875, 50.0, 50.0, 50.0, ALPHA) == pytest.approx(0.0, abs=1e-20)
    assert internal_clearance_change(0.085, 0.015875, 0.0, 10.0, 0.0, ALPHA) > 0.0


def test_thermal_preload_small_interference_and_spring():
    """Rigid mounting, 2 um diametral interference: delta_n = (2e-6/2) cos(40 deg) = 0.766 um to
    first order (the second-order term is ~4e-4 relative here); Q = K_n delta^1.5, F_a = Z Q sin a.
    A soft axial spring lets the rings slide apart: F_a = k s at the solution, far below rigid."""
    kn = ball_stiffness_kn(G)
    q, fa, ang, delta, s = thermal_preload(-2e-6, G, kn)
    assert delta == pytest.approx(1e-6 * math.cos(math.radians(40.0)), rel=1e-3)
    assert q == pytest.approx(kn * delta ** 1.5, rel=1e-12)
    assert fa == pytest.approx(15 * q * math.sin(math.radians(ang)), rel=1e-12) and s == 0.0
    assert thermal_preload(5e-6, G, kn)[1] == 0.0                  # clearance left: no preload
    qs, fas, _, _, ss = thermal_preload(-10e-6, G, kn, k_axial=5e6)
    assert fas == pytest.approx(5e6 * ss, rel=1e-9)
    assert fas < 0.05 * thermal_preload(-10e-6, G, kn)[1]
    # a very stiff spring tends to the rigid mounting
    assert thermal_preload(-10e-6, G, kn, k_axial=1e13)[1] == pytest.approx(thermal_preload(-10e-6, G, kn)[1],
                                                                             rel=1e-2)


def test_fixed_heat_shrinks_clearance_and_raises_drag_as_the_formulas_say():
    """40 W into the inner ring of the rig's network (no feedback), cold clearance 20 um, rigid
    axial mounting, F_r = 555 N (rotor weight share), 7000 rpm (733 rad/s).
    Steady temperatures -> dP_d by the clearance formula -> P_d < 0 -> preload -> Harris-Palmgren
    torque with F_a = preload, each step recomputed here by the other call path
    (harris_palmgren_torque with keywords), and the drag must exceed the cold drag.
    Found: inner +108.3 K, balls +60.0 K, outer +11.9 K; P_d = 20 - 97.4 = -77.4 um; preload
    F_a = 19.5 kN; torque 0.875 N m against 0.011 N m cold (x79)."""
    nw = catcher_bearing_network()
    cap, lap, g = nw.arrays()
    t = steady_state(np.array([0.0, 40.0, 0.0, 0.0, 0.0]), lap, g, TA)
    dti, dtb, dto = t[1] - TA, t[2] - TA, t[3] - TA
    assert dti > dtb > dto > 0.0                                   # heat flows inner -> balls -> outer
    pd = 20e-6 + ALPHA * (0.100875 * dto - 0.069125 * dti - 2 * 0.015875 * dtb)
    assert pd < 0.0
    fa = thermal_preload(pd, G)[1]
    m = FeedbackModel(nw, G, HP, omega=733.0, f_radial=555.0, clearance0=20e-6)
    p, torque, pd_law, fa_law = drag_state(m, t)
    assert pd_law == pytest.approx(pd, rel=1e-9) and fa_law == pytest.approx(fa, rel=1e-12)
    t_hand = harris_palmgren_torque(733.0, 555.0, fa, **HP_KW, omega_reg=0.1)
    assert torque == pytest.approx(t_hand, rel=1e-12)
    t_cold = harris_palmgren_torque(733.0, 555.0, 0.0, **HP_KW, omega_reg=0.1)
    assert abs(torque) > 3.0 * abs(t_cold)
    assert p == pytest.approx(abs(t_hand) * 733.0, rel=1e-12)
    assert preloaded_drag_torque(733.0, 555.0, 0.0, fa, HP) == pytest.approx(torque, rel=1e-12)


def _model(k_axial=math.inf, omega=150.0):
    return FeedbackModel(catcher_bearing_network(), G, HP, omega=omega, f_radial=555.0, clearance0=20e-6,
                         k_axial=k_axial)


def _q(q_inner):
    return np.array([0.0, q_inner, 0.0, 0.0, 0.0])


@functools.lru_cache(maxsize=None)
def _critical_heat_of(k_axial, omega):
    return _critical_heat(_model(k_axial, omega))


def _critical_heat(model, lo=0.0, hi=60.0):
    """Heat into the inner ring [W] between a stable state and none (bisection, 50 halvings)."""
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        if steady_with_feedback(model, _q(mid))["status"] == "stable":
            lo = mid
        else:
            hi = mid
    return lo


def test_runaway_threshold_is_where_the_loop_gain_reaches_one():
    """Rigid axial mounting at 1430 rpm (150 rad/s): below a critical heat into the inner ring the
    bearing settles; above it there is no steady state below 200 C. Approaching the threshold
    from below, the loop gain dP_out/dP of the stable state rises towards 1 (the saddle-node):
    found q_crit = 11.44 W; gain 0.83 at 0.99 q_crit, 0.94 at 0.999, 0.994 at 0.99999. Far below
    (0.5 q_crit) the preload is still zero (the clearance not yet consumed) and the gain 0."""
    m = _model()
    qc = _critical_heat_of(math.inf, 150.0)
    assert 5.0 < qc < 30.0
    assert steady_with_feedback(m, _q(1.02 * qc))["status"] == "runaway"
    far = steady_with_feedback(m, _q(0.5 * qc))
    assert far["status"] == "stable" and far["loop_gain"] == 0.0 and far["preload"] == 0.0
    near = steady_with_feedback(m, _q(0.99999 * qc))
    assert near["status"] == "stable" and 0.9 < near["loop_gain"] < 1.0
    mid = steady_with_feedback(m, _q(0.99 * qc))
    assert 0.0 < mid["loop_gain"] < near["loop_gain"]


def test_full_speed_runaway_sits_on_the_harris_palmgren_floor():
    """At 7000 rpm the threshold is where the preload lifts F_beta off its floor F_r
    (0.9 F_a cot a - 0.1 F_r = F_r, F_a = 1.1 F_r tan a / 0.9 = 569 N at F_r = 555 N): on the floor
    the drag does not depend on the preload (gain 0), just above it the gain is already > 1, so the
    bearing runs away as soon as the preload reaches it. Found q_crit = 6.87 W, preload 567 N at
    0.999 q_crit."""
    m = _model(omega=733.0)
    qc = _critical_heat_of(math.inf, 733.0)
    below = steady_with_feedback(m, _q(0.999 * qc))
    assert below["status"] == "stable" and below["loop_gain"] == 0.0
    assert below["preload"] == pytest.approx(1.1 * 555.0 * math.tan(math.radians(40.0)) / 0.9, rel=0.05)


def test_spring_mounted_bearing_does_not_run_away():
    """The same heat that runs the rigidly mounted bearing away leaves the one on a 5e6 N/m axial
    spring (the rig's k_ws) stable with a small preload: the spring takes up the growth."""
    m_rigid, m_spring = _model(), _model(k_axial=5e6)
    q = 1.5 * _critical_heat_of(math.inf, 150.0)
    assert steady_with_feedback(m_rigid, _q(q))["status"] == "runaway"
    r = steady_with_feedback(m_spring, _q(q))
    assert r["status"] == "stable" and r["preload"] < 100.0 and r["loop_gain"] < 0.1
    assert steady_with_feedback(m_spring, _q(500.0))["status"] == "overheat"


def test_transient_settles_below_and_runs_away_above_the_threshold():
    """Backward Euler with the drag fed back each step (dt = 5 s): below the threshold the
    temperatures settle at the steady fixed point; above it a node passes 200 C in finite time
    (found 3630 s at 1.3 q_crit, drag 1.7 W -> 376 W)."""
    m = _model()
    qc = _critical_heat_of(math.inf, 150.0)
    stable = steady_with_feedback(m, _q(0.8 * qc))
    tr = transient_with_feedback(m, _q(0.8 * qc), t_end=8 * 3600.0, dt=5.0)
    assert tr["runaway_time"] is None
    assert tr["temps"][-1] == pytest.approx(stable["t_nodes"], abs=0.05)
    tr2 = transient_with_feedback(m, _q(1.3 * qc), t_end=8 * 3600.0, dt=5.0)
    assert tr2["runaway_time"] is not None and 60.0 < tr2["runaway_time"] < 8 * 3600.0
    assert np.max(tr2["temps"][-1]) > 473.15
    # the drag power rises without bound towards the end (the last hour's rise > the first's)
    p = tr2["p_drag"]
    assert p[-1] > 3.0 * p[0]


def test_preload_fast_leaf_compiles_with_numba():
    numba = pytest.importorskip("numba")
    from user_forces.thermal_growth import thermal_preload_fast
    f = numba.njit(thermal_preload_fast)
    kn = ball_stiffness_kn(G)
    a0 = (0.52 + 0.53 - 1.0) * 15.875e-3
    for pd, k in ((-10e-6, math.inf), (-10e-6, 5e6), (3e-6, math.inf)):
        q, fa, ang, delta, s = thermal_preload(pd, G, kn, k)
        assert f(pd, 15, math.radians(40.0), a0, kn, k) == pytest.approx((q, fa, math.radians(ang), delta, s),
                                                                          rel=1e-12, abs=1e-18)
