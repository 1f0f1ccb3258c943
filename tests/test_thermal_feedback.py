"""Issue 18, step 3: the registry's thermal_feedback mechanism (rotorlanding/thermal_feedback.py):
the carried temperatures retune the journal clearance, the ball set's stiffness and the drag's
axial load; off it contributes nothing.

Checked against hand formulas of linear growth (not the functions under test), the first-order
preload delta_n = -P_d/2 cos a0 of a rigid mounting, a finite difference of the radial force of
the preloaded ball set summed ball by ball, and the compiled kernel's race torque against the
Harris-Palmgren law called with the preload added to the axial load."""

import math
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.bearing_kernel import bearing_parameters, bearing_rhs
from rotorlanding.landing import build_spec
from rotorlanding.mechanisms import evaluate, retuned_spec
from rotorlanding.scenario import load_scenario
from rotorlanding.thermal_feedback import geometry, state
from user_forces.ball_bearing import ball_force, harris_palmgren_fast
from user_forces.contact_stress import ball_stiffness_kn

ROOT = Path(__file__).resolve().parents[1]
LANDING = ROOT / "scenarios" / "landing_7000rpm.toml"
ALPHA = 11.9e-6
RISE = {"sleeve": 80.0, "inner_ring": 60.0, "ball_set": 40.0, "outer_ring": 10.0, "housing": 2.0}  # K


def _spec(*sets):
    return build_spec(load_scenario(LANDING, ["effects.thermal_feedback=true", *sets]))


def _carry(spec, rise=RISE):
    ta = spec.bearings[0].laws.extra["thermal_ambient_k"]
    return {f"{b.name}_temperature_{n}_k": ta + d for b in spec.bearings for n, d in rise.items()}


def test_hot_bearing_clearances_by_hand():
    spec = _spec()
    hot = retuned_spec(spec, _carry(spec))
    b0, b1 = spec.bearings[0], hot.bearings[0]
    r_bore, r_s = b0.laws.race_radius, b0.laws.sleeve_radius
    # journal: the bore grows with the inner ring, the sleeve with itself
    assert b1.laws.clearance == pytest.approx(b0.laws.clearance + ALPHA * (r_bore * 60.0 - r_s * 80.0), rel=1e-12)
    assert b1.laws.race_radius - b1.laws.sleeve_radius == pytest.approx(b1.laws.clearance, rel=1e-9)
    # internal: groove bottoms d_m -+ D, balls across 2 D
    d_m, d = 0.085, 15.875e-3
    pd = 20e-6 + ALPHA * ((d_m + d) * 10.0 - (d_m - d) * 60.0 - 2 * d * 40.0)
    st = state(b0.laws, [293.15 + RISE[n] for n in RISE])
    assert st["internal_clearance"] == pytest.approx(pd, rel=1e-12)
    assert pd < 0 and b1.laws.drag_axial_preload > 0 and b1.laws.k_b1 > b0.laws.k_b1


def test_rigid_mount_preload_is_first_order_and_stiffness_is_the_ball_sum():
    spec = _spec("bearings.DE.thermal_axial_mount_stiffness_n_m=1e14")
    laws = spec.bearings[0].laws
    rise = dict(RISE, inner_ring=30.0, ball_set=20.0, sleeve=30.0)  # a few um of interference
    st = state(laws, [293.15 + rise[n] for n in RISE])
    g = geometry(laws)
    a0 = math.radians(g.contact_angle_deg)
    assert st["delta_n"] == pytest.approx(-0.5 * st["internal_clearance"] * math.cos(a0), rel=2e-3)
    # radial stiffness: d/d dr of sum_j K_n (delta_n + dr cos psi_j cos a)^1.5 cos a cos psi_j
    k_n, z, a = ball_stiffness_kn(g), g.n_balls, st["contact_angle_rad"]
    psi = 2 * math.pi * np.arange(z) / z

    def f_r(dr):
        dj = np.maximum(st["delta_n"] + dr * np.cos(psi) * math.cos(a), 0.0)
        return float(np.sum(k_n * dj**1.5 * math.cos(a) * np.cos(psi)))

    h = 1e-3 * st["delta_n"]
    assert st["dk_b1"] == pytest.approx((f_r(h) - f_r(-h)) / (2 * h), rel=1e-5)


def test_the_kernel_drags_with_the_preload_in_the_axial_load():
    spec = _spec()
    hot = retuned_spec(spec, _carry(spec))
    b = hot.bearings[0]  # DE: no axial face, so the drag's axial load is the preload alone
    assert not b.laws.axial_face
    P = bearing_parameters(hot, b)
    ey, omi = 3e-6, 400.0
    # journal centred (no contact), inner race displaced by ey from the outer race, spinning
    f = bearing_rhs(P, 0.0, 0.0, 0.0, 0.0, ey, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 700.0, 0.0, 0.0, 0.0, omi, 0.0, 0.0,
                    0.0, 0.0)
    by, bz = ball_force(ey, 0.0, b.laws.k_b1, b.laws.k_b2)
    t_expected = harris_palmgren_fast(omi, math.hypot(by, bz), b.laws.drag_axial_preload, b.laws.hp)
    assert f[6] == pytest.approx(t_expected, rel=1e-12)
    cold = harris_palmgren_fast(omi, math.hypot(*ball_force(ey, 0.0, spec.bearings[0].laws.k_b1,
                                                             spec.bearings[0].laws.k_b2)), 0.0, b.laws.hp)
    assert abs(f[6]) > abs(cold)  # the hot bearing drags more


def test_off_contributes_nothing():
    spec = build_spec(load_scenario(LANDING))  # thermal_feedback off by default
    assert retuned_spec(spec, _carry(spec)) is spec
    for b in spec.bearings:
        assert b.laws.drag_axial_preload == 0.0
    t = np.array([0.0, 1e-4])
    q = np.tile(spec.initial_state()[0], (2, 1))
    v = np.tile(spec.initial_state()[1], (2, 1))
    s = evaluate(spec, t, q, v)
    for b in spec.bearing_names:
        for n in ("journal_clearance_m", "internal_clearance_m", "thermal_preload_n"):
            assert not np.any(s[f"{b}_{n}"])
