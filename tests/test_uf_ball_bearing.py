"""Tests of user_forces.ball_bearing (eq 22; Harris-Palmgren eqs 23-27, corrected)."""

from __future__ import annotations

import math

import pytest

from user_forces.ball_bearing import (ball_force, harris_palmgren_constants, harris_palmgren_torque,
                                      worn_drag_development, worn_drag_torque)

HP = dict(contact_angle_deg=40.0, C_s=45000.0, d_m=0.085, z_hp=0.001, y_hp=0.33,
          omega_reg=0.1)


def test_ball_force_restoring_polynomial_and_action_reaction():
    assert ball_force(0.0, 0.0, 1e8, 1e12) == (0.0, 0.0)        # r = 0 regular
    k1, k2 = 2e8, 3e12
    dy, dz = 3e-6, -4e-6                                         # r = 5e-6
    fy, fz = ball_force(dy, dz, k1, k2)
    mag = k2 * 25e-12 + k1 * 5e-6                                # = 75 + 1000 = 1075 N
    assert math.hypot(fy, fz) == pytest.approx(1075.0, rel=1e-12)
    assert fy * dy + fz * dz < 0.0                               # restoring (towards outer)
    assert fy == pytest.approx(-mag * 0.6) and fz == pytest.approx(mag * 0.8)
    # outer race gets the opposite: swapping roles flips the force
    assert ball_force(-dy, -dz, k1, k2) == pytest.approx((-fy, -fz))
    # optional viscous term
    gy, gz = ball_force(dy, dz, k1, k2, dvy=0.1, dvz=0.0, c_b=100.0)
    assert (gy - fy, gz - fz) == pytest.approx((-10.0, 0.0))


def test_eq26_ys_catalogue_values():
    # Y_s from eq 26 with the contact angle in degrees matches catalogue Y0 (0.46 @ 15, 0.26 @ 40)
    def ys(a):
        return 7.1429e-5 * a * a - 1.2443e-2 * a + 0.64129
    assert ys(15.0) == pytest.approx(0.46, abs=0.015)
    assert ys(40.0) == pytest.approx(0.26, abs=0.005)


def test_harris_palmgren_hand_calculation():
    # Case 1: Fr = 2000 N, Fa = 1000 N, a = 40 deg, C_s = 45000 N, d_m = 0.085 m, z = 0.001,
    # y = 0.33, omega = 100 rad/s, omega_reg = 0.1 rad/s.
    #   Y_s   = 7.1429e-5*1600 - 1.2443e-2*40 + 0.64129 = 0.1142864 - 0.49772 + 0.64129 = 0.2578564
    #   F_s   = 0.5*2000 + 0.2578564*1000 = 1257.8564 < Fr  -> F_s = Fr = 2000 (catalogue rule)
    #   f1    = 0.001*(2000/45000)^0.33 = 0.001*0.0444444^0.33 = 0.001*0.357915 = 3.57915e-4
    #   cot40 = 1.1917536;  F_beta = 0.9*1000*1.1917536 - 0.1*2000 = 872.578 < Fr -> 2000
    #   reg   = 100/sqrt(100^2 + 0.1^2) = 0.9999995
    #   T     = -3.57915e-4 * 2000 * 0.085 * 0.9999995 = -0.0608455 N m
    t1 = harris_palmgren_torque(100.0, 2000.0, 1000.0, **HP)
    assert t1 == pytest.approx(-0.0608455, rel=2e-6)
    # Case 2: Fr = 1000 N, Fa = 3000 N (the other branches of both max rules)
    #   F_s    = 0.5*1000 + 0.2578564*3000 = 1273.5692 (> Fr)
    #   f1     = 0.001*(1273.5692/45000)^0.33 = 0.001*0.0283015^0.33 = 3.083879e-4
    #   F_beta = 0.9*3000*1.1917536 - 0.1*1000 = 3217.7347 - 100 = 3117.7347 (> Fr)
    #   T      = -3.083879e-4 * 3117.7347 * 0.085 * 0.9999995 = -0.0817251 N m
    t2 = harris_palmgren_torque(100.0, 1000.0, 3000.0, **HP)
    assert t2 == pytest.approx(-0.0817251, rel=2e-6)
    # loads enter as absolute values; the torque opposes the relative spin (odd in omega)
    assert harris_palmgren_torque(-100.0, -1000.0, -3000.0, **HP) == pytest.approx(-t2)


def test_harris_palmgren_f_beta_never_negative_pure_radial():
    # the printed eq 27 gives F_beta = -0.1 Fr < 0 for Fa = 0 (a driving torque); with Harris's
    # max rule F_beta = Fr and the torque still opposes the spin
    t = harris_palmgren_torque(50.0, 3000.0, 0.0, **HP)
    f1 = 0.001 * (3000.0 / 45000.0) ** 0.33       # F_s = max(0.5*3000, 3000) = 3000
    assert t < 0.0
    assert t == pytest.approx(-f1 * 3000.0 * 0.085, rel=1e-5)
    assert harris_palmgren_torque(50.0, 0.0, 0.0, **HP) == 0.0


def test_harris_palmgren_regularised_sign():
    t_small = harris_palmgren_torque(1e-4, 1000.0, 3000.0, **HP)
    t_big = harris_palmgren_torque(100.0, 1000.0, 3000.0, **HP)
    assert abs(t_small) < 2e-3 * abs(t_big)                       # smooth through zero
    assert harris_palmgren_torque(0.0, 1000.0, 3000.0, **HP) == 0.0
    with pytest.raises(ValueError):
        harris_palmgren_torque(1.0, 1.0, 1.0, **{**HP, "contact_angle_deg": 0.0})


def test_worn_drag_torque_is_a_regularised_coulomb_torque():
    """Opposes the race spin, magnitude -> the set torque once |omega| >> omega_reg, odd,
    load-independent, and never feeds energy in (T * omega <= 0)."""
    for w in (733.0, 20.0, -50.0):
        assert worn_drag_torque(w, 2.5) == pytest.approx(-2.5 * math.copysign(1.0, w), rel=1e-4)
    assert worn_drag_torque(0.0, 2.5) == 0.0
    assert worn_drag_torque(0.1, 2.5, omega_reg=0.1) == pytest.approx(-2.5 / math.sqrt(2.0))
    for w in (-3.0, -1e-3, 1e-3, 0.05, 400.0):
        assert worn_drag_torque(w, 1.7) == -worn_drag_torque(-w, 1.7)
        assert worn_drag_torque(w, 1.7) * w < 0.0
    assert worn_drag_torque(500.0, 0.0) == 0.0


def test_worn_drag_development_closed_form_and_derivative():
    """g = 1 - exp(-|phi| / phi_c): 0 at the landing, 1 - 1/e after phi_c, -> 1; even in phi;
    g = 1 for phi_c = 0 (drag present from the start); dg/dphi against a central difference."""
    assert worn_drag_development(0.0, 60.0)[0] == 0.0
    assert worn_drag_development(60.0, 60.0)[0] == pytest.approx(1.0 - math.exp(-1.0), rel=1e-14)
    assert worn_drag_development(-60.0, 60.0)[0] == worn_drag_development(60.0, 60.0)[0]
    assert worn_drag_development(6000.0, 60.0)[0] == 1.0
    assert worn_drag_development(123.0, 0.0) == (1.0, 0.0)
    for phi in (-80.0, -1.0, 0.3, 45.0, 300.0):
        h = 1e-6 * max(1.0, abs(phi))
        fd = (worn_drag_development(phi + h, 60.0)[0] - worn_drag_development(phi - h, 60.0)[0]) / (2 * h)
        assert worn_drag_development(phi, 60.0)[1] == pytest.approx(fd, rel=1e-6)


def test_developing_worn_drag_is_the_developed_share_of_the_full_torque():
    """T(omega, phi) = g(phi) T(omega) for any speed; still opposes the spin; the default
    (growth_angle 0) is the torque present from the start."""
    for w in (733.0, -20.0, 0.05):
        for phi in (0.0, 10.0, 60.0, 700.0):
            g = worn_drag_development(phi, 60.0)[0]
            assert worn_drag_torque(w, 2.5, 0.1, phi, 60.0) == pytest.approx(g * worn_drag_torque(w, 2.5, 0.1), rel=1e-14)
            assert worn_drag_torque(w, 2.5, 0.1, phi, 60.0) * w <= 0.0
        assert worn_drag_torque(w, 2.5, 0.1, 50.0, 0.0) == worn_drag_torque(w, 2.5, 0.1)


@pytest.mark.parametrize("omega, fr, fa", [
    (50.0, 800.0, 0.0),      # pure radial: both catalogue floors (F_s = F_beta = F_r) active
    (-20.0, 300.0, 4000.0),  # thrust-dominated: X_s F_r + Y_s F_a and 0.9 F_a cot(a) - 0.1 F_r branches
    (0.05, 1500.0, 200.0),   # inside the regularisation band omega ~ omega_reg
])
def test_harris_palmgren_derivatives_equal_central_differences(omega, fr, fa):
    from user_forces.ball_bearing import harris_palmgren_fast, harris_palmgren_with_derivatives

    k = harris_palmgren_constants(40.0, 4.5e4, 0.085, 0.001, 0.33, omega_reg=0.1)
    T, d_fr, d_fa, d_om = harris_palmgren_with_derivatives(omega, fr, fa, k)
    assert T == harris_palmgren_fast(omega, fr, fa, k)
    assert T == pytest.approx(harris_palmgren_torque(omega, fr, fa, contact_angle_deg=40.0, C_s=4.5e4, d_m=0.085,
                                                     z_hp=0.001, y_hp=0.33, omega_reg=0.1), rel=1e-12)
    for x, d, h in ((0, d_fr, 1e-3), (1, d_fa, 1e-3), (2, d_om, 1e-4 * max(abs(omega), 0.1))):
        args = [omega, fr, fa]
        hi, lo = list(args), list(args)
        idx = {0: 1, 1: 2, 2: 0}[x]
        hi[idx] += h
        lo[idx] -= h
        fd = (harris_palmgren_with_derivatives(*hi, k)[0] - harris_palmgren_with_derivatives(*lo, k)[0]) / (2 * h)
        # truncation ~ (h / omega)^2 <= 2e-8 here; the round-off of a central difference is ~eps |T| / h
        assert abs(d - fd) <= 1e-6 * abs(fd) + 8 * 2.2e-16 * abs(T) / h, (x, d, fd)


def test_worn_friction_hand_calculation_and_sign():
    """T = -mu_w (d_m / 2) F_beta g reg(omega): pure radial load (F_beta = F_r, Harris's floor) and a
    thrust-dominated one (F_beta = 0.9 F_a cot a - 0.1 F_r), by hand."""
    from user_forces.ball_bearing import worn_friction_torque

    kw = dict(friction=0.2, contact_angle_deg=40.0, d_m=0.085, omega_reg=0.1)
    # 2 kN radial, race far above omega_reg: 0.2 x 0.0425 m x 2000 N = 17 N m
    assert worn_friction_torque(700.0, 2000.0, 0.0, **kw) == pytest.approx(-17.0, rel=1e-7)
    # 300 N radial + 4 kN axial: F_beta = 0.9 x 4000 x cot(40 deg) - 0.1 x 300 = 4260.3 N
    f_beta = 0.9 * 4000.0 / math.tan(math.radians(40.0)) - 30.0
    assert worn_friction_torque(-700.0, 300.0, 4000.0, **kw) == pytest.approx(0.2 * 0.0425 * f_beta, rel=1e-7)
    assert worn_friction_torque(0.0, 2000.0, 0.0, **kw) == 0.0
    assert worn_friction_torque(700.0, 2000.0, 0.0, **{**kw, "friction": 0.0}) == 0.0  # off: nothing
    # the load-proportional part scales with the load (the property the mu_rad switch rests on)
    assert worn_friction_torque(700.0, 5000.0, 0.0, **kw) == pytest.approx(
        2.5 * worn_friction_torque(700.0, 2000.0, 0.0, **kw), rel=1e-12)
    # it develops with the race angle exactly as the load-independent worn drag
    g = worn_drag_development(30.0, 60.0)[0]
    assert worn_friction_torque(700.0, 2000.0, 0.0, angle=30.0, growth_angle=60.0, **kw) == pytest.approx(
        g * worn_friction_torque(700.0, 2000.0, 0.0, **kw), rel=1e-14)


@pytest.mark.parametrize("omega, fr, fa, angle, growth", [
    (50.0, 800.0, 0.0, 20.0, 60.0),      # pure radial, developing
    (-20.0, 300.0, 4000.0, -5.0, 60.0),  # thrust-dominated branch, negative spin and angle
    (0.05, 1500.0, 200.0, 200.0, 60.0),  # inside the regularisation band
    (400.0, 1500.0, 0.0, 3.0, 0.0),      # no development (growth angle 0)
])
def test_worn_friction_derivatives_equal_central_differences(omega, fr, fa, angle, growth):
    from user_forces.ball_bearing import worn_friction_constants, worn_friction_with_derivatives

    k = worn_friction_constants(0.2, 40.0, 0.085, growth, omega_reg=0.1)
    out = worn_friction_with_derivatives(omega, fr, fa, angle, k)
    T = out[0]
    args = [omega, fr, fa, angle]
    # (argument index, derivative, step)
    for idx, d, h in ((1, out[1], 1e-3), (2, out[2], 1e-3), (0, out[3], 1e-4 * max(abs(omega), 0.1)), (3, out[4], 1e-4)):
        hi, lo = list(args), list(args)
        hi[idx] += h
        lo[idx] -= h
        fd = (worn_friction_with_derivatives(*hi, k)[0] - worn_friction_with_derivatives(*lo, k)[0]) / (2 * h)
        assert abs(d - fd) <= 1e-6 * abs(fd) + 8 * 2.2e-16 * abs(T) / h, (idx, d, fd)
