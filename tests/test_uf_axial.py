"""Tests of user_forces.axial (eqs 2-5) and user_forces.spin (eq 6)."""

from __future__ import annotations


import pytest

from user_forces.axial import axial_acceleration, axial_force
from user_forces.spin import windage_coefficients_cylinder, windage_torque

CL, DM = 2e-4, 3e-4
KCB, KWS, KH, CAX = 4e8, 2e7, 1e9, 5e3
K1 = 1.0 / (1.0 / KCB + 1.0 / KWS)
K2 = 1.0 / (1.0 / KCB + 1.0 / KH)


def fax(x, v=0.0, c=CAX):
    return axial_force(x, v, CL, DM, KCB, KWS, KH, c)


def test_free_inside_clearance_even_when_moving():
    for x in (-CL, -0.5 * CL, 0.0, 0.3 * CL, CL):
        assert fax(x, v=3.0) == 0.0          # no contact, no damper (paper applies c_ax always)


def test_continuity_at_both_breakpoints_and_series_stiffness():
    eps = 1e-12
    for sgn in (+1.0, -1.0):
        # onset
        assert abs(fax(sgn * (CL + eps))) <= 1.01 * K1 * eps
        # support bottoming out: elastic force continuous, slope changes from K1 to K2
        xb = sgn * (CL + DM)
        f_lo, f_hi = fax(xb - sgn * eps), fax(xb + sgn * eps)
        assert abs(f_hi - f_lo) <= 2.0 * (K1 + K2) * eps   # a jump would be O(K1 DM)
        assert f_lo == pytest.approx(-sgn * K1 * DM, rel=1e-7)    # preload of the support
        h = 1e-6
        k_a = -(fax(sgn * (CL + 0.5 * DM) + h) - fax(sgn * (CL + 0.5 * DM) - h)) / (2 * h)
        k_b = -(fax(sgn * (CL + 2 * DM) + h) - fax(sgn * (CL + 2 * DM) - h)) / (2 * h)
        assert k_a == pytest.approx(K1, rel=1e-6)
        assert k_b == pytest.approx(K2, rel=1e-6)


def test_odd_symmetry():
    for x in (0.5 * CL, 1.5 * CL, CL + 0.9 * DM, CL + 1.7 * DM, 10 * DM):
        for v in (0.0, 0.02, -0.05):
            assert fax(-x, -v) == pytest.approx(-fax(x, v), rel=1e-12, abs=0.0)


def test_damping_only_in_contact_and_never_adhesive():
    x = CL + 0.5 * DM
    assert fax(x, 0.1) == pytest.approx(-K1 * 0.5 * DM - CAX * 0.1)
    # separating fast: -k1 e - c v > 0 would pull -> clipped to 0
    assert fax(CL + 1e-7, -1.0) == 0.0
    assert fax(-(CL + 1e-7), +1.0) == 0.0


def test_axial_acceleration_divides_both_forces_by_mass():
    m = 120.0
    x, v, thrust = CL + 2 * DM, 0.01, 8000.0
    a = axial_acceleration(x, v, thrust, m, CL, DM, KCB, KWS, KH, CAX)
    assert a == pytest.approx((thrust + fax(x, v)) / m, rel=1e-12)
    # static equilibrium under thrust: F_thrust + F_ax = 0 -> zero acceleration
    x_eq = CL + DM + (thrust - K1 * DM) / K2
    assert axial_acceleration(x_eq, 0.0, thrust, m, CL, DM, KCB, KWS, KH, CAX) == \
        pytest.approx(0.0, abs=1e-9)


def test_windage_law_and_example_value():
    c1, c2 = windage_coefficients_cylinder(0.03, 1.0, 733.0)
    assert c1 == pytest.approx(2.036e-7, rel=1e-3)
    assert c2 == pytest.approx(1.080e-8, rel=2e-3)
    t = windage_torque(733.0, c1, c2)
    assert t == pytest.approx(-5.95e-3, rel=3e-3)
    assert windage_torque(-733.0, c1, c2) == pytest.approx(-t)   # odd, always opposes spin
    assert windage_torque(0.0, c1, c2) == 0.0
    assert windage_torque(10.0, 1e-3, 0.0) * 10.0 < 0.0
