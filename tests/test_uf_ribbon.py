"""Tests of user_forces.ribbon (eqs 28-30)."""

from __future__ import annotations

import math

import pytest

from user_forces.ribbon import outer_race_friction, ribbon_force

K, CR, ETA, VREG = 6.3e7, 2000.0, 0.15, 1e-3


@pytest.mark.parametrize("sense", [+1.0, -1.0])
def test_cross_coupling_power_nonpositive_on_circular_orbit(sense):
    # circular orbit of radius R at whirl rate sense*w; the cross-coupled part alone (c = 0,
    # minus the -k x part) must dissipate k eta R^2 |w| at every instant, in either direction
    R, w = 5e-5, 2 * math.pi * 50.0
    for i in range(36):
        ph = 2 * math.pi * i / 36
        y, z = R * math.cos(ph), R * math.sin(ph)
        vy, vz = -sense * R * w * math.sin(ph), sense * R * w * math.cos(ph)
        fy, fz = ribbon_force(y, z, vy, vz, K, 0.0, ETA, VREG)
        fcy, fcz = fy + K * y, fz + K * z            # remove the elastic -k x
        power = fcy * vy + fcz * vz
        v_t = R * w
        expected = -K * ETA * R * v_t * v_t / math.sqrt(v_t ** 2 + VREG ** 2)
        assert power < 0.0
        assert power == pytest.approx(expected, rel=1e-9)


def test_ribbon_elastic_viscous_parts_and_centre():
    assert ribbon_force(0.0, 0.0, 0.0, 0.0, K, CR, ETA, VREG) == (0.0, 0.0)
    assert ribbon_force(0.0, 0.0, 0.1, 0.0, K, CR, ETA, VREG) == pytest.approx((-200.0, 0.0))
    # radial motion only: no tangential velocity -> no cross-coupled force
    fy, fz = ribbon_force(1e-5, 0.0, 0.01, 0.0, K, CR, ETA, VREG)
    assert (fy, fz) == pytest.approx((-K * 1e-5 - CR * 0.01, 0.0))


def test_outer_race_friction_regularised_coulomb():
    fy, fz = outer_race_friction(0.03, -0.04, -4000.0, 0.2, VREG)     # |v| = 0.05
    mag = 0.2 * 4000.0 * 0.05 / math.sqrt(0.05 ** 2 + VREG ** 2)
    assert math.hypot(fy, fz) == pytest.approx(mag, rel=1e-12)
    assert fy * 0.03 + fz * -0.04 < 0.0                                # opposes velocity
    assert outer_race_friction(0.0, 0.0, 4000.0, 0.2, VREG) == (0.0, 0.0)
    assert outer_race_friction(0.03, -0.04, 0.0, 0.2, VREG) == (0.0, 0.0)
    # sign of F_ax does not matter (|F_ax|), eq 30 as printed would flip it
    assert outer_race_friction(0.03, -0.04, 4000.0, 0.2, VREG) == pytest.approx((fy, fz))
