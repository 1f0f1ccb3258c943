"""Tests of user_forces.axial_rub (eqs 18-21, our notation) and of the package rules."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from user_forces.axial_rub import V_REG_DEFAULT, axial_rub, axial_rub_reference, axial_rub_slip_jacobian

W = 733.0                  # 7000 rpm
R1, R2 = 0.032, 0.045      # contact annulus about the race centre [m]
MU, FAX = 0.3, 4000.0
D = (8e-5, -6e-5)          # |d| = 0.1 mm

#        dy    dz    dvy   dvz  om_r  om_i    alpha  beta   delta_ax  f_ax  sign
STATES = {
    "wilkes_race_spun_up": (*D, 0.0, 0.0, W, W, 0.0, 0.0, 1e-5, FAX, +1),
    "race_at_rest": (*D, 0.01, -0.02, W, 0.0, 0.0, 0.0, 1e-5, FAX, +1),
    "tilt_partial_rest": (*D, 0.0, 0.0, W, 0.0, 2e-4, -1e-4, 2e-6, FAX, +1),
    "tilt_partial_spun_neg_face": (*D, 0.01, 0.0, W, 0.7 * W, 2e-4, -1e-4, -3e-6, -FAX, -1),
    "tilt_line_inside_annulus": (*D, 0.0, 0.0, W, 0.5 * W, 2e-4, -1e-4, 8e-6, FAX, +1),
    "tilt_full_contact": (*D, 0.0, 0.0, W, 0.5 * W, 2e-5, -1e-5, 8e-6, FAX, +1),
    "near_synchronous": (*D, 0.0, 0.0, W, W - 2.0, 0.0, 0.0, 1e-5, FAX, +1),
}


def rub(state, fn=axial_rub):
    return fn(*state, MU, V_REG_DEFAULT, R1, R2)


def _power(out, st):
    fy, fz, t_r, t_i, _ = out
    return fy * st[2] + fz * st[3] + t_r * st[4] + t_i * st[5]


@pytest.mark.parametrize("name", list(STATES))
def test_fast_quadrature_matches_reference(name):
    st = STATES[name]
    f, r = rub(st), rub(st, axial_rub_reference)
    scale_t = MU * FAX * R2
    assert math.hypot(f[0] - r[0], f[1] - r[1]) <= 5e-3 * math.hypot(r[0], r[1]) + 1e-9 * MU * FAX
    assert abs(f[2] - r[2]) <= 5e-3 * abs(r[2]) + 1e-9 * scale_t
    assert abs(f[3] - r[3]) <= 5e-3 * abs(r[3]) + 1e-9 * scale_t
    assert f[4] == pytest.approx(r[4], rel=5e-3)


@pytest.mark.parametrize("name", list(STATES))
@pytest.mark.parametrize("fn", [axial_rub, axial_rub_reference])
def test_friction_power_and_angular_momentum_balance(name, fn):
    st = STATES[name]
    out = rub(st, fn)
    fy, fz, t_r, t_i, p = out
    assert p > 0.0
    assert _power(out, st) == pytest.approx(-p, rel=1e-9)          # friction only dissipates
    # action = reaction: race force is -F; angular momentum about a fixed point is conserved
    dy, dz = st[0], st[1]
    assert abs(t_r + t_i + (dy * fz - dz * fy)) <= 1e-9 * MU * FAX * R2


def test_wilkes_forward_force_direction():
    # race spun up to the rotor speed, rotor eccentric: uniform slip -W e_x x d, so the force on
    # the rotor is mu |F_ax| along e_x x d / |d| = (-d_z, d_y)/|d| = (0.6, 0.8): forward
    fy, fz, t_r, t_i, p = rub(STATES["wilkes_race_spun_up"])
    assert fy == pytest.approx(MU * FAX * 0.6, rel=1e-3)
    assert fz == pytest.approx(MU * FAX * 0.8, rel=1e-3)
    # the uniform traction has no moment about the race centre
    assert abs(t_i) < 1e-9 * MU * FAX * R2
    # whirl the eccentricity the other way: the force follows e_x x d
    st = list(STATES["wilkes_race_spun_up"])
    st[0], st[1] = 0.0, -1e-4                 # rotor at the bottom -> force along +y
    fy, fz = rub(tuple(st))[:2]
    assert fy == pytest.approx(MU * FAX, rel=1e-3) and abs(fz) < 1e-6 * MU * FAX


def test_concentric_equal_spin_no_force():
    st = (0.0, 0.0, 0.0, 0.0, W, W, 0.0, 0.0, 1e-5, FAX, +1)
    out = rub(st)
    assert all(abs(v) < 1e-12 for v in out)


def test_concentric_race_at_rest_mean_friction_radius():
    # d = 0, race at rest, uniform pressure: T_rotor = -mu F r_f, r_f = 2/3 (r2^3-r1^3)/(r2^2-r1^2)
    st = (0.0, 0.0, 0.0, 0.0, W, 0.0, 0.0, 0.0, 1e-5, FAX, +1)
    fy, fz, t_r, t_i, p = rub(st)
    r_f = 2.0 / 3.0 * (R2 ** 3 - R1 ** 3) / (R2 ** 2 - R1 ** 2)
    assert t_r == pytest.approx(-MU * FAX * r_f, rel=1e-6)
    assert t_i == pytest.approx(-t_r, rel=1e-12)           # eq 21 holds for d = 0
    assert math.hypot(fy, fz) < 1e-9 * MU * FAX


def test_no_axial_force_or_no_contact_no_friction():
    st = list(STATES["tilt_partial_rest"])
    st[9] = 0.0
    assert rub(tuple(st)) == (0.0,) * 5
    st = list(STATES["race_at_rest"])
    st[8] = -1e-6                                  # faces apart, no tilt
    assert rub(tuple(st)) == (0.0,) * 5
    assert rub(tuple(st), axial_rub_reference) == (0.0,) * 5


def test_tilt_moves_the_contact_to_one_side():
    # face_sign +1, alpha > 0 (rotation about y): points with z > 0 move to +x and press harder.
    # Concentric rotor, race at rest: pressure on the +z side only; the friction there on the
    # spinning rotor (surface moving -y there) is along +y; with face_sign -1 the -z side
    # carries the load and the force is along -y.
    base = [0.0, 0.0, 0.0, 0.0, W, 0.0, 1e-3, 0.0, 0.0, FAX, +1]
    fy_p = rub(tuple(base))[0]
    base[10] = -1
    fy_m = rub(tuple(base))[0]
    assert fy_p > 0.3 * MU * FAX and fy_m < -0.3 * MU * FAX


def test_laws_are_plain_python_without_numpy_or_exudyn():
    code = ("import sys, user_forces.radial_contact, user_forces.ball_bearing, "
            "user_forces.ribbon, user_forces.axial, user_forces.spin, user_forces.axial_rub\n"
            "bad = [m for m in ('numpy', 'exudyn') if m in sys.modules]\n"
            "assert not bad, bad\n")
    subprocess.run([sys.executable, "-c", code], check=True)
    out = axial_rub(*STATES["race_at_rest"], MU, V_REG_DEFAULT, R1, R2)
    assert type(out) is tuple and all(type(v) is float for v in out)


def _slip_jacobian_columns(st):
    """d(Fy, Fz, T_rot, T_race)/d(dy, dz, dvy, dvz, om_r, om_i) from axial_rub_slip_jacobian's sums
    by the chain rule (plus T_rot's explicit lever arm), at a fixed contact patch."""
    fy, fz, _, _, sc, d = rub(st, axial_rub_slip_jacobian)
    dy, dz, om = st[0], st[1], st[4]
    e = [(0.0, -om, 0.0), (om, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (dz, -dy, 1.0), (0.0, 0.0, -1.0)]
    cols = []
    for e0, e1, e2 in e:
        dsy, dsz, dmi = (d[3 * i] * e0 + d[3 * i + 1] * e1 + d[3 * i + 2] * e2 for i in range(3))
        cols.append([-sc * dsy, -sc * dsz, -sc * (dmi - dy * dsz + dz * dsy), sc * dmi])
    cols[0][2] += -fz
    cols[1][2] += fy
    return cols


@pytest.mark.parametrize("name", list(STATES))
def test_slip_jacobian_has_the_laws_forces(name):
    st = STATES[name]
    assert rub(st, axial_rub_slip_jacobian)[:4] == rub(st)[:4]     # same quadrature, same rounding


@pytest.mark.parametrize("name", [n for n, st in STATES.items() if st[6] == st[7] == 0.0])
def test_slip_jacobian_against_central_differences(name):
    """Without tilt the patch does not move with any of the six inputs, so the derivatives through
    the slip field (plus the lever arm) are the whole derivative of axial_rub."""
    st = STATES[name]
    cols = _slip_jacobian_columns(st)
    steps = (1e-9, 1e-9, 1e-6, 1e-6, 1e-4, 1e-4)
    for j, h in enumerate(steps):
        up, dn = list(st), list(st)
        up[j] += h
        dn[j] -= h
        fd = [(a - b) / (2 * h) for a, b in zip(rub(tuple(up))[:4], rub(tuple(dn))[:4])]
        scale = max(abs(x) for x in fd) + 1e-12
        for i in range(4):
            assert cols[j][i] == pytest.approx(fd[i], rel=1e-5, abs=1e-6 * scale), (j, i)
