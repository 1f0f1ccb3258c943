"""Compiled catcher-bearing connector: the laws of :func:`rotorlanding.forces.bearing_forces`
as one numba function, and its analytic Jacobian for Exudyn's ``jacobianUserFunction``.

Why: Exudyn differentiates Python user functions numerically (about 2 n + 1 calls of the
9-coordinate bearing function per Jacobian, each crossing the C++/Python boundary). The kernel
here computes the same forces (the laws of ``user_forces`` compiled unchanged with numba) and
the 9 x 9 derivatives w.r.t. the local coordinates and velocities in one call:

- radial contact, balls, Harris-Palmgren drag, ribbon, outer-race Coulomb friction, axial
  force: analytic derivatives of the plain-float laws (chain rule through the local
  kinematics d = station - race, r = race - outer);
- axial rub (a 72-point quadrature): the derivatives through the slip field come with the
  quadrature from ``user_forces.axial_rub.axial_rub_slip_jacobian`` (forward mode, same points);
  the contact patch's motion with the axial approach by a central difference of the compiled law;
  f_axial enters linearly (exact). One Python call.

The rotor tilt at the axial face comes from a holder updated once per step (as in
``bearing_forces``) and is a parameter here, not a coordinate.

Local coordinates (``forces.BEARING_LOCAL``):
q = [station y, z | theta, x_ax | race y, z, phi | outer y, z], v = their rates.

``tests/test_bearing_jacobian.py`` checks the forces against ``bearing_forces`` and the
Jacobian against finite differences (free flight, radial contact with slip, face contact with
full and partial pressure, moving outer race) and against Exudyn's own numerical system
Jacobian.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from user_forces.amb import amb_force as _amb_py
from user_forces.axial import axial_force as _axial_force_py
from user_forces.axial_rub import axial_rub_quadrature as _axial_rub_q_py
from user_forces.ball_bearing import ball_force as _ball_force_py
from user_forces.ball_bearing import harris_palmgren_with_derivatives as _hp_law_py
from user_forces.ball_bearing import worn_drag_development as _worn_dev_py
from user_forces.ball_bearing import worn_drag_torque as _worn_drag_py
from user_forces.ball_bearing import worn_friction_with_derivatives as _worn_fr_law_py
from user_forces.radial_contact import radial_contact as _radial_contact_py
from user_forces.ribbon import outer_race_friction as _outer_race_friction_py
from user_forces.ribbon import ribbon_force as _ribbon_force_py
from user_forces.spin import drive_torque as _drive_py
from user_forces.spin import windage_torque as _windage_py
from user_forces.spin import windage_torque_derivative as _windage_d_py
from user_forces.contact_stress import line_contact_fast as _line_contact_py
from user_forces.thermal import blok_partition_fast as _blok_py

from .landing import G_ACC, BearingSpec, LandingSpec
from .params import OMEGA_REG_HP

_njit = numba.njit(cache=True, fastmath=False)
# every law the kernel evaluates, compiled unchanged from user_forces (no law is written here; the
# post-processing series at the end add only the energy and power bookkeeping around the laws)
(_radial_contact, _axial_force, _axial_rub_q, _worn_drag, _worn_dev, _worn_fr_law, _ball_force, _hp_law,
 _ribbon_force, _outer_race_friction, _windage, _windage_d, _drive, _amb) = map(_njit, (
    _radial_contact_py, _axial_force_py, _axial_rub_q_py, _worn_drag_py, _worn_dev_py, _worn_fr_law_py,
    _ball_force_py, _hp_law_py, _ribbon_force_py, _outer_race_friction_py, _windage_py, _windage_d_py, _drive_py,
    _amb_py))
_line_contact, _blok = _njit(_line_contact_py), _njit(_blok_py)

# parameter vector layout
(P_CL, P_RR, P_RI, P_KH, P_EX, P_KV, P_MU, P_VREG, P_KB1, P_KB2, P_CB, P_DRAG, P_XS, P_YS, P_INVCS, P_ZDM,
 P_YHP, P_C4COT, P_C5, P_WREG2, P_KRIB, P_CRIB, P_ETA, P_COUL, P_MUD, P_CI, P_CO, P_WI, P_WO, P_FACE, P_RUB,
 P_MUAX, P_R1, P_R2, P_VREGAX, P_CLAX, P_DM, P_KCB, P_KWS, P_KHS, P_CAX, P_TW, P_TWPHI, P_WMU, P_WC4, P_WC5,
 P_WWREG2, P_WPHI, P_FAPRE, P_SIZE) = range(50)


# the kernel's slot of every BearingLaws field it reads (bools as 0/1; hp fills P_XS..P_WREG2, worn P_WMU..P_WPHI)
_P_FIELDS = {
    P_CL: "clearance", P_RR: "sleeve_radius", P_RI: "race_radius", P_KH: "k_hertz", P_EX: "exponent",
    P_KV: "k_visc", P_MU: "mu_rad", P_VREG: "v_reg", P_KB1: "k_b1", P_KB2: "k_b2", P_CB: "c_b",
    P_DRAG: "ball_drag", P_KRIB: "k_rib", P_CRIB: "c_rib", P_ETA: "eta", P_COUL: "outer_coulomb", P_MUD: "mu_d",
    P_CI: "inner_race_damping", P_CO: "outer_race_damping", P_FACE: "axial_face", P_RUB: "axial_rub",
    P_MUAX: "mu_ax", P_R1: "face_inner_radius", P_R2: "face_outer_radius", P_VREGAX: "v_reg_axial",
    P_TW: "worn_drag_torque", P_TWPHI: "worn_drag_growth_angle", P_FAPRE: "drag_axial_preload",
}


def bearing_parameters(spec: LandingSpec, b: BearingSpec) -> np.ndarray:
    """The bearing's resolved laws (``b.laws``) and the rotor's axial law as the kernel's float vector."""
    L = b.laws
    a = spec.scenario.axial
    P = np.zeros(P_SIZE)
    for slot, name in _P_FIELDS.items():
        P[slot] = float(getattr(L, name))
    P[P_XS:P_WREG2 + 1] = L.hp
    P[P_WMU:P_WPHI + 1] = L.worn
    P[P_WI], P[P_WO] = -L.inner_race_mass * G_ACC, -L.outer_race_mass * G_ACC
    P[P_CLAX], P[P_DM], P[P_KCB], P[P_KWS], P[P_KHS], P[P_CAX] = a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax
    return P


@_njit
def _hp(omi, fr, fa, P):
    """Harris-Palmgren drag torque and its derivatives (d|fr|, d|fa|, domi): the user_forces law."""
    return _hp_law(omi, fr, fa, (P[P_XS], P[P_YS], P[P_INVCS], P[P_ZDM], P[P_YHP], P[P_C4COT], P[P_C5], P[P_WREG2]))


@_njit
def _worn_fr(omi, fr, fa, rphi, P):
    """Load-proportional worn drag and its derivatives (d|fr|, d|fa|, domi, dphi): the user_forces law."""
    return _worn_fr_law(omi, fr, fa, rphi, (P[P_WMU], P[P_WC4], P[P_WC5], P[P_WWREG2], P[P_WPHI]))


@_njit
def _axial_force_d(x, xd, P):
    """axial_force and its derivatives (d/dx, d/dxd)."""
    f = _axial_force(x, xd, P[P_CLAX], P[P_DM], P[P_KCB], P[P_KWS], P[P_KHS], P[P_CAX])
    if f == 0.0:
        return 0.0, 0.0, 0.0
    cl = P[P_CLAX]
    e = abs(x) - cl
    if e <= P[P_DM]:
        kx = 1.0 / (1.0 / P[P_KCB] + 1.0 / P[P_KWS])
    else:
        kx = 1.0 / (1.0 / P[P_KCB] + 1.0 / P[P_KHS])
    return f, -kx, -P[P_CAX]


@_njit
def _rub(dy, dz, dvy, dvz, om, omi, ta, tb, x, f_ax, P):
    r = _axial_rub_q(dy, dz, dvy, dvz, om, omi, ta, tb, abs(x) - P[P_CLAX], f_ax,
                     1.0 if x >= 0 else -1.0, P[P_MUAX], P[P_VREGAX], P[P_R1], P[P_R2], False)
    return r[0], r[1], r[2], r[3], r[4]


@_njit
def _rub_velocity_jac(dy, dz, dvy, dvz, om, omi, ta, tb, x, f_ax, P, C):
    """Axial rub with its derivatives through the slip field, d(Fy, Fz, T_rot, T_race)/d(dy, dz,
    dvy, dvz, om, omi) at a fixed contact patch, added into C[:, 0:6]: the quadrature sums and
    their derivatives are user_forces.axial_rub_quadrature's, the chain rule is here; the
    patch's dependence on the axial approach a0 (and through it on dy, dz, x) is added by the
    caller. Returns (Fy, Fz, T_rot, T_race)."""
    fy, fz, trot, trace, _, sc, D = _axial_rub_q(dy, dz, dvy, dvz, om, omi, ta, tb, abs(x) - P[P_CLAX], f_ax,
                                                 1.0 if x >= 0 else -1.0, P[P_MUAX], P[P_VREGAX], P[P_R1], P[P_R2],
                                                 True)
    if sc == 0.0:
        return 0.0, 0.0, 0.0, 0.0
    # (cy0, cz0, dom) w.r.t. inputs (dy, dz, dvy, dvz, om, omi)
    E = np.zeros((3, 6))
    E[1, 0] = -om
    E[0, 1] = om
    E[0, 2] = 1.0
    E[1, 3] = 1.0
    E[0, 4] = dz
    E[1, 4] = -dy
    E[2, 4] = 1.0
    E[2, 5] = -1.0
    for j in range(6):
        dsy = D[0] * E[0, j] + D[1] * E[1, j] + D[2] * E[2, j]
        dsz = D[3] * E[0, j] + D[4] * E[1, j] + D[5] * E[2, j]
        dmi = D[6] * E[0, j] + D[7] * E[1, j] + D[8] * E[2, j]
        C[0, j] += -sc * dsy
        C[1, j] += -sc * dsz
        C[2, j] += -sc * (dmi - dy * dsz + dz * dsy)
        C[3, j] += sc * dmi
    # explicit d in T_rot = -sc (mi - dy sz + dz sy): -fz = sc sz, fy = -sc sy
    C[2, 0] += -fz
    C[2, 1] += fy
    return fy, fz, trot, trace


@_njit
def bearing_rhs(P, sy, sz, th, x, ry, rz, rphi, oy, oz, vsy, vsz, om, xd, vry, vrz, omi, voy, voz, ta, tb):
    """The 9 local generalized forces of one bearing (= forces.bearing_forces)."""
    dy = sy - ry
    dz = sz - rz
    dvy = vsy - vry
    dvz = vsz - vrz
    fy, fz, t_rot, t_race, _, _, _, _ = _radial_contact(dy, dz, dvy, dvz, om, omi, P[P_CL], P[P_KH], P[P_EX],
                                                        P[P_KV], P[P_MU], P[P_VREG], P[P_RR], P[P_RI])
    f_ax = 0.0
    if P[P_FACE] != 0.0:
        f_ax = abs(_axial_force(x, xd, P[P_CLAX], P[P_DM], P[P_KCB], P[P_KWS], P[P_KHS], P[P_CAX]))
    if P[P_RUB] != 0.0 and f_ax > 0.0:
        gy, gz, gr, gi, _ = _rub(dy, dz, dvy, dvz, om, omi, ta, tb, x, f_ax, P)
        fy += gy
        fz += gz
        t_rot += gr
        t_race += gi
    by, bz = _ball_force(ry - oy, rz - oz, P[P_KB1], P[P_KB2], vry - voy, vrz - voz, P[P_CB])
    if P[P_DRAG] != 0.0:
        t_race += _hp(omi, math.sqrt(by * by + bz * bz), f_ax + P[P_FAPRE], P)[0]
    if P[P_TW] != 0.0:
        t_race += _worn_drag(omi, P[P_TW], OMEGA_REG_HP, rphi, P[P_TWPHI])
    if P[P_WMU] != 0.0:
        t_race += _worn_fr(omi, math.sqrt(by * by + bz * bz), f_ax + P[P_FAPRE], rphi, P)[0]
    hy, hz = _ribbon_force(oy, oz, voy, voz, P[P_KRIB], P[P_CRIB], P[P_ETA], P[P_VREG])
    if P[P_COUL] != 0.0 and f_ax > 0.0:
        ky, kz = _outer_race_friction(voy, voz, f_ax, P[P_MUD], P[P_VREG])
        hy += ky
        hz += kz
    ci = P[P_CI]
    co = P[P_CO]
    return (fy, fz, t_rot, 0.0, -fy + by - ci * vry, -fz + bz - ci * vrz + P[P_WI], t_race,
            -by + hy - co * voy, -bz + hz - co * voz + P[P_WO])


@_njit
def _radial_jac(dy, dz, dvy, dvz, om, omi, P, J):
    """Derivatives of (fy, fz, t_rot, t_race) of the radial contact w.r.t.
    (dy, dz, dvy, dvz, om, omi) into J[4, 6] (zeros outside contact)."""
    cl = P[P_CL]
    dist = math.sqrt(dy * dy + dz * dz)
    if dist <= cl or dist == 0.0:
        return
    ny = dy / dist
    nz = dz / dist
    delta = dist - cl
    ex = P[P_EX]
    kh = P[P_KH]
    kv = P[P_KV]
    rr = P[P_RR]
    ri = P[P_RI]
    vn = ny * dvy + nz * dvz
    v_s = ny * dvz - nz * dvy + om * rr - omi * ri
    de = delta ** ex
    fn = de * (kh + kv * vn)
    if fn <= 0.0:
        return
    vreg = P[P_VREG]
    m2 = v_s * v_s + vreg * vreg
    m = math.sqrt(m2)
    s = v_s / m
    ds = vreg * vreg / (m2 * m)
    mu = P[P_MU]
    ff = mu * fn * s
    # P = (I - n n^T) / dist
    p00 = (1.0 - ny * ny) / dist
    p01 = -ny * nz / dist
    p11 = (1.0 - nz * nz) / dist
    de1 = ex * delta ** (ex - 1.0) * (kh + kv * vn)
    # 6 inputs: dy, dz, dvy, dvz, om, omi
    for j in range(6):
        dny = 0.0
        dnz = 0.0
        ddelta = 0.0
        dvn = 0.0
        dvs = 0.0
        if j == 0:
            dny, dnz = p00, p01
            ddelta = ny
        elif j == 1:
            dny, dnz = p01, p11
            ddelta = nz
        if j < 2:
            dvn = dny * dvy + dnz * dvz
            dvs = dny * dvz - dnz * dvy
        elif j == 2:
            dvn = ny
            dvs = -nz
        elif j == 3:
            dvn = nz
            dvs = ny
        elif j == 4:
            dvs = rr
        else:
            dvs = -ri
        dfn = de1 * ddelta + de * kv * dvn
        dff = mu * (dfn * s + fn * ds * dvs)
        J[0, j] = -dfn * ny - fn * dny + dff * nz + ff * dnz
        J[1, j] = -dfn * nz - fn * dnz - dff * ny - ff * dny
        J[2, j] = -rr * dff
        J[3, j] = ri * dff


@_njit
def bearing_jacobian(P, q, v, ta, tb, fq, fv, out):
    """out[9, 9] = -(fq dF/dq + fv dF/dv) (Exudyn's jacobianUserFunction of a force on the RHS)."""
    sy, sz, _th, x, ry, rz, rphi, oy, oz = q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8]
    vsy, vsz, om, xd, vry, vrz, omi, voy, voz = v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]
    Jq = np.zeros((9, 9))
    Jv = np.zeros((9, 9))
    dy = sy - ry
    dz = sz - rz
    dvy = vsy - vry
    dvz = vsz - vrz
    # contact forces on the rotor (fy, fz, t_rot, t_race) w.r.t. (dy, dz, dvy, dvz, om, omi, x, xd)
    C = np.zeros((4, 8))
    _radial_jac(dy, dz, dvy, dvz, om, omi, P, C)
    f_ax = 0.0
    dfa_x = 0.0
    dfa_xd = 0.0
    if P[P_FACE] != 0.0:
        fa_signed, dfx, dfxd = _axial_force_d(x, xd, P)
        f_ax = abs(fa_signed)
        sg = 1.0 if fa_signed > 0.0 else -1.0
        dfa_x = sg * dfx
        dfa_xd = sg * dfxd
    if P[P_RUB] != 0.0 and f_ax > 0.0:
        base = _rub_velocity_jac(dy, dz, dvy, dvz, om, omi, ta, tb, x, f_ax, P, C)
        # the contact patch moves with the axial approach a0 = |x| - cl_ax + s (beta dy - alpha dz):
        # central difference in x at fixed f_ax (two quadratures), chained to dy, dz
        sg = 1.0 if x >= 0 else -1.0
        ex = 1e-10
        ra = _rub(dy, dz, dvy, dvz, om, omi, ta, tb, x + ex, f_ax, P)
        rb = _rub(dy, dz, dvy, dvz, om, omi, ta, tb, x - ex, f_ax, P)
        for i in range(4):
            dda0 = (ra[i] - rb[i]) / (2.0 * ex) * sg
            C[i, 6] += dda0 * sg
            C[i, 0] += dda0 * sg * tb
            C[i, 1] -= dda0 * sg * ta
        # f_ax scales the rub linearly
        for i in range(4):
            C[i, 6] += base[i] / f_ax * dfa_x
            C[i, 7] += base[i] / f_ax * dfa_xd
    # map (dy, dz, dvy, dvz, om, omi, x, xd) to local coordinates; rows: fy -> 0, fz -> 1, t_rot -> 2,
    # -fy -> 4, -fz -> 5, t_race -> 6
    for i in range(4):
        row = i if i < 3 else 6
        Jq[row, 0] += C[i, 0]
        Jq[row, 4] -= C[i, 0]
        Jq[row, 1] += C[i, 1]
        Jq[row, 5] -= C[i, 1]
        Jv[row, 0] += C[i, 2]
        Jv[row, 4] -= C[i, 2]
        Jv[row, 1] += C[i, 3]
        Jv[row, 5] -= C[i, 3]
        Jv[row, 2] += C[i, 4]
        Jv[row, 6] += C[i, 5]
        Jq[row, 3] += C[i, 6]
        Jv[row, 3] += C[i, 7]
    for j in range(9):
        Jq[4, j] = -Jq[0, j]
        Jq[5, j] = -Jq[1, j]
        Jv[4, j] = -Jv[0, j]
        Jv[5, j] = -Jv[1, j]
    # balls: b = -k(r) e - c_b ev, e = race - outer
    ey = ry - oy
    ez = rz - oz
    r = math.sqrt(ey * ey + ez * ez)
    kb1 = P[P_KB1]
    kb2 = P[P_KB2]
    cb = P[P_CB]
    k = kb2 * r + kb1
    by = -k * ey - cb * (vry - voy)
    bz = -k * ez - cb * (vrz - voz)
    if r > 0.0:
        byy = -k - kb2 * ey * ey / r
        byz = -kb2 * ey * ez / r
        bzz = -k - kb2 * ez * ez / r
    else:
        byy = -kb1
        byz = 0.0
        bzz = -kb1
    # d(by, bz)/d(ey, ez) and d/d(evy, evz) = -cb I
    Bq = np.array([[byy, byz], [byz, bzz]])
    for i in range(2):
        for j in range(2):
            Jq[4 + i, 4 + j] += Bq[i, j]
            Jq[4 + i, 7 + j] -= Bq[i, j]
            Jq[7 + i, 4 + j] -= Bq[i, j]
            Jq[7 + i, 7 + j] += Bq[i, j]
        Jv[4 + i, 4 + i] -= cb
        Jv[4 + i, 7 + i] += cb
        Jv[7 + i, 4 + i] += cb
        Jv[7 + i, 7 + i] -= cb
    if P[P_TW] != 0.0:
        m2 = omi * omi + P[P_WREG2]
        g, dg = _worn_dev(rphi, P[P_TWPHI])
        Jv[6, 6] -= P[P_TW] * g * P[P_WREG2] / (m2 * math.sqrt(m2))
        Jq[6, 6] -= P[P_TW] * dg * omi / math.sqrt(m2)
    if P[P_DRAG] != 0.0 or P[P_WMU] != 0.0:
        fr = math.sqrt(by * by + bz * bz)
        dT_fr = dT_fa = dT_om = 0.0
        if P[P_DRAG] != 0.0:
            _, dT_fr, dT_fa, dT_om = _hp(omi, fr, f_ax + P[P_FAPRE], P)
        if P[P_WMU] != 0.0:
            # the worn bearing's load-proportional drag: same loads as Harris-Palmgren, plus its growth
            _, wfr, wfa, wom, wphi = _worn_fr(omi, fr, f_ax + P[P_FAPRE], rphi, P)
            dT_fr += wfr
            dT_fa += wfa
            dT_om += wom
            Jq[6, 6] += wphi
        Jv[6, 6] += dT_om
        Jq[6, 3] += dT_fa * dfa_x
        Jv[6, 3] += dT_fa * dfa_xd
        if fr > 0.0:
            gy = dT_fr * by / fr
            gz = dT_fr * bz / fr
            for j in range(2):
                Jq[6, 4 + j] += gy * Bq[0, j] + gz * Bq[1, j]
                Jq[6, 7 + j] -= gy * Bq[0, j] + gz * Bq[1, j]
            Jv[6, 4] += -cb * gy
            Jv[6, 7] += cb * gy
            Jv[6, 5] += -cb * gz
            Jv[6, 8] += cb * gz
    # ribbon on the outer race
    krib = P[P_KRIB]
    crib = P[P_CRIB]
    Jq[7, 7] -= krib
    Jq[8, 8] -= krib
    Jv[7, 7] -= crib
    Jv[8, 8] -= crib
    h = oy * voz - oz * voy
    vr = P[P_VREG]
    den = h * h + vr * vr * (oy * oy + oz * oz)
    if den > 0.0 and P[P_ETA] != 0.0:
        S = math.sqrt(den)
        ke = krib * P[P_ETA] * h / S
        # d(ke)/d(oy, oz, voy, voz)
        dh = (voz, -voy, -oz, oy)
        dd = (2.0 * vr * vr * oy, 2.0 * vr * vr * oz, 0.0, 0.0)
        for j in range(4):
            dden = 2.0 * h * dh[j] + dd[j]
            dke = krib * P[P_ETA] * (dh[j] / S - 0.5 * h * dden / (S * S * S))
            if j < 2:
                Jq[7, 7 + j] += dke * oz
                Jq[8, 7 + j] -= dke * oy
            else:
                Jv[7, 5 + j] += dke * oz
                Jv[8, 5 + j] -= dke * oy
        Jq[7, 8] += ke
        Jq[8, 7] -= ke
    if P[P_COUL] != 0.0 and f_ax > 0.0:
        m2 = voy * voy + voz * voz + vr * vr
        m = math.sqrt(m2)
        s = -P[P_MUD] * f_ax / m
        Jv[7, 7] += s - s * voy * voy / m2
        Jv[7, 8] += -s * voy * voz / m2
        Jv[8, 7] += -s * voz * voy / m2
        Jv[8, 8] += s - s * voz * voz / m2
        # d s / d f_ax = s / f_ax
        Jq[7, 3] += s / f_ax * voy * dfa_x
        Jv[7, 3] += s / f_ax * voy * dfa_xd
        Jq[8, 3] += s / f_ax * voz * dfa_x
        Jv[8, 3] += s / f_ax * voz * dfa_xd
    # race damping
    Jv[4, 4] -= P[P_CI]
    Jv[5, 5] -= P[P_CI]
    Jv[7, 7] -= P[P_CO]
    Jv[8, 8] -= P[P_CO]
    for i in range(9):
        for j in range(9):
            out[i, j] = -(fq * Jq[i, j] + fv * Jv[i, j])
    return out


def bearing_functions(spec: LandingSpec, b: BearingSpec, tilt: list | None = None):
    """(force, jacobian) user functions for an Exudyn ObjectGenericODE2 over BEARING_LOCAL."""
    P = bearing_parameters(spec, b)
    if P[P_RUB] != 0.0 and tilt is None:
        raise ValueError(f"bearing {b.name}: axial rub needs the tilt holder")
    tl = tilt if tilt is not None else [0.0, 0.0]
    rhs = bearing_rhs
    jac = bearing_jacobian
    out = np.zeros((9, 9))
    asarray = np.asarray

    def force(mbs, t, item, q, q_t):
        return list(rhs(P, *q, *q_t, tl[0], tl[1]))

    def jacobian(mbs, t, item, q, q_t, fq, fv):
        return jac(P, asarray(q), asarray(q_t), tl[0], tl[1], fq, fv, out)

    # compile / load from numba's cache now, not inside the timed solve
    z = [0.0] * 9
    force(None, 0.0, 0, z, z)
    jacobian(None, 0.0, 0, z, z, 1.0, 1.0)

    return force, jacobian, P


@_njit
def _normal_forces(P, dy, dz, dvy, dvz):
    out = np.zeros(dy.shape[0])
    for k in range(dy.shape[0]):
        # F_N does not depend on the spins or the friction coefficient (zeros here)
        out[k] = _radial_contact(dy[k], dz[k], dvy[k], dvz[k], 0.0, 0.0, P[P_CL], P[P_KH], P[P_EX], P[P_KV], 0.0,
                                 P[P_VREG], P[P_RR], P[P_RI])[4]
    return out


def contact_normal_forces(spec: LandingSpec, q: np.ndarray, v: np.ndarray) -> list[np.ndarray]:
    """Contact normal force F_N (eq 15) of each bearing at every stored sample: the compiled
    ``user_forces.radial_contact`` law over the samples (the coast-down's decimation reads it at
    the full output rate, where a Python call per sample would cost ~5 % of the solve)."""
    out = []
    for b in spec.bearings:
        s, r = b.i_station, b.i_race
        out.append(_normal_forces(bearing_parameters(spec, b), q[:, s] - q[:, r], q[:, s + 1] - q[:, r + 1],
                                  v[:, s] - v[:, r], v[:, s + 1] - v[:, r + 1]))
    return out


# ---------------------------------------------------------------------------------------------
# All bearings (+ the spin/axial rotor loads) in one connector: one Python call per residual.

(R_ON, R_CLAX, R_DM, R_KCB, R_KWS, R_KHS, R_CAX, R_CW1, R_CW2, R_WIND, R_DRIVE, R_GAIN, R_OMEGA0, R_KAXAMB,
 R_CAXAMB, R_SIZE) = range(16)


def rotor_load_parameters(spec: LandingSpec, include: bool) -> np.ndarray:
    """Spin and axial loads of forces.rotor_forces (windage, drive, axial contact, axial AMB) as a
    float vector; ``include`` False leaves them to a separate rotor-loads connector."""
    sc = spec.scenario
    a = sc.axial
    R = np.zeros(R_SIZE)
    R[R_ON] = 1.0 if include else 0.0
    R[R_CLAX], R[R_DM], R[R_KCB], R[R_KWS], R[R_KHS], R[R_CAX] = a.cl_ax, a.delta_m, a.k_cb, a.k_ws, a.k_h, a.c_ax
    rl = spec.rotor_laws
    R[R_CW1], R[R_CW2] = rl.c_w1, rl.c_w2
    R[R_WIND] = 1.0 if rl.windage else 0.0
    R[R_DRIVE] = 1.0 if rl.constant_drive else 0.0
    R[R_GAIN], R[R_OMEGA0] = rl.drive_gain, rl.omega0
    R[R_KAXAMB], R[R_CAXAMB] = sc.amb.axial_stiffness, sc.amb.axial_damping
    return R


@_njit
def _rotor_loads(R, om, x, xd, thrust, amb_axial):
    """Spin and axial rotor loads with their derivatives, one pass over the same branches:
    (spin torque, d torque / d omega, axial force incl. ``thrust``, -d F_ax/dx, -d F_ax/dxd)."""
    tq = 0.0
    dt = 0.0
    if R[R_WIND] != 0.0:
        tq += _windage(om, R[R_CW1], R[R_CW2])
        dt += _windage_d(om, R[R_CW1], R[R_CW2])
    if R[R_DRIVE] != 0.0:
        tq += _drive(om, R[R_GAIN], R[R_OMEGA0])
        dt -= R[R_GAIN]
    f = _axial_force(x, xd, R[R_CLAX], R[R_DM], R[R_KCB], R[R_KWS], R[R_KHS], R[R_CAX])
    fa = thrust + f
    kx = 0.0
    cx = 0.0
    if f != 0.0:
        if abs(x) - R[R_CLAX] <= R[R_DM]:
            kx = 1.0 / (1.0 / R[R_KCB] + 1.0 / R[R_KWS])
        else:
            kx = 1.0 / (1.0 / R[R_KCB] + 1.0 / R[R_KHS])
        cx = R[R_CAX]
    if amb_axial:
        fa += _amb(x, xd, -thrust, R[R_KAXAMB], R[R_CAXAMB])
        kx += R[R_KAXAMB]
        cx += R[R_CAXAMB]
    return tq, dt, fa, kx, cx


@_njit
def landing_rhs(PB, IDX, R, q, v, tilts, thrust, amb_axial, out):
    """Generalized forces of all bearings (+ spin/axial rotor loads when R[R_ON]) on the merged
    connector's local coordinates. IDX[b] = local indices of BEARING_LOCAL of bearing b."""
    for i in range(out.shape[0]):
        out[i] = 0.0
    for b in range(PB.shape[0]):
        ix = IDX[b]
        r = bearing_rhs(PB[b], q[ix[0]], q[ix[1]], q[ix[2]], q[ix[3]], q[ix[4]], q[ix[5]], q[ix[6]], q[ix[7]],
                        q[ix[8]], v[ix[0]], v[ix[1]], v[ix[2]], v[ix[3]], v[ix[4]], v[ix[5]], v[ix[6]], v[ix[7]],
                        v[ix[8]], tilts[b, 0], tilts[b, 1])
        for k in range(9):
            out[ix[k]] += r[k]
    if R[R_ON] != 0.0:
        i_th = IDX[0, 2]
        i_ax = IDX[0, 3]
        tq, _, fa, _, _ = _rotor_loads(R, v[i_th], q[i_ax], v[i_ax], thrust, amb_axial)
        out[i_th] += tq
        out[i_ax] += fa
    return out


@_njit
def landing_jacobian(PB, IDX, R, q, v, tilts, amb_axial, fq, fv, out):
    """out = -(fq dF/dq + fv dF/dv) of landing_rhs."""
    out[:, :] = 0.0
    jb = np.zeros((9, 9))
    qb = np.zeros(9)
    vb = np.zeros(9)
    for b in range(PB.shape[0]):
        ix = IDX[b]
        for k in range(9):
            qb[k] = q[ix[k]]
            vb[k] = v[ix[k]]
        bearing_jacobian(PB[b], qb, vb, tilts[b, 0], tilts[b, 1], fq, fv, jb)
        for i in range(9):
            for j in range(9):
                out[ix[i], ix[j]] += jb[i, j]
    if R[R_ON] != 0.0:
        i_th = IDX[0, 2]
        i_ax = IDX[0, 3]
        _, dt, _, kx, cx = _rotor_loads(R, v[i_th], q[i_ax], v[i_ax], 0.0, amb_axial)
        out[i_th, i_th] -= fv * dt
        out[i_ax, i_ax] += fq * kx + fv * cx
    return out


def direct(dispatcher, *args):
    """The compiled function of a numba dispatcher for exactly the types of ``args`` (compiled or
    loaded from the cache now), callable without the dispatcher's per-call type resolution; the
    dispatcher itself when numba does not expose it. Same machine code, so the same results."""
    dispatcher(*args)
    try:
        sig = tuple(dispatcher.typeof_pyval(a) for a in args)
        return dispatcher.overloads[sig].entry_point
    except (AttributeError, KeyError, TypeError):
        return dispatcher


@_njit
def update_tilts(q, TA, TB, rows, n_lat, tilts):
    """tilts[rows[k]] = (TA[k] . q[:n_lat], TB[k] . q[:n_lat]): the rotor tilt at the axial faces of
    the rubbing bearings, once per step from the pre-step (np.dot is BLAS's ddot here as in numpy,
    so the values are the bits of ``float(row @ q[:n_lat])``)."""
    ql = q[:n_lat]
    for k in range(rows.shape[0]):
        tilts[rows[k], 0] = np.dot(TA[k], ql)
        tilts[rows[k], 1] = np.dot(TB[k], ql)


def landing_functions(spec: LandingSpec, local_index: list, tilts: np.ndarray, include_rotor_loads: bool):
    """(force, jacobian) user functions of one ObjectGenericODE2 over all bearings.

    local_index[b]: the 9 local indices (BEARING_LOCAL order) of bearing b in the connector's
    coordinates; tilts: (n_bearings, 2) array that the pre-step updates in place (rotor tilt at
    the axial face; zeros for bearings without axial rub); include_rotor_loads: also apply the
    spin and axial rotor loads of forces.rotor_forces (only valid when those need no lateral
    coordinates)."""
    PB = np.array([bearing_parameters(spec, b) for b in spec.bearings])
    IDX = np.array(local_index, dtype=np.int64)
    R = rotor_load_parameters(spec, include_rotor_loads)
    n = int(IDX.max()) + 1
    out = np.zeros(n)
    jout = np.zeros((n, n))
    amb = spec.scenario.amb
    t_drop, drop_axial = amb.t_drop, amb.drop_axial
    thrust = spec.thrust

    # the compiled entry points for exactly these argument types (numba's dispatcher would type
    # every argument on every call: ~0.2 us of the ~1 us kernel call); q, q_t arrive from Exudyn
    # as lists; the force goes back as the reused array (Exudyn copies it on return)
    z = np.zeros(n)
    rhs = direct(landing_rhs, PB, IDX, R, z, z, tilts, 0.0, True, out)
    jac = direct(landing_jacobian, PB, IDX, R, z, z, tilts, True, 1.0, 1.0, jout)
    fromiter, f64 = np.fromiter, np.float64

    def force(mbs, t, item, q, q_t):
        return rhs(PB, IDX, R, fromiter(q, f64, n), fromiter(q_t, f64, n), tilts, thrust(t),
                   t < t_drop or not drop_axial, out)

    def jacobian(mbs, t, item, q, q_t, fq, fv):
        return jac(PB, IDX, R, fromiter(q, f64, n), fromiter(q_t, f64, n), tilts, t < t_drop or not drop_axial,
                   fq, fv, jout)

    z = [0.0] * n
    force(None, 0.0, 0, z, z)
    jacobian(None, 0.0, 0, z, z, 1.0, 1.0)
    return force, jacobian


def system_forces(spec: LandingSpec):
    """The whole landing right-hand side f(t, q, v) of M q'' = f in the spec's coordinates, built
    from the same compiled kernel (a lean RHS for scipy's LSODA in the speed benchmark; the
    tilt at the axial face is evaluated from the current state). Returns (f, jac) with
    jac(t, q, v) -> (df/dq, df/dv) (the tilt's own dependence on q is left out of the Jacobian).
    ``tests/test_bearing_jacobian.py`` checks f against rotorlanding.reference.generalized_forces."""
    from .forces import rotor_forces, rotor_loads_need_lateral

    sc = spec.scenario
    nl = spec.n_lat
    n = spec.n
    need_lateral = rotor_loads_need_lateral(spec, False)
    IDX = np.array([[b.i_station, b.i_station + 1, spec.i_theta, spec.i_axial, b.i_race, b.i_race + 1, b.i_race + 2,
                     b.i_race + 3, b.i_race + 4] for b in spec.bearings], dtype=np.int64)
    PB = np.array([bearing_parameters(spec, b) for b in spec.bearings])
    R = rotor_load_parameters(spec, not need_lateral)
    rub = [bool(P[P_RUB]) for P in PB]
    TA = np.array([b.tilt_alpha for b in spec.bearings])
    TB = np.array([b.tilt_beta for b in spec.bearings])
    tilts = np.zeros((len(spec.bearings), 2))
    K, C, G, fg = spec.K, spec.C, spec.G, spec.f_gravity
    gyro = spec.rotor_laws.gyroscopic
    frot = rotor_forces(spec, gyroscopic_in_user_function=False) if need_lateral else None
    rot_idx = list(range(nl)) + [spec.i_theta, spec.i_axial]
    amb = sc.amb
    out = np.zeros(n)
    jout = np.zeros((n, n))

    def f(t, q, v):
        ql = q[:nl]
        vl = v[:nl]
        for k in range(len(rub)):
            if rub[k]:
                tilts[k, 0] = TA[k] @ ql
                tilts[k, 1] = TB[k] @ ql
        landing_rhs(PB, IDX, R, q, v, tilts, spec.thrust(t), t < amb.t_drop or not amb.drop_axial, out)
        res = out.copy()
        lin = fg - K @ ql - C @ vl
        if gyro:
            lin -= v[spec.i_theta] * (G @ vl)
        res[:nl] += lin
        if frot is not None:
            res[rot_idx] += frot(t, q[rot_idx].tolist(), v[rot_idx].tolist())
        return res

    def jac(t, q, v):
        ql = q[:nl]
        for k in range(len(rub)):
            if rub[k]:
                tilts[k, 0] = TA[k] @ ql
                tilts[k, 1] = TB[k] @ ql
        amb_ax = t < amb.t_drop or not amb.drop_axial
        Jq = -landing_jacobian(PB, IDX, R, q, v, tilts, amb_ax, 1.0, 0.0, jout).copy()
        Jv = -landing_jacobian(PB, IDX, R, q, v, tilts, amb_ax, 0.0, 1.0, jout).copy()
        Jq[:nl, :nl] -= K
        Jv[:nl, :nl] -= C
        if gyro:
            Jv[:nl, :nl] -= v[spec.i_theta] * G
            Jv[:nl, spec.i_theta] -= G @ v[:nl]
        if frot is not None:
            from .forces import rotor_loads_jacobian

            jr = rotor_loads_jacobian(spec, gyroscopic_in_user_function=False)
            Jq[np.ix_(rot_idx, rot_idx)] -= jr(t, q[rot_idx].tolist(), v[rot_idx].tolist(), 1.0, 0.0)
            Jv[np.ix_(rot_idx, rot_idx)] -= jr(t, q[rot_idx].tolist(), v[rot_idx].tolist(), 0.0, 1.0)
        return Jq, Jv

    return f, jac


@_njit
def rub_series(dy, dz, dvy, dvz, om, wi, q, ta, tb, n_lat, n_ax, x, cl_ax, mu_ax, v_reg, r1, r2, gy, gz, p):
    """The axial rub's post-processing series (mechanisms._post_rub) over all output samples: the
    user_forces law compiled as in the solver, the tilt per sample by BLAS's ddot as in numpy
    (``float(tilt @ q[i, :n_lat])``), so the series equal the plain-Python loop's."""
    for i in range(dy.shape[0]):
        if n_ax[i] > 0:
            ql = q[i, :n_lat]
            r = _axial_rub_q(dy[i], dz[i], dvy[i], dvz[i], om[i], wi[i], np.dot(ta, ql), np.dot(tb, ql),
                             abs(x[i]) - cl_ax, n_ax[i], 1.0 if x[i] >= 0 else -1.0, mu_ax, v_reg, r1, r2, False)
            gy[i], gz[i], p[i] = r[0], r[1], r[4]


# --- post-processing series: the laws over every output sample, compiled as in the solver -------
# (mechanisms' post hooks; the plain per-sample Python loops took about 0.2 s of a 1 s landing's
# 0.3 s of post-processing; tests/test_post_series.py checks each against the plain loop)

@_njit
def radial_series(dy, dz, dvy, dvz, om, wi, cl, kh, ex, kv, mu, vreg, rr, ri, out):
    """Radial contact (eqs 10-17) per sample into ``out`` (n x 8): F_y, F_z, F_N, delta, v_s on the
    rotor, friction power, Hunt-Crossley damping power, Hertz energy."""
    for i in range(dy.shape[0]):
        r = _radial_contact(dy[i], dz[i], dvy[i], dvz[i], om[i], wi[i], cl, kh, ex, kv, mu, vreg, rr, ri)
        out[i, 0], out[i, 1], out[i, 2], out[i, 4], out[i, 5] = r[0], r[1], r[4], r[6], r[7]
        delta = r[5]
        if delta > 0:
            out[i, 3] = delta
            ddot = (dy[i] * dvy[i] + dz[i] * dvz[i]) / math.hypot(dy[i], dz[i])
            out[i, 6] = (r[4] - kh * delta ** ex) * ddot
            out[i, 7] = kh * delta ** (ex + 1) / (ex + 1)


@_njit
def ball_series(ey, ez, evy, evz, kb1, kb2, cb, out):
    """Ball set (eq 22) per sample into ``out`` (n x 3): force on the inner race y, z, elastic energy."""
    for i in range(ey.shape[0]):
        f = _ball_force(ey[i], ez[i], kb1, kb2, evy[i], evz[i], cb)
        out[i, 0], out[i, 1] = f[0], f[1]
        rr = math.hypot(ey[i], ez[i])
        out[i, 2] = kb1 * rr * rr / 2 + kb2 * rr ** 3 / 3


@_njit
def drag_series(wi, by, bz, n_ax, preload, hp, out):
    """Harris-Palmgren drag torque (eqs 23-27) per sample into ``out``: radial load = ball force,
    axial = face load + preload; ``hp`` the law's constants tuple."""
    for i in range(wi.shape[0]):
        out[i] = _hp_law(wi[i], math.hypot(by[i], bz[i]), n_ax[i] + preload, hp)[0]


@_njit
def ribbon_series(oy, oz, ovy, ovz, krib, crib, eta, vreg, out):
    """Ribbon (eqs 28-29) per sample into ``out`` (n x 4): force on the outer race y, z, elastic
    energy, cross-coupled (hysteretic) power."""
    for i in range(oy.shape[0]):
        f = _ribbon_force(oy[i], oz[i], ovy[i], ovz[i], krib, crib, eta, vreg)
        out[i, 0], out[i, 1] = f[0], f[1]
        out[i, 2] = 0.5 * krib * (oy[i] * oy[i] + oz[i] * oz[i])
        ccy, ccz = f[0] + crib * ovy[i] + krib * oy[i], f[1] + crib * ovz[i] + krib * oz[i]
        out[i, 3] = -(ccy * ovy[i] + ccz * ovz[i])


@_njit
def blok_sleeve_series(fn, om, wi, r_sleeve, r_race, r_equiv, width, e_star, k, chi, out):
    """Blok's sleeve share of the sleeve-bore contact heat per sample (0.5 where there is no contact)."""
    for i in range(fn.shape[0]):
        b = _line_contact(fn[i], width, r_equiv, e_star)[1] if fn[i] > 0.0 else 0.0
        out[i] = _blok(om[i] * r_sleeve, wi[i] * r_race, b, k, chi, k, chi) if b > 0.0 else 0.5


@_njit
def blok_face_series(om, wi, r_m, half, k, chi, out):
    """Blok's sleeve share of the face-rub heat per sample (mean face radius, half the annulus width)."""
    for i in range(om.shape[0]):
        out[i] = _blok(abs(om[i]) * r_m, abs(wi[i]) * r_m, half, k, chi, k, chi)
