"""Tests of user_forces.radial_contact (paper eqs 10-17, corrected)."""

from __future__ import annotations

import math

import pytest

from user_forces.radial_contact import EXPONENT_HERTZ_POINT, V_REG_DEFAULT, radial_contact

C = 1.0e-4          # clearance [m]
R_ROT = 0.030       # sleeve radius [m]
R_RACE = R_ROT + C  # bore radius [m]
K_H = 5.0e9         # N/m^1.5
K_V = 5.0e9 * 1.0   # N s/m^2.5 (Hunt-Crossley, ~1 s/m damping factor)
MU = 0.3
W = 733.0           # 7000 rpm


def rc(dy, dz, dvy=0.0, dvz=0.0, om_r=W, om_i=0.0, mu=MU, k_v=K_V):
    return radial_contact(dy, dz, dvy, dvz, om_r, om_i, C, K_H, EXPONENT_HERTZ_POINT, k_v, mu,
                          V_REG_DEFAULT, R_ROT, R_RACE)


def test_zero_force_without_contact_and_at_centre():
    assert rc(0.0, 0.0) == (0.0,) * 8                        # |d| = 0: no division by zero
    assert rc(0.3 * C, -0.9 * C, 1.0, -2.0) == (0.0,) * 8    # inside the clearance
    assert rc(0.0, -C, 0.0, -1.0) == (0.0,) * 8              # exactly at the clearance


def test_penetration_is_radial_distance_eq14():
    # bottom contact: y = 0 (the printed eq 14, y - c, would say no contact)
    out = rc(0.0, -(C + 2e-6))
    assert out[5] == pytest.approx(2e-6, rel=1e-9)
    assert out[4] == pytest.approx(K_H * (2e-6) ** 1.5, rel=1e-9)
    # normal force pushes the rotor back towards the race centre (+z at the bottom)
    out = rc(0.0, -(C + 2e-6), om_r=0.0)
    assert out[0] == pytest.approx(0.0, abs=1e-12) and out[1] == pytest.approx(out[4], rel=1e-12)
    # same penetration in an oblique direction gives the same force magnitude
    ang = 1.1
    o2 = rc((C + 2e-6) * math.cos(ang), (C + 2e-6) * math.sin(ang), om_r=0.0)
    assert math.hypot(o2[0], o2[1]) == pytest.approx(out[4], rel=1e-9)


def test_force_continuous_at_onset_and_never_adhesive():
    # Hunt-Crossley: damping ~ delta^e, so even an impact at 1 m/s starts from zero force
    f_small = rc(0.0, -(C + 1e-12), 0.0, -1.0)
    f_ref = rc(0.0, -(C + 1e-6), 0.0, -1.0)
    assert math.hypot(f_small[0], f_small[1]) < 1e-8 * math.hypot(f_ref[0], f_ref[1])
    # a fast separation would make the normal force negative: clipped to zero
    out = rc(0.0, -(C + 1e-6), 0.0, +10.0)      # delta_dot = -10 m/s, k_visc*delta_dot < -k
    assert out[4] == 0.0 and out[0] == 0.0 and out[1] == 0.0
    assert out[5] > 0.0                          # still reports the penetration


def test_frame_is_a_rotation_friction_sign_at_bottom():
    # Rotor spinning +x resting at the bottom: its surface there moves along e_x x (-e_z) = +y,
    # so the friction on the rotor is -y, the race is dragged +y and spun up (T_race > 0).
    # The paper's reflection (eq 12) flips this on one side of the bore.
    for ang in (-math.pi / 2, 0.0, 0.7, math.pi / 2, 2.5):
        ny, nz = math.cos(ang), math.sin(ang)
        out = rc((C + 1e-6) * ny, (C + 1e-6) * nz, om_r=W, om_i=0.0)
        fy, fz, t_rot, t_race, fn = out[:5]
        ty, tz = -nz, ny
        f_t = fy * ty + fz * tz
        assert f_t == pytest.approx(-MU * fn, rel=1e-6)   # friction along -t on the rotor
        assert t_rot < 0.0 < t_race
    out = rc(0.0, -(C + 1e-6), om_r=W)
    assert out[0] < 0.0


def test_friction_power_balance_and_own_radii():
    # total power of contact actions = -F_N delta_dot - P_diss, with P_diss = mu F_N v_s reg >= 0
    # (fails with the paper's mean radius (r_i + r_r)/2 on both bodies)
    for dvy, dvz, om_r, om_i in [(0.05, -0.02, W, 0.0), (-0.3, 0.1, W, 400.0),
                                 (0.0, 0.0, 100.0, 2000.0), (0.01, 0.0, -50.0, 10.0)]:
        dy, dz = 0.6 * (C + 3e-6), -0.8 * (C + 3e-6)
        fy, fz, t_r, t_i, fn, delta, v_s, p = rc(dy, dz, dvy, dvz, om_r, om_i)
        ny, nz = dy / math.hypot(dy, dz), dz / math.hypot(dy, dz)
        ddot = ny * dvy + nz * dvz
        power = fy * dvy + fz * dvz + t_r * om_r + t_i * om_i
        assert fn > 0.0 and p >= 0.0
        assert power == pytest.approx(-fn * ddot - p, rel=1e-9, abs=1e-9)
        reg = v_s / math.sqrt(v_s ** 2 + V_REG_DEFAULT ** 2)
        assert p == pytest.approx(MU * fn * v_s * reg, rel=1e-12)
        # slip velocity eq 16 with both surface speeds
        assert v_s == pytest.approx(-nz * dvy + ny * dvz + om_r * R_ROT - om_i * R_RACE,
                                    rel=1e-12)
        # friction opposes slip: tangential force on rotor has the sign of -v_s
        assert (fy * -nz + fz * ny) * v_s <= 0.0


def test_action_reaction_angular_momentum():
    # Force on race = -force on rotor (returned implicitly).  Angular momentum about a fixed
    # point: T_rotor + T_race + (d x F_rotor)_x = -mu F_N reg * delta (contact-point ambiguity
    # of a penetrating contact, O(delta)); it vanishes for delta -> 0.
    dy, dz = -(C + 4e-6) * 0.28, -(C + 4e-6) * 0.96
    fy, fz, t_r, t_i, fn, delta, v_s, p = rc(dy, dz, 0.01, 0.02, W, 300.0)
    reg = v_s / math.sqrt(v_s ** 2 + V_REG_DEFAULT ** 2)
    lhs = t_r + t_i + (dy * fz - dz * fy)
    assert lhs == pytest.approx(-MU * fn * reg * delta, rel=1e-6)


def test_rolling_without_slip_no_friction():
    out = rc(0.0, -(C + 1e-6), om_r=W, om_i=W * R_ROT / R_RACE)
    assert abs(out[6]) < 1e-12
    assert abs(out[0]) < 1e-9 * out[4] and abs(out[2]) < 1e-9
