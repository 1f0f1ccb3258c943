"""Tests of the laws of the levitated state and the drive (user_forces.amb, user_forces.spin):
each against an independent computation."""

import math

import pytest

from user_forces.amb import amb_force, unbalance_force
from user_forces.spin import drive_torque, windage_torque, windage_torque_derivative


def test_amb_holds_its_static_load_at_the_equilibrium_offset():
    # a rotor share of 500 N on an axis of 2e7 N/m with no bias sags to x = -W/k, where the AMB
    # force balances the weight; with the bias = weight it stays at its set point
    k, c, w = 2.0e7, 3.0e3, 500.0
    assert amb_force(-w / k, 0.0, 0.0, k, c) == pytest.approx(w, rel=1e-15)
    assert amb_force(0.0, 0.0, w, k, c) == w
    assert amb_force(1e-6, 0.01, w, k, c) == pytest.approx(w - k * 1e-6 - c * 0.01, rel=1e-15)


def test_unbalance_force_is_the_centripetal_reaction_of_the_point_mass():
    """m e Omega^2 outwards along the unbalance: the reaction to the point mass's acceleration,
    here by central differences of its position e (cos(Omega t + phi), sin(...))."""
    m, e, om, phi = 0.02, 5e-3, 733.0, 0.7
    me = m * e
    h = 1e-6
    pos = [(e * math.cos(om * t + phi), e * math.sin(om * t + phi)) for t in (-h, 0.0, h)]
    ay = (pos[0][0] - 2 * pos[1][0] + pos[2][0]) / h**2
    az = (pos[0][1] - 2 * pos[1][1] + pos[2][1]) / h**2
    fy, fz = unbalance_force(om, phi, me)
    assert fy == pytest.approx(-m * ay, rel=1e-5) and fz == pytest.approx(-m * az, rel=1e-5)


def test_drive_torque_pulls_to_its_set_speed():
    g, w0 = 2.0, 733.0
    assert drive_torque(w0, g, w0) == 0.0
    assert drive_torque(w0 - 10.0, g, w0) == pytest.approx(20.0) and drive_torque(w0 + 1.0, g, w0) < 0


@pytest.mark.parametrize("omega", [-500.0, -0.3, 0.4, 733.0])
def test_windage_derivative_against_central_differences(omega):
    c1, c2 = 2e-7, 1.1e-8
    h = 1e-3 * max(abs(omega), 1.0)
    fd = (windage_torque(omega + h, c1, c2) - windage_torque(omega - h, c1, c2)) / (2 * h)
    assert windage_torque_derivative(omega, c1, c2) == pytest.approx(fd, rel=1e-9)
